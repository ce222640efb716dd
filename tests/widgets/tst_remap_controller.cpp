// SPDX-License-Identifier: GPL-3.0-or-later
// RemapController: only the newest request's map is delivered, a stale run is cancelled, the
// delivered map is the batch map, and moving the time forward continues the map exactly.

#include <QSignalSpy>
#include <QtTest>
#include <random>

#include "remap_controller.h"
#include "sonargrid/engine/scan_source.h"
#include "sonargrid/forward/forward_em.h"
#include "sonargrid/io/log_reader.h"
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

// A robot driving 40 m along a wavy line, 2000 scans of 16 random ranges (fixed seed): the second
// half takes it past where the first half's grid (with its slack) ends.
Dataset walkLog() {
  Dataset d;
  d.name = "walk";
  d.ring = SonarRing::pioneer3dx();
  std::mt19937 random(2000);
  std::uniform_real_distribution<double> range(0.3, 4.8);
  for (int i = 0; i < 2000; ++i) {
    Scan s;
    s.time = 0.1 * i;
    s.odometry = Pose2D(0.02 * i, 2.0 * std::sin(0.002 * i), 0.001 * i);
    for (std::uint16_t k = 0; k < 16; ++k)
      s.readings.push_back({k, range(random), s.time + 0.001 * k});
    d.scans.push_back(std::move(s));
  }
  return d;
}

// What a batch run of the scans [0, count) maps on the limits `spec`.
OccupancyMap batchOn(const Dataset& data, std::size_t count, const MapperSettings& s,
                     const GridSpec& spec) {
  Dataset part = data;
  part.scans.resize(count);
  Mapper m(data.ring, spec, s);
  m.mapDataset(part);
  return m.snapshot();
}

bool sameLayers(const OccupancyMap& a, const OccupancyMap& b) {
  return a.spec == b.spec && a.level == b.level && a.filled == b.filled &&
         a.observed == b.observed && a.probability.identical(b.probability) &&
         a.native.identical(b.native) && a.evidence.identical(b.evidence);
}

std::vector<Scan> scansOf(const Dataset& d, std::size_t from, std::size_t to) {
  return std::vector<Scan>(d.scans.begin() + static_cast<std::ptrdiff_t>(from),
                           d.scans.begin() + static_cast<std::ptrdiff_t>(to));
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

  void previewThinsTheLogToItsBudget() {
    // With a time budget, a preview maps one scan in `stride` (RemapController::previewStride):
    // with no budget every scan; with a budget far below any map's cost the largest stride, 64;
    // with a budget of an hour, 1. The preview is the batch map, at 10 cm, of the log with only
    // scans 0, 64, 128, ... (on the whole log's fitting grid: the view keeps its ground), and the
    // full map that follows is the whole log's at 5 cm.
    const auto data = roomLog();
    RemapController remap;
    remap.setPreview(2, 0.0);
    QCOMPARE(remap.previewStride(), 1);  // no budget
    QSignalSpy previewed(&remap, &RemapController::previewed);
    QSignalSpy mapped(&remap, &RemapController::mapped);
    remap.start(data, 0.05, settingsFor("hpf", "bayes"), std::numeric_limits<double>::infinity());
    QVERIFY(mapped.wait(60000));
    remap.setPreviewBudget(1e-9);
    QCOMPARE(remap.previewStride(), RemapController::kMaxPreviewStride);
    remap.setPreviewBudget(3.6e6);
    QCOMPARE(remap.previewStride(), 1);
    remap.setPreviewBudget(1e-9);

    const MapperSettings second = settingsFor("parameterized", "bayes");
    remap.setSettings(second);
    QTRY_COMPARE_WITH_TIMEOUT(mapped.count(), 2, 60000);
    QCOMPARE(previewed.count(), 1);
    QCOMPARE(previewed.at(0).at(3).toInt(), 64);
    Dataset thin;
    thin.ring = data->ring;
    for (std::size_t i = 0; i < data->scans.size(); i += 64) thin.scans.push_back(data->scans[i]);
    QVERIFY(thin.scans.size() >= 2 && thin.scans.size() < data->scans.size() / 32);
    Mapper coarse(data->ring, data->fittingGrid(second.pose, 0.1), second);
    coarse.mapDataset(thin);
    const auto preview = previewed.at(0).at(0).value<std::shared_ptr<const OccupancyMap>>();
    QVERIFY(preview->spec == coarse.grid());
    QVERIFY(preview->level == coarse.snapshot().level);
    const double end = std::numeric_limits<double>::infinity();
    QVERIFY(preview->level != batchMap(*data, second, end, 0.1).level);  // thinned, not whole
    const auto full = mapped.at(1).at(0).value<std::shared_ptr<const OccupancyMap>>();
    QVERIFY(full->level == batchMap(*data, second, end, 0.05).level);
  }

  void theEngineReachesEveryRun() {
    // setPrecision(): every run maps with that engine whatever the settings say, and a change
    // re-maps: the fast map is the batch map under Precision::Fast (a cone model's Bayes cells
    // in four bytes: docs/models.md), the exact one the batch map under Exact.
    const auto data = roomLog();
    RemapController remap;
    QSignalSpy mapped(&remap, &RemapController::mapped);
    MapperSettings s = settingsFor("murphy", "bayes-recursive");
    remap.start(data, 0.05, s, std::numeric_limits<double>::infinity());
    QVERIFY(mapped.wait(60000));
    const auto exact = mapped.at(0).at(0).value<std::shared_ptr<const OccupancyMap>>();
    remap.setPrecision(Precision::Fast);
    QTRY_COMPARE_WITH_TIMEOUT(mapped.count(), 2, 60000);
    const auto fast = mapped.at(1).at(0).value<std::shared_ptr<const OccupancyMap>>();
    s.precision = Precision::Fast;
    const double end = std::numeric_limits<double>::infinity();
    QVERIFY(fast->probability == batchMap(*data, s, end, 0.05).probability);
    s.precision = Precision::Exact;
    QVERIFY(exact->probability == batchMap(*data, s, end, 0.05).probability);
    QVERIFY(fast->probability != exact->probability);  // four bytes, not eight
    remap.setSettings(s);                              // says Exact: the controller's engine wins
    QTRY_COMPARE_WITH_TIMEOUT(mapped.count(), 3, 60000);
    QCOMPARE(remap.settings().precision, Precision::Fast);
    QVERIFY(remap.mapsWith(s));  // what the window asks before it re-maps (onSettingsChanged)
    // A pair whose cells are the same under both engines maps with Exact, and a change of engine
    // does not re-map it.
    const MapperSettings himm = settingsFor("himm", "himm");
    remap.setSettings(himm);
    QTRY_COMPARE_WITH_TIMEOUT(mapped.count(), 4, 60000);
    QCOMPARE(remap.settings().precision, Precision::Exact);
    QSignalSpy started(&remap, &RemapController::started);
    remap.setPrecision(Precision::Exact);
    remap.setPrecision(Precision::Fast);
    QTest::qWait(100);
    QCOMPARE(started.count(), 0);
    QVERIFY(remap.mapsWith(himm));
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

  void liveAppendsEqualTheBatchMap() {
    // A live log: the first half, then ten batches of 100 scans, each followed by
    // scansAppended() and its map. Every append is delivered as a continuation (no re-map), and
    // each equals, in every layer, the batch map of the scans received so far on its limits; the
    // grid grew on the way. A change of settings then re-maps everything received, on the same
    // limits, and the next append continues it.
    const Dataset d = walkLog();
    auto source = std::make_shared<ScanSource>(d.name, d.ring);
    source->append(scansOf(d, 0, 1000));
    const MapperSettings first = settingsFor("hpf", "addition");
    RemapController remap;
    QSignalSpy mapped(&remap, &RemapController::mapped);
    QSignalSpy cancelled(&remap, &RemapController::cancelled);
    remap.startLive(source, 0.05, first);
    QVERIFY(mapped.wait(60000));
    QCOMPARE(mapped.last().at(3).toBool(), false);
    const auto firstMap = mapped.last().at(0).value<std::shared_ptr<const OccupancyMap>>();
    QVERIFY(sameLayers(*firstMap, batchOn(d, 1000, first, firstMap->spec)));

    for (std::size_t b = 0; b < 10; ++b) {
      const std::size_t end = 1100 + 100 * b;
      source->append(scansOf(d, end - 100, end));
      remap.scansAppended();
      QTRY_COMPARE_WITH_TIMEOUT(mapped.count(), static_cast<int>(b) + 2, 60000);
      QCOMPARE(mapped.last().at(3).toBool(), true);
      const auto map = mapped.last().at(0).value<std::shared_ptr<const OccupancyMap>>();
      QVERIFY2(sameLayers(*map, batchOn(d, end, first, map->spec)), qPrintable(QString::number(b)));
    }
    const auto appended = mapped.last().at(0).value<std::shared_ptr<const OccupancyMap>>();
    QVERIFY(appended->spec != firstMap->spec);  // it had to grow
    QCOMPARE(cancelled.count(), 0);

    const MapperSettings second = settingsFor("hpf", "bayes");  // same model, same reach
    remap.setSettings(second);
    QTRY_COMPARE_WITH_TIMEOUT(mapped.count(), 12, 60000);
    QCOMPARE(mapped.last().at(3).toBool(), false);
    const auto remapped = mapped.last().at(0).value<std::shared_ptr<const OccupancyMap>>();
    QCOMPARE(remapped->spec, appended->spec);  // the live view keeps its ground
    QCOMPARE(remapped->rule, std::string("bayes"));
    QVERIFY(sameLayers(*remapped, batchOn(d, 2000, second, remapped->spec)));

    source->append(scansOf(d, 2000, 2000));  // nothing
    remap.scansAppended();
    QTRY_COMPARE_WITH_TIMEOUT(mapped.count(), 13, 60000);
    QCOMPARE(mapped.last().at(3).toBool(), true);
    QVERIFY(
        sameLayers(*mapped.last().at(0).value<std::shared_ptr<const OccupancyMap>>(), *remapped));
  }

  void liveAppendsWhileBusyAreCoalesced() {
    // Appends that arrive while a run is under way join one queued run: nothing is cancelled,
    // the maps arrive in order and the last holds every scan. (The link appends from this thread
    // here; the source itself is safe to append to from another: tst_scan_source.)
    const Dataset d = walkLog();
    auto source = std::make_shared<ScanSource>(d.name, d.ring);
    source->append(scansOf(d, 0, 200));
    const MapperSettings s = settingsFor("konolige", "logodds");
    RemapController remap;
    QSignalSpy mapped(&remap, &RemapController::mapped);
    QSignalSpy cancelled(&remap, &RemapController::cancelled);
    remap.startLive(source, 0.05, s);
    for (std::size_t k = 200; k < 2000; k += 50) {
      source->append(scansOf(d, k, k + 50));
      remap.scansAppended();
    }
    QTRY_VERIFY_WITH_TIMEOUT(!remap.busy(), 120000);
    QCOMPARE(cancelled.count(), 0);
    QVERIFY(mapped.count() >= 2);
    QVERIFY(mapped.count() <= 1 + 36);  // at most one per append, fewer when they joined
    quint64 last = 0;
    for (const QList<QVariant>& m : mapped) {
      QVERIFY(m.at(2).value<quint64>() > last);
      last = m.at(2).value<quint64>();
    }
    const auto map = mapped.last().at(0).value<std::shared_ptr<const OccupancyMap>>();
    QVERIFY(sameLayers(*map, batchOn(d, 2000, s, map->spec)));
  }

  void liveTimeBackwardsRemaps() {
    // A live map taken back in time maps the readings up to then, on the same limits; forward
    // again, it continues.
    const Dataset d = walkLog();
    auto source = std::make_shared<ScanSource>(d.name, d.ring);
    source->append(scansOf(d, 0, 600));
    const MapperSettings s = settingsFor("parameterized", "bayes-recursive");
    RemapController remap;
    QSignalSpy mapped(&remap, &RemapController::mapped);
    remap.startLive(source, 0.05, s);
    QVERIFY(mapped.wait(60000));
    const auto whole = mapped.last().at(0).value<std::shared_ptr<const OccupancyMap>>();
    remap.setUntil(30.0);  // the readings up to 30 s: half the scans
    QVERIFY(mapped.wait(60000));
    QCOMPARE(mapped.last().at(3).toBool(), false);
    const auto back = mapped.last().at(0).value<std::shared_ptr<const OccupancyMap>>();
    QCOMPARE(back->spec, whole->spec);
    Mapper m(d.ring, back->spec, s);
    m.mapDataset(d, 30.0);
    QVERIFY(sameLayers(*back, m.snapshot()));
    remap.setUntil(std::numeric_limits<double>::infinity());
    QVERIFY(mapped.wait(60000));
    QCOMPARE(mapped.last().at(3).toBool(), true);
    QVERIFY(sameLayers(*mapped.last().at(0).value<std::shared_ptr<const OccupancyMap>>(), *whole));
  }

  void aLoadedLogTakesTheLiveRoad() {
    // One road for scans (issue 44): a log opened by the reader's entry point (openLog(), a
    // complete ScanSource) and the same scans streamed into a live source a few at a time, as a
    // robot link appends them, both mapped through startLive(), give the same grid. Each has the
    // bits of a batch run on its own limits (Mapper: batch and incremental mapping are identical,
    // also when the grid grew on the way: GridSpec::base), and the two agree cell for cell. The
    // room log comes 10 scans to an append.
    const std::shared_ptr<ScanSource> opened = openLog(SONARGRID_DATASETS "/room/room.sglog");
    QVERIFY(opened->complete());
    const std::shared_ptr<const Dataset> log = opened->view();
    QCOMPARE(opened->size(), log->scans.size());
    const MapperSettings s = settingsFor("parameterized", "bayes-recursive");

    RemapController whole;
    QSignalSpy wholeMapped(&whole, &RemapController::mapped);
    whole.startLive(opened, 0.05, s);
    QVERIFY(wholeMapped.wait(60000));
    const auto fromLog = wholeMapped.last().at(0).value<std::shared_ptr<const OccupancyMap>>();

    auto stream = std::make_shared<ScanSource>(log->name, log->ring);
    RemapController live;
    QSignalSpy liveMapped(&live, &RemapController::mapped);
    stream->append(scansOf(*log, 0, 10));
    live.startLive(stream, 0.05, s);
    for (std::size_t k = 10; k < log->scans.size(); k += 10) {
      stream->append(scansOf(*log, k, std::min(k + 10, log->scans.size())));
      live.scansAppended();
      QCoreApplication::processEvents();
    }
    stream->finish();
    QTRY_VERIFY_WITH_TIMEOUT(!live.busy(), 120000);
    const auto fromStream = liveMapped.last().at(0).value<std::shared_ptr<const OccupancyMap>>();

    QVERIFY(sameLayers(*fromLog, batchOn(*log, log->scans.size(), s, fromLog->spec)));
    QVERIFY(sameLayers(*fromStream, batchOn(*log, log->scans.size(), s, fromStream->spec)));
    // The same grid: the two limits differ (a live grid grows by half its size whenever a batch
    // reaches past it, so its limits depend on how the scans were batched) but lie on one lattice
    // of cells from the first pose, and every cell either observed holds the same value in both.
    const GridSpec& a = fromLog->spec;
    const GridSpec& b = fromStream->spec;
    const double sx = (b.origin.x() - a.origin.x()) / a.cellSize;
    const double sy = (b.origin.y() - a.origin.y()) / a.cellSize;
    QVERIFY(std::abs(sx - std::round(sx)) < 1e-6 && std::abs(sy - std::round(sy)) < 1e-6);
    const int dx = static_cast<int>(std::lround(sx)), dy = static_cast<int>(std::lround(sy));
    auto observedCount = [](const OccupancyMap& m) {
      return std::count(m.observed.begin(), m.observed.end(), std::uint8_t{1});
    };
    std::ptrdiff_t common = 0;
    for (int y = 0; y < b.height; ++y)
      for (int x = 0; x < b.width; ++x) {
        const int ax = x + dx, ay = y + dy;
        const std::size_t j = static_cast<std::size_t>(y) * b.width + x;
        if (ax < 0 || ay < 0 || ax >= a.width || ay >= a.height) {
          QCOMPARE(fromStream->observed[j], std::uint8_t{0});
          continue;
        }
        const std::size_t i = static_cast<std::size_t>(ay) * a.width + ax;
        QCOMPARE(fromStream->observed[j], fromLog->observed[i]);
        QCOMPARE(fromStream->level[j], fromLog->level[i]);
        QCOMPARE(fromStream->probability[j], fromLog->probability[i]);
        common += fromLog->observed[i];
      }
    QVERIFY(common > 1000);
    QCOMPARE(common, observedCount(*fromLog));  // none of the log's observed cells is left out
  }

  void theForwardModelRunsEmWithProgress() {
    // docs/forward-model.md: a forward-model run is EM over the whole log with emProgress() after
    // each iteration (the start, then one per iteration), no preview even with previews on, and
    // the map EM gives in the core (forward_em.h) to the last bit.
    const auto data = roomLog();
    RemapController remap;
    remap.setPreview(2, 0.0);
    QSignalSpy progress(&remap, &RemapController::emProgress);
    QSignalSpy previewed(&remap, &RemapController::previewed);
    QSignalSpy mapped(&remap, &RemapController::mapped);
    remap.start(data, 0.05, settingsFor("hpf", "bayes"), std::numeric_limits<double>::infinity());
    QVERIFY(mapped.wait(60000));
    MapperSettings em;
    em.model = forward::kModelName;
    em.rule = forward::kRuleName;
    em.parameters = forward::defaultForwardParameters();
    em.parameters.set("iterations", 4);
    remap.setSettings(em);
    QTRY_COMPARE_WITH_TIMEOUT(mapped.count(), 2, 60000);
    QCOMPARE(previewed.count(), 0);
    QTRY_COMPARE(progress.count(), 5);  // the starting map and 4 iterations
    for (int i = 0; i < 5; ++i) {
      QCOMPARE(progress.at(i).at(0).toInt(), i);
      QCOMPARE(progress.at(i).at(1).toInt(), 4);
      if (i > 0) QVERIFY(progress.at(i).at(2).toDouble() >= progress.at(i - 1).at(2).toDouble());
    }
    const auto map = mapped.at(1).at(0).value<std::shared_ptr<const OccupancyMap>>();
    QCOMPARE(map->model, std::string(forward::kModelName));
    const forward::EmResult expected = forward::runEm(forward::beamsOf(*data, PoseSource::Odometry),
                                                      data->fittingGrid(PoseSource::Odometry, 0.05),
                                                      forward::settingsOf(em.parameters));
    QVERIFY(map->probability.identical(expected.map.probability));
    QCOMPARE(map->level, expected.map.level);

    // Stop ends a run: cancelled, no map; the last map stays the controller's.
    em.parameters.set("iterations", 500);
    em.parameters.set("p_rand", 0.02);
    QSignalSpy cancelled(&remap, &RemapController::cancelled);
    const qsizetype before = progress.count();
    remap.setSettings(em);
    QTRY_VERIFY_WITH_TIMEOUT(progress.count() > before, 60000);  // EM is under way
    remap.stop();
    QVERIFY(cancelled.wait(60000));
    QVERIFY(cancelled.at(0).at(1).toBool());  // stopped part-way
    QTest::qWait(50);
    QCOMPARE(mapped.count(), 2);
    QCOMPARE(remap.lastMap(), map);
  }

  void theForwardModelRefusesALiveLink() {
    auto source = std::make_shared<ScanSource>("live", SonarRing::pioneer3dx());
    MapperSettings em;
    em.model = forward::kModelName;
    em.rule = forward::kRuleName;
    em.parameters = forward::defaultForwardParameters();
    RemapController remap;
    QSignalSpy failed(&remap, &RemapController::failed);
    remap.startLive(source, 0.05, em);
    QVERIFY(failed.wait(10000));
    QVERIFY2(failed.at(0).at(0).toString().contains("whole log"),
             qPrintable(failed.at(0).at(0).toString()));
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
