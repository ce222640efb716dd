// RemapController: only the newest request's map is delivered, a stale run is cancelled, the
// delivered map is the batch map, and moving the time forward continues the map exactly.

#include <QSignalSpy>
#include <QtTest>
#include <random>

#include "remap_controller.h"
#include "sonargrid/io/sglog.h"

using namespace sg;
using namespace sg::ui;

namespace {

// A log large enough that a run takes far longer than issuing the next request: 8000 scans of a
// 16-sonar ring, 128 000 readings, on a 30 m walk (fixed seed).
std::shared_ptr<const Dataset> largeLog() {
  auto data = std::make_shared<Dataset>();
  data->ring = SonarRing::pioneer3dx();
  std::mt19937 random(1990);
  std::uniform_real_distribution<double> range(0.3, 4.8);
  for (int i = 0; i < 8000; ++i) {
    Scan s;
    s.time = 0.1 * i;
    s.odometry = Pose2D(0.00375 * i, 2.0 * std::sin(0.002 * i), 0.001 * i);
    for (std::uint16_t k = 0; k < 16; ++k) s.readings.push_back({k, range(random), s.time});
    data->scans.push_back(std::move(s));
  }
  return data;
}

MapperSettings settingsFor(const std::string& model, const std::string& rule) {
  MapperSettings s;
  s.model = model;
  s.rule = rule;
  s.parameters = defaultParameters(model, rule);
  return s;
}

OccupancyMap batchMap(const Dataset& data, const MapperSettings& s, double until, double cell) {
  Mapper m(data.ring, data.fittingGrid(s.pose, cell), s);
  m.mapDataset(data, until);
  return m.snapshot();
}

std::shared_ptr<const Dataset> roomLog() {
  return std::make_shared<const Dataset>(readSglog(SONARGRID_DATASETS "/room/room.sglog"));
}

}  // namespace

class TestRemapController : public QObject {
  Q_OBJECT

 private slots:
  void previewThenFullMap() {
    // setPreview(2, 0): every settings change (after a first full map) is first mapped on cells
    // twice as large and delivered as previewed(), then in full as mapped(), same generation, in
    // that order. Each is the batch map of its cell size. The first map of a log and a change of
    // time are never previewed; previews off (factor 1) give mapped() alone.
    const auto data = roomLog();
    RemapController remap;
    remap.setPreview(2, 0.0);
    QCOMPARE(remap.previewFactor(), 2);
    QSignalSpy previewed(&remap, &RemapController::previewed);
    QSignalSpy mapped(&remap, &RemapController::mapped);
    std::vector<char> order;  // 'p' or 'm', as delivered
    connect(&remap, &RemapController::previewed, this, [&] { order.push_back('p'); });
    connect(&remap, &RemapController::mapped, this, [&] { order.push_back('m'); });
    const MapperSettings first = settingsFor("hpf", "bayes");
    remap.start(data, 0.05, first, std::numeric_limits<double>::infinity());
    QVERIFY(mapped.wait(60000));
    QCOMPARE(previewed.count(), 0);

    const MapperSettings second = settingsFor("parameterized", "bayes");
    remap.setSettings(second);
    QTRY_COMPARE_WITH_TIMEOUT(mapped.count(), 2, 60000);
    QCOMPARE(previewed.count(), 1);
    QCOMPARE(order, (std::vector<char>{'m', 'p', 'm'}));
    QCOMPARE(previewed.at(0).at(2).value<quint64>(), mapped.at(1).at(2).value<quint64>());
    const auto preview = previewed.at(0).at(0).value<std::shared_ptr<const OccupancyMap>>();
    const auto full = mapped.at(1).at(0).value<std::shared_ptr<const OccupancyMap>>();
    QCOMPARE(preview->spec.cellSize, 0.1);
    QCOMPARE(full->spec.cellSize, 0.05);
    const double end = std::numeric_limits<double>::infinity();
    QVERIFY(preview->level == batchMap(*data, second, end, 0.1).level);
    QVERIFY(full->level == batchMap(*data, second, end, 0.05).level);

    // A change of time: no preview.
    remap.setUntil(30.0);
    QTRY_COMPARE_WITH_TIMEOUT(mapped.count(), 3, 60000);
    QCOMPARE(previewed.count(), 1);

    // Off again: settings changes map once.
    remap.setPreview(1, 0.0);
    remap.setSettings(first);
    QTRY_COMPARE_WITH_TIMEOUT(mapped.count(), 4, 60000);
    QTest::qWait(50);
    QCOMPARE(previewed.count(), 1);
  }

  void previewOnlyForSlowLogs() {
    // The window previews only when the last full re-map took longer than `aboveMs`: with an
    // hour's threshold, never.
    const auto data = roomLog();
    RemapController remap;
    remap.setPreview(2, 3.6e6);
    QSignalSpy previewed(&remap, &RemapController::previewed);
    QSignalSpy mapped(&remap, &RemapController::mapped);
    remap.start(data, 0.05, settingsFor("hpf", "bayes"), std::numeric_limits<double>::infinity());
    QVERIFY(mapped.wait(60000));
    remap.setSettings(settingsFor("murphy", "bayes-recursive"));
    QTRY_COMPARE_WITH_TIMEOUT(mapped.count(), 2, 60000);
    QCOMPARE(previewed.count(), 0);
  }

  void staleRunIsCancelled() {
    const auto data = largeLog();
    RemapController remap;
    QSignalSpy mapped(&remap, &RemapController::mapped);
    QSignalSpy cancelled(&remap, &RemapController::cancelled);
    QSignalSpy busy(&remap, &RemapController::busyChanged);
    const MapperSettings first = settingsFor("hpf", "addition");
    MapperSettings second = settingsFor("hpf", "bayes");
    remap.start(data, 0.05, first, std::numeric_limits<double>::infinity());  // generation 1
    remap.setSettings(second);                                                // generation 2
    QCOMPARE(remap.latestGeneration(), quint64(2));
    QVERIFY(remap.busy());
    QVERIFY(mapped.wait(60000));
    QTRY_COMPARE(busy.count(), 2);  // busy once, idle once: the runs went one after the other
    QCOMPARE(busy.at(0).at(0).toBool(), true);
    QCOMPARE(busy.at(1).at(0).toBool(), false);

    QCOMPARE(mapped.count(), 1);
    QCOMPARE(mapped.at(0).at(2).value<quint64>(), quint64(2));
    QCOMPARE(cancelled.count(), 1);
    QCOMPARE(cancelled.at(0).at(0).value<quint64>(), quint64(1));
    // 128 000 readings cannot be mapped in the microseconds between the two requests: the stale
    // run was stopped part-way, not merely discarded at the end.
    QVERIFY(cancelled.at(0).at(1).toBool());

    const auto map = mapped.at(0).at(0).value<std::shared_ptr<const OccupancyMap>>();
    QVERIFY(map);
    QCOMPARE(map->rule, std::string("bayes"));
    const OccupancyMap expected =
        batchMap(*data, second, std::numeric_limits<double>::infinity(), 0.05);
    QVERIFY(map->level == expected.level);
    QVERIFY(map->probability == expected.probability);
  }

  void forwardInTimeContinuesTheMap() {
    const auto data = roomLog();
    const MapperSettings s = settingsFor("himm", "himm");
    RemapController remap;
    QSignalSpy mapped(&remap, &RemapController::mapped);
    remap.start(data, 0.05, s, 20.0);
    QVERIFY(mapped.wait(30000));
    QCOMPARE(mapped.last().at(3).toBool(), false);  // the first run starts from nothing
    remap.setUntil(35.05);                          // between two scans' readings
    QVERIFY(mapped.wait(30000));
    QCOMPARE(mapped.last().at(3).toBool(), true);  // continued from t = 20
    const auto map = mapped.last().at(0).value<std::shared_ptr<const OccupancyMap>>();
    const OccupancyMap expected = batchMap(*data, s, 35.05, 0.05);
    QVERIFY(map->level == expected.level);
    QVERIFY(map->native == expected.native);
    // ...and differs from the map at 20 s, so the comparison means something.
    QVERIFY(map->level != batchMap(*data, s, 20.0, 0.05).level);

    remap.setUntil(10.0);  // backwards: starts over
    QVERIFY(mapped.wait(30000));
    QCOMPARE(mapped.last().at(3).toBool(), false);
    QVERIFY(mapped.last().at(0).value<std::shared_ptr<const OccupancyMap>>()->level ==
            batchMap(*data, s, 10.0, 0.05).level);
  }

  void failureIsReported() {
    // A log without true poses cannot be mapped with them.
    auto data = std::make_shared<Dataset>();
    data->ring = SonarRing::pioneer3dx();
    Scan scan;
    scan.readings = {{0, 1.0, 0.0}};
    data->scans = {scan};
    MapperSettings s = settingsFor("hpf", "addition");
    s.pose = PoseSource::Truth;
    RemapController remap;
    QSignalSpy failed(&remap, &RemapController::failed);
    QSignalSpy mapped(&remap, &RemapController::mapped);
    remap.start(data, 0.05, s, std::numeric_limits<double>::infinity());
    QVERIFY(failed.wait(10000));
    QVERIFY(failed.at(0).at(0).toString().contains("true pose"));
    QCOMPARE(mapped.count(), 0);
  }
};

QTEST_MAIN(TestRemapController)
#include "tst_remap_controller.moc"
