// SPDX-License-Identifier: BSD-3-Clause
// The mapper: batch equals incremental bit for bit, "until t" equals the prefix of the log,
// results are deterministic, and the errors a user can cause are reported.

#include <QtTest>
#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <set>
#include <thread>
#include <utility>

#include "sonargrid/base/concurrency.h"
#include "sonargrid/data/scan_poses.h"
#include "sonargrid/engine/mapper.h"
#include "sonargrid/engine/scan_source.h"
#include "sonargrid/io/sglog.h"
#include "sonargrid/rules/rule_classes.h"

using namespace sg;

namespace {

// A robot driving along a corridor whose walls are at y = ±1.2 m. Each sonar reports the nearest
// wall point inside its 25° cone, as a sonar does: the perpendicular distance when the normal lies
// in the cone, else the distance along the cone edge nearest the normal. Every fifth reading is a
// no-echo. Odometry drifts from the truth by 1 mm per scan.
Dataset corridor(int scans = 60) {
  Dataset d;
  d.name = "corridor";
  d.ring = SonarRing::pioneer3dx();
  const double half = d.ring.apertureRad / 2;
  for (int k = 0; k < scans; ++k) {
    Scan s;
    s.time = 0.1 * k;
    s.truth = Pose2D(0.05 * k, 0.0, 0.0);
    s.odometry = Pose2D(0.05 * k, 0.001 * k, 0.0);
    for (std::uint16_t i = 0; i < d.ring.size(); ++i) {
      const Pose2D sensor = s.truth->compose(d.ring.sonars[i].pose);
      const double h = sensor.heading;
      const bool north = std::sin(h) > 0;
      const double perpendicular = north ? 1.2 - sensor.y() : sensor.y() + 1.2;
      const double normal = north ? std::numbers::pi / 2 : -std::numbers::pi / 2;
      const double off = std::abs(wrapAngle(normal - h));
      const double toNormal =
          off <= half ? 0.0 : off - half;  // cone direction closest to the normal
      double range = perpendicular / std::cos(toNormal);
      if (toNormal > degToRad(60) || range >= d.ring.maxRange) range = Reading::kNoEcho;
      if ((k * 16 + i) % 5 == 0) range = Reading::kNoEcho;
      s.readings.push_back(Reading{i, range, s.time + 0.002 * i});
    }
    d.scans.push_back(std::move(s));
  }
  return d;
}

// The settings of a model × rule pair given by name (a data row's).
MapperSettings settingsOf(const QString& model, const QString& rule) {
  MapperSettings s;
  s.model = model.toStdString();
  s.rule = rule.toStdString();
  return s;
}

std::vector<std::pair<std::string, std::string>> allPairs() {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& m : sensorModelNames())
    for (const auto& r : updateRuleNames())
      if (compatibility(m, r).allowed) out.emplace_back(m, r);
  return out;
}

// Counts the footprints it is shown.
struct Counter final : FootprintObserver {
  std::size_t seen = 0;
  void reset(std::size_t) override { seen = 0; }
  void observe(const Footprint&) override { ++seen; }
};

bool sameLayers(const OccupancyMap& a, const OccupancyMap& b) {
  // Bit-identical: compare the doubles' bytes, not their values within a tolerance.
  return a.spec == b.spec && a.level == b.level && a.filled == b.filled &&
         a.observed == b.observed && a.probability.identical(b.probability) &&
         a.native.identical(b.native) && a.evidence.identical(b.evidence);
}

}  // namespace

class TstMapper : public QObject {
  Q_OBJECT

 private slots:
  void batchEqualsIncremental_data();
  void batchEqualsIncremental();
  void himmDirectEqualsFootprints_data();
  void himmDirectEqualsFootprints();
  void parallelBatchEqualsIncremental_data();
  void parallelBatchEqualsIncremental();
  void parallelIsRepeatable();
  void cancelMidRun();
  void cancelBands();
  void bandsForEveryRuleKind_data();
  void bandsForEveryRuleKind();
  void untilIsAPrefix();
  void deterministic();
  void poseSource();
  void buildsWalls();
  void errors();
  void cancel();
  void appendEqualsBatch_data();
  void appendEqualsBatch();
  void growthLeftAndDownEqualsBatch_data();
  void growthLeftAndDownEqualsBatch();
  void growthKeepsEveryValue_data();
  void growthKeepsEveryValue();
  void dirtyRowsAreTheRowsWritten_data();
  void dirtyRowsAreTheRowsWritten();
  void streamFromAnotherThread();
  void scansWithoutTruthAreLeftOut();
  void appendErrors();
  void snapshotsStayAsTaken_data();
  void snapshotsStayAsTaken();
  void snapshotLayersAreTheRules();
  void snapshotReadWhileMapping();
};

void TstMapper::batchEqualsIncremental_data() {
  QTest::addColumn<QString>("model");
  QTest::addColumn<QString>("rule");
  for (const auto& [m, r] : allPairs())
    QTest::newRow((m + "/" + r).c_str()) << QString::fromStdString(m) << QString::fromStdString(r);
}

void TstMapper::batchEqualsIncremental() {
  QFETCH(QString, model);
  QFETCH(QString, rule);
  const Dataset d = corridor();
  MapperSettings s = settingsOf(model, rule);
  const GridSpec grid = d.fittingGrid(PoseSource::Odometry, 0.05);
  Mapper batch(d.ring, grid, s);
  batch.mapDataset(d);
  Mapper incremental(d.ring, grid, s);
  for (const Scan& scan : d.scans) incremental.integrate(scan);
  QCOMPARE(batch.readingsIntegrated(), d.readingCount());
  QCOMPARE(incremental.readingsIntegrated(), d.readingCount());
  QVERIFY(sameLayers(batch.snapshot(), incremental.snapshot()));
  // A map with no evidence at all would make the comparison empty.
  QVERIFY(batch.snapshot().filledCount() > 0);

  // The same with no-echo readings clearing their cones.
  s.parameters = defaultParameters(s.model, s.rule);
  s.parameters.set("no_echo", 1.0);
  Mapper batchFree(d.ring, grid, s), incrementalFree(d.ring, grid, s);
  batchFree.mapDataset(d);
  for (const Scan& scan : d.scans) incrementalFree.integrate(scan);
  QVERIFY(sameLayers(batchFree.snapshot(), incrementalFree.snapshot()));
  QVERIFY(!sameLayers(batchFree.snapshot(), batch.snapshot()));
}

void TstMapper::himmDirectEqualsFootprints_data() {
  QTest::addColumn<double>("increment");
  QTest::addColumn<double>("decrement");
  QTest::addColumn<double>("cvMax");
  QTest::addColumn<double>("pHit");
  QTest::addColumn<double>("pMiss");
  QTest::addColumn<double>("noEcho");
  // Paper 000 §2.2's I⁺ = 3, I⁻ = 1, CV_max = 15; then the parameters' limits (himm_rule.cpp,
  // himm_model.cpp): a hit of p 0.5 and a miss of p 0.5 carry no evidence either way, so the HIMM
  // rule leaves such cells alone (but they are still observed).
  QTest::newRow("paper") << 3.0 << 1.0 << 15.0 << 0.7 << 0.4 << 0.0;
  QTest::newRow("no echo clears") << 3.0 << 1.0 << 15.0 << 0.7 << 0.4 << 1.0;
  QTest::newRow("saturate at 1") << 15.0 << 0.0 << 1.0 << 1.0 << 0.0 << 1.0;
  QTest::newRow("big decrement") << 1.0 << 15.0 << 15.0 << 0.9 << 0.1 << 0.0;
  QTest::newRow("hit says nothing") << 3.0 << 1.0 << 15.0 << 0.5 << 0.4 << 0.0;
  QTest::newRow("miss says nothing") << 3.0 << 1.0 << 15.0 << 0.7 << 0.5 << 1.0;
}

// A batch re-map with HIMM's model and rule folds the axis straight into the grid (on one thread,
// as this short log is mapped: SensorModel::integrateDirect); scan by scan goes through footprints
// and the rule's apply(). The two must leave the same bytes, on a grid that the corridor's beams
// leave on every side, so that some axis cells fall outside it and are skipped. (tst_fused_runs
// covers the listed path on several threads.)
void TstMapper::himmDirectEqualsFootprints() {
  QFETCH(double, increment);
  QFETCH(double, decrement);
  QFETCH(double, cvMax);
  QFETCH(double, pHit);
  QFETCH(double, pMiss);
  QFETCH(double, noEcho);
  const Dataset d = corridor();
  MapperSettings s;
  s.model = "himm";
  s.rule = "himm";
  s.parameters = defaultParameters(s.model, s.rule);
  s.parameters.set("increment", increment);
  s.parameters.set("decrement", decrement);
  s.parameters.set("cv_max", cvMax);
  s.parameters.set("p_hit", pHit);
  s.parameters.set("p_miss", pMiss);
  s.parameters.set("no_echo", noEcho);
  // The robot drives from x = 0 to 3 m between walls at y = ±1.2 m: this grid holds the walls
  // from x = 0.5 to 2.5 m only, so the beams leave it at both ends.
  GridSpec grid;
  grid.origin = Position(0.5, -1.5);
  grid.cellSize = 0.05;
  grid.width = 40;
  grid.height = 60;
  Mapper batch(d.ring, grid, s);
  batch.mapDataset(d);
  Mapper incremental(d.ring, grid, s);
  for (const Scan& scan : d.scans) incremental.integrate(scan);
  QCOMPARE(batch.readingsIntegrated(), d.readingCount());
  const OccupancyMap a = batch.snapshot(), b = incremental.snapshot();
  QVERIFY(sameLayers(a, b));
  QCOMPARE(a.level, b.level);  // the CVs themselves (levelOf is the CV)
  // Not an empty comparison: readings were observed and, but for the rows whose evidence says
  // nothing, changed CVs.
  QVERIFY(std::count(a.observed.begin(), a.observed.end(), 1) > 100);
  if (pHit > 0.5) QVERIFY(a.filledCount() > 0);
}

// The bundled room log has 11 888 readings, above the mapper's threshold for working on several
// threads (4096): these rows exercise the banded pipeline.
const Dataset& room() {
  static const Dataset d = readSglog(SONARGRID_DATASETS "/room/room.sglog");
  return d;
}

void TstMapper::parallelBatchEqualsIncremental_data() {
  batchEqualsIncremental_data();
}

void TstMapper::parallelBatchEqualsIncremental() {
  QFETCH(QString, model);
  QFETCH(QString, rule);
  const Dataset& d = room();
  QVERIFY(d.readingCount() > 4096);
  MapperSettings s = settingsOf(model, rule);
  s.pose = PoseSource::Truth;
  const GridSpec grid = d.fittingGrid(PoseSource::Truth, 0.05);
  Mapper batch(d.ring, grid, s);
  QVERIFY(batch.mapDataset(d));
  Mapper incremental(d.ring, grid, s);
  for (const Scan& scan : d.scans) incremental.integrate(scan);
  QCOMPARE(batch.readingsIntegrated(), d.readingCount());
  QVERIFY(sameLayers(batch.snapshot(), incremental.snapshot()));
}

void TstMapper::parallelIsRepeatable() {
  // Thread timing differs run to run; the grid must not.
  const Dataset& d = room();
  MapperSettings s;
  s.model = "konolige";
  s.rule = "dempster-shafer";
  const GridSpec grid = d.fittingGrid(PoseSource::Odometry, 0.05);
  Mapper m(d.ring, grid, s);
  m.mapDataset(d);
  const OccupancyMap first = m.snapshot();
  for (int k = 0; k < 5; ++k) {
    m.mapDataset(d);
    QVERIFY(sameLayers(first, m.snapshot()));
  }
}

void TstMapper::cancelMidRun() {
  // An observer raises the flag after 3000 readings; the batch stops at its next check (every 256
  // readings), reports it, and the same mapper then maps the whole log exactly as a fresh one.
  struct Canceller final : FootprintObserver {
    std::atomic<bool>* flag = nullptr;
    std::size_t seen = 0;
    void reset(std::size_t) override { seen = 0; }
    void observe(const Footprint&) override {
      if (++seen == 3000) flag->store(true);
    }
  };
  const Dataset& d = room();
  MapperSettings s;
  s.model = "hpf";
  s.rule = "bayes";
  const GridSpec grid = d.fittingGrid(PoseSource::Odometry, 0.05);
  std::atomic<bool> stop{false};
  Canceller canceller;
  canceller.flag = &stop;
  Mapper m(d.ring, grid, s);
  m.setObserver(&canceller);
  QVERIFY(!m.mapDataset(d, std::numeric_limits<double>::infinity(), &stop));
  QVERIFY(m.readingsIntegrated() >= 3000 && m.readingsIntegrated() < 3000 + 256 + 1);
  m.setObserver(nullptr);
  stop.store(false);
  QVERIFY(m.mapDataset(d, std::numeric_limits<double>::infinity(), &stop));
  Mapper fresh(d.ring, grid, s);
  fresh.mapDataset(d);
  QVERIFY(sameLayers(m.snapshot(), fresh.snapshot()));
}

void TstMapper::cancelBands() {
  // Without an observer a large log is mapped in bands of rows, one per thread (HIMM's
  // axis: listed on any thread, folded in in order). Cancelled before it starts: nothing is
  // integrated. Cancelled from another thread while it runs (the flag may come after the end on a
  // fast machine): either way the same mapper then maps the whole log exactly as a fresh one.
  const Dataset& d = room();
  const GridSpec grid = d.fittingGrid(PoseSource::Odometry, 0.05);
  const ScopedThreadCount policy(3);  // several threads whatever the machine's CPUs
  // Addition normalises: threads in step.
  for (const auto& [model, rule] : {std::pair{"hpf", "bayes"}, std::pair{"hpf", "addition"},
                                    std::pair{"himm", "himm"}, std::pair{"himm", "logodds"}}) {
    MapperSettings s;
    s.model = model;
    s.rule = rule;
    Mapper m(d.ring, grid, s);
    std::atomic<bool> stop{true};
    QVERIFY(!m.mapDataset(d, std::numeric_limits<double>::infinity(), &stop));
    QCOMPARE(m.readingsIntegrated(), std::size_t{0});
    stop.store(false);
    std::thread canceller([&stop] {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      stop.store(true);
    });
    const bool finished = m.mapDataset(d, std::numeric_limits<double>::infinity(), &stop);
    canceller.join();
    QVERIFY(finished ? m.readingsIntegrated() == d.readingCount()
                     : m.readingsIntegrated() < d.readingCount());
    stop.store(false);
    QVERIFY(m.mapDataset(d, std::numeric_limits<double>::infinity(), &stop));
    Mapper fresh(d.ring, grid, s);
    for (const Scan& scan : d.scans) fresh.integrate(scan);
    QVERIFY(sameLayers(m.snapshot(), fresh.snapshot()));
  }
}

void TstMapper::bandsForEveryRuleKind_data() {
  // The four ways a large log is mapped on several threads, each bit-identical to one thread
  // scan by scan, at any thread count (the policy's, concurrency.h): bands of rows (Bayes), bands
  // in two passes a chunk sharing each footprint's total (addition with normalisation, which
  // scales a footprint by its sum), HIMM's axis cells listed on any thread and folded in in order
  // (Mapper::integrateDirect; with its own rule and a probabilistic one), and, with an observer,
  // the ordered pipeline of footprints. 3 threads do not divide the rows evenly; 8 are more than
  // this machine may have.
  QTest::addColumn<QString>("model");
  QTest::addColumn<QString>("rule");
  QTest::addColumn<double>("normalise");  // < 0: the rule has no such parameter
  QTest::addColumn<bool>("observer");
  QTest::addColumn<unsigned>("threads");
  struct Case {
    const char* model;
    const char* rule;
    double normalise;
    bool observer;
  };
  for (const Case& c :
       {Case{"parameterized", "bayes", -1, false}, Case{"hpf", "addition", 1, false},
        Case{"hpf", "addition", 0, false}, Case{"murphy", "addition", 1, false},
        Case{"himm", "himm", -1, false}, Case{"himm", "dempster-shafer", -1, false},
        Case{"konolige", "logodds", -1, true}}) {
    for (unsigned threads : {1u, 2u, 3u, 8u}) {
      QTest::addRow("%s x %s%s%s, threads %u", c.model, c.rule,
                    c.normalise == 0 ? " (not normalised)" : "", c.observer ? ", observed" : "",
                    threads)
          << c.model << c.rule << c.normalise << c.observer << threads;
    }
  }
}

void TstMapper::bandsForEveryRuleKind() {
  QFETCH(QString, model);
  QFETCH(QString, rule);
  QFETCH(double, normalise);
  QFETCH(bool, observer);
  QFETCH(unsigned, threads);
  const Dataset& d = room();
  const GridSpec grid = d.fittingGrid(PoseSource::Odometry, 0.05);
  MapperSettings s = settingsOf(model, rule);
  s.parameters = defaultParameters(s.model, s.rule);
  if (normalise >= 0) s.parameters.set("normalise", normalise);
  Mapper incremental(d.ring, grid, s);
  for (const Scan& scan : d.scans) incremental.integrate(scan);
  Counter counter;
  const ScopedThreadCount policy(threads);
  Mapper batch(d.ring, grid, s);
  if (observer) batch.setObserver(&counter);
  QVERIFY(batch.mapDataset(d));
  QCOMPARE(batch.readingsIntegrated(), d.readingCount());
  if (observer) QCOMPARE(counter.seen, d.readingCount());  // each footprint once
  QVERIFY(sameLayers(batch.snapshot(), incremental.snapshot()));
  QVERIFY(batch.snapshot().filledCount() > 100);
}

void TstMapper::untilIsAPrefix() {
  // Mapping up to t = 2.0105 s keeps exactly the readings stamped at or before it: scans 0..19
  // whole (16 readings each) and, from scan 20 (t = 2.0 s, readings at 2.0 + 0.002 i), i = 0..5.
  const Dataset d = corridor();
  MapperSettings s;
  s.model = "murphy";
  s.rule = "bayes-recursive";
  const GridSpec grid = d.fittingGrid(PoseSource::Odometry, 0.05);
  Mapper until(d.ring, grid, s);
  until.mapDataset(d, 2.0105);
  QCOMPARE(until.readingsIntegrated(), std::size_t{20 * 16 + 6});

  Dataset prefix = d;
  prefix.scans.resize(21);
  prefix.scans[20].readings.resize(6);
  Mapper whole(d.ring, grid, s);
  whole.mapDataset(prefix);
  QVERIFY(sameLayers(until.snapshot(), whole.snapshot()));
}

void TstMapper::deterministic() {
  const Dataset d = corridor();
  MapperSettings s;
  s.model = "konolige";
  s.rule = "log";
  const GridSpec grid = d.fittingGrid(PoseSource::Odometry, 0.05);
  Mapper a(d.ring, grid, s), b(d.ring, grid, s);
  a.mapDataset(d);
  b.mapDataset(d);
  a.mapDataset(d);  // re-mapping the same mapper starts from scratch
  QVERIFY(sameLayers(a.snapshot(), b.snapshot()));
}

void TstMapper::poseSource() {
  const Dataset d = corridor();
  MapperSettings s;
  s.model = "himm";
  s.rule = "himm";
  const GridSpec grid = d.fittingGrid(PoseSource::Truth, 0.05);
  Mapper odom(d.ring, grid, s);
  odom.mapDataset(d);
  s.pose = PoseSource::Truth;
  Mapper truth(d.ring, grid, s);
  truth.mapDataset(d);
  QVERIFY(!sameLayers(odom.snapshot(), truth.snapshot()));
}

void TstMapper::buildsWalls() {
  // The corridor's walls are at y = ±1.2 m. HIMM puts each echo on the acoustic axis at the
  // reported (nearest-in-cone) range, so an oblique sonar's echo lands short of the wall: at most
  // for the ±30° sonars, whose nearest wall point is 60° − 12.5° = 47.5° off their axis, at
  // axis point y = r sin 30° = d⊥ sin 30°/cos 47.5° = 0.74 d⊥, about 0.29 m short of the wall for
  // d⊥ ≈ 1.1 m. So every filled cell lies within 0.35 m of a wall. The ±90° sonars hit the wall
  // square on, twice per 5 cm column (sonars 0 and 15, 0.226 m apart), less the one reading in five
  // the generator silences: along x = 1..2 m at least 15 of the 20 columns have a filled cell on
  // each wall.
  const Dataset d = corridor();
  MapperSettings s;
  s.model = "himm";
  s.rule = "himm";
  s.pose = PoseSource::Truth;
  const GridSpec grid = d.fittingGrid(PoseSource::Truth, 0.05);
  Mapper m(d.ring, grid, s);
  m.mapDataset(d);
  const OccupancyMap map = m.snapshot();
  std::set<int> north, south;
  for (std::size_t i = 0; i < map.filled.size(); ++i) {
    if (!map.filled[i]) continue;
    const Position c = grid.cellCentre(grid.fromLinear(i));
    const double fromWall = std::abs(std::abs(c.y()) - 1.2);
    QVERIFY2(fromWall <= 0.35, qPrintable(QString("filled cell at y = %1").arg(c.y())));
    if (fromWall <= 0.025 + 1e-9 && c.x() > 1.0 && c.x() < 2.0)
      (c.y() > 0 ? north : south).insert(grid.fromLinear(i).x());
  }
  QVERIFY2(north.size() >= 15 && south.size() >= 15,
           qPrintable(QString("north %1 south %2").arg(north.size()).arg(south.size())));
}

void TstMapper::errors() {
  const Dataset d = corridor(3);
  const GridSpec grid = d.fittingGrid(PoseSource::Odometry, 0.05);
  MapperSettings s;
  s.model = "nope";
  QVERIFY_THROWS_EXCEPTION(MapperError, Mapper(d.ring, grid, s));
  s.model = "hpf";
  s.rule = "himm";
  try {
    Mapper m(d.ring, grid, s);
    QFAIL("an incompatible pair was accepted");
  } catch (const MapperError& e) {
    QVERIFY(std::string(e.what()).find("cannot be used with rule 'himm'") != std::string::npos);
  }
  s.rule = "bayes";
  s.pose = PoseSource::Truth;
  Dataset noTruth = d;
  for (Scan& scan : noTruth.scans) scan.truth.reset();
  Mapper m(d.ring, grid, s);
  QVERIFY_THROWS_EXCEPTION(MapperError, m.mapDataset(noTruth));
  Dataset badSonar = d;
  badSonar.scans[1].readings[0].sonar = 16;
  s.pose = PoseSource::Odometry;
  Mapper m2(d.ring, grid, s);
  QVERIFY_THROWS_EXCEPTION(MapperError, m2.mapDataset(badSonar));
  // Parameters outside their declared range are refused where they are set.
  ParameterSet p = defaultParameters("hpf", "bayes");
  QVERIFY_THROWS_EXCEPTION(ParameterError, p.set("epsilon", -1.0));
  QVERIFY_THROWS_EXCEPTION(ParameterError, p.set("epsilon", std::nan("")));
  QVERIFY_THROWS_EXCEPTION(ParameterError, p.set("p4", 0.9));  // not a parameter of hpf × bayes

  // A grid the caller made itself is held to the core's cap too: 20 000² = 4e8 cells > 2e8,
  // refused before any cell is allocated.
  GridSpec huge = grid;
  huge.width = 20000;
  huge.height = 20000;
  s.rule = "bayes";
  QVERIFY_THROWS_EXCEPTION(GridLimitError, Mapper(d.ring, huge, s));
  // A log may declare any finite max_range; one whose cone tables would need more than
  // kMaxReachCells cells of radius is refused with a message, not an undefined cast: 1e12 m at
  // 5 cm is 2e13 cells; 150 m at 5 cm (3000 cells, plus HPF's reach) is over 2048 too.
  for (const double maxRange : {1e12, 150.0}) {
    SonarRing far = d.ring;
    far.maxRange = maxRange;
    try {
      Mapper m3(far, grid, s);
      QFAIL("a reach beyond the table limit was accepted");
    } catch (const MapperError& e) {
      QVERIFY2(std::string(e.what()).find("the limit is 2048 cells") != std::string::npos,
               e.what());
    }
  }
}

void TstMapper::cancel() {
  const Dataset d = corridor();
  MapperSettings s;
  const GridSpec grid = d.fittingGrid(PoseSource::Odometry, 0.05);
  Mapper m(d.ring, grid, s);
  std::atomic<bool> stop{true};
  QVERIFY(!m.mapDataset(d, std::numeric_limits<double>::infinity(), &stop));
  QCOMPARE(m.readingsIntegrated(), std::size_t{0});
}

// Streaming.

namespace {

// A one-cell grid at the first scan's position: everything else is growth.
GridSpec seedGrid(const Dataset& d, double cell = 0.05) {
  const Position p = d.scans.front().odometry.position;
  return GridSpec::covering(p, p, cell, 0.0);
}

// The rows of the grid that the readings of `scans` write, from the model's footprints.
std::set<int> rowsWritten(const Mapper& m, std::span<const Scan> scans) {
  std::set<int> rows;
  for (const Scan& scan : scans)
    for (const Reading& r : scan.readings)
      for (const CellEvidence& c : m.footprintOf(scan.odometry, r).cells)
        rows.insert(static_cast<int>(c.cell / static_cast<std::uint32_t>(m.grid().width)));
  return rows;
}

}  // namespace

void TstMapper::appendEqualsBatch_data() {
  batchEqualsIncremental_data();
}

void TstMapper::appendEqualsBatch() {
  // A 30 m corridor walk (600 scans, 9600 readings), mapped as a live robot would send it: the
  // first half at once (4800 readings: on several threads) on a grid that starts as one cell, then
  // the second half in 10 batches of 30 scans, each followed by a live refresh of the map. The
  // result equals, bit for bit in every layer, a batch map of all 600 scans on the grid's final
  // limits. The grid had to grow during the second half (the first half's grid reaches 5.3 m
  // past x = 15 m; the robot drives to x = 30 m), so growth kept every value.
  QFETCH(QString, model);
  QFETCH(QString, rule);
  const Dataset d = corridor(600);
  MapperSettings s = settingsOf(model, rule);
  const std::span<const Scan> all(d.scans);
  Mapper live(d.ring, seedGrid(d), s);
  QVERIFY(live.append(all.first(300)));
  const GridSpec firstHalf = live.grid();
  live.liveMap();
  for (std::size_t b = 0; b < 10; ++b) {
    QVERIFY(live.append(all.subspan(300 + 30 * b, 30)));
    live.liveMap();
  }
  QVERIFY(live.grid() != firstHalf);
  QCOMPARE(live.readingsIntegrated(), d.readingCount());

  Mapper batch(d.ring, live.grid(), s);
  QVERIFY(batch.mapDataset(d));
  const OccupancyMap expected = batch.snapshot();
  QVERIFY(sameLayers(expected, live.snapshot()));
  QVERIFY(sameLayers(expected, live.liveMap()));
  QVERIFY(expected.filledCount() > 0);
  // No footprint was cut by the edge: the batch grid's border rows and columns are unobserved.
  const GridSpec& g = expected.spec;
  for (int x = 0; x < g.width; ++x) {
    QVERIFY(!expected.observed[g.linear({x, 0})]);
    QVERIFY(!expected.observed[g.linear({x, g.height - 1})]);
  }
}

void TstMapper::growthLeftAndDownEqualsBatch_data() {
  batchEqualsIncremental_data();
}

void TstMapper::growthLeftAndDownEqualsBatch() {
  // The bundled room log (two laps of a simulated 6 x 4 m room) sent 10 scans at a time on a grid
  // that starts as one cell at the first pose: the grid grows in every direction, so its origin
  // moves left and down. The result equals, bit for bit in every layer, a batch map of the log on
  // the final limits (which count cells from the same base, GridSpec::base). The simulated poses
  // and ranges fall on cell boundaries: while the models counted cells from the moving origin
  // ((x - origin) / cell), a boundary point could land on either side, and himm × himm differed
  // in 10 cells, parameterized × bayes-recursive in 2 levels and 2 837 values (found by the scan
  // road's test, tst_remap_controller aLoadedLogTakesTheLiveRoad).
  QFETCH(QString, model);
  QFETCH(QString, rule);
  const Dataset& d = room();
  const MapperSettings s = settingsOf(model, rule);
  const std::span<const Scan> all(d.scans);
  Mapper live(d.ring, seedGrid(d), s);
  const GridSpec first = live.grid();
  for (std::size_t k = 0; k < all.size(); k += 10) {
    QVERIFY(live.append(all.subspan(k, std::min<std::size_t>(10, all.size() - k))));
    live.liveMap();
  }
  QVERIFY(live.grid().origin.x() < first.origin.x() && live.grid().origin.y() < first.origin.y());
  QVERIFY(live.grid().base == first.origin);
  Mapper batch(d.ring, live.grid(), s);
  QVERIFY(batch.mapDataset(d));
  const OccupancyMap expected = batch.snapshot();
  QVERIFY(sameLayers(expected, live.snapshot()));
  QVERIFY(sameLayers(expected, live.liveMap()));
  QVERIFY(expected.filledCount() > 0);
}

void TstMapper::snapshotsStayAsTaken_data() {
  batchEqualsIncremental_data();
}

void TstMapper::snapshotsStayAsTaken() {
  // A snapshot reads its p(occupied), native value, evidence and filled flag from the grid's cells,
  // which it shares rather than copies (docs/models.md, "Snapshots"). Mapping on must copy them
  // before writing: every snapshot taken along the way (and every copy of the live map) still
  // holds, bit for bit, what a copy of its layers made when it was taken (hold()) holds, through
  // append() with growth, integrate(), mapDataset() and reset().
  QFETCH(QString, model);
  QFETCH(QString, rule);
  const Dataset d = corridor(200);
  MapperSettings s = settingsOf(model, rule);
  Mapper m(d.ring, seedGrid(d), s);
  std::vector<OccupancyMap> taken, held;
  auto take = [&](const OccupancyMap& snapshot) {
    QVERIFY(snapshot.derived());
    taken.push_back(snapshot);
    held.push_back(snapshot);
    held.back().hold();
    QVERIFY(!held.back().derived());
  };
  const std::span<const Scan> all(d.scans);
  QVERIFY(m.append(all.first(40)));
  take(m.snapshot());
  take(m.liveMap());
  const GridSpec before = m.grid();
  QVERIFY(m.append(all.subspan(40, 60)));  // 3 m further on: the grid grows
  QVERIFY(m.grid() != before);
  take(m.liveMap());
  for (std::size_t k = 100; k < 110; ++k) m.integrate(d.scans[k]);
  take(m.liveMap());
  QVERIFY(m.mapDataset(d));
  take(m.snapshot());
  m.reset();
  QVERIFY(m.append(all.first(5)));
  for (std::size_t k = 0; k < taken.size(); ++k)
    QVERIFY2(sameLayers(taken[k], held[k]), qPrintable(QString("snapshot %1").arg(k)));
  // The snapshots differ from one another, so a snapshot that followed the grid would be seen.
  QVERIFY(!sameLayers(held[0], held[4]) && !sameLayers(held[2], held[3]));
}

void TstMapper::snapshotLayersAreTheRules() {
  // A mapped snapshot keeps only its levels and observed flags (2 bytes a cell); its other layers
  // are the rule's reading of the grid's cells (UpdateRule::occupancy and the rest), bit for bit.
  // Writing a layer of a copy makes that copy hold its own values and leaves the snapshot as it
  // was.
  const Dataset d = corridor(60);
  for (const std::string rule : {"addition", "dempster-shafer", "logodds"}) {
    MapperSettings s;
    s.rule = rule;
    Mapper m(d.ring, d.fittingGrid(PoseSource::Odometry, 0.05), s);
    QVERIFY(m.mapDataset(d));
    const OccupancyMap snapshot = m.snapshot();
    QCOMPARE(snapshot.bytesPerCell(), std::size_t{2});
    const Grid& g = m.storage();
    const UpdateRule& r = m.rule();
    std::size_t written = 0;
    for (std::size_t i = 0; i < g.cellCount(); ++i) {
      QCOMPARE(std::bit_cast<std::uint64_t>(snapshot.probability[i]),
               std::bit_cast<std::uint64_t>(r.occupancy(g, i)));
      QCOMPARE(std::bit_cast<std::uint64_t>(snapshot.native[i]),
               std::bit_cast<std::uint64_t>(r.native(g, i)));
      QCOMPARE(std::bit_cast<std::uint64_t>(snapshot.evidence[i]),
               std::bit_cast<std::uint64_t>(r.evidence(g, i)));
      QCOMPARE(snapshot.filled[i], static_cast<std::uint8_t>(r.filled(g, i) ? 1 : 0));
      QCOMPARE(snapshot.level[i], r.level(g, i));
      written += g.observed(i) ? 1 : 0;
    }
    QVERIFY(written > 0);
    OccupancyMap copy = snapshot;
    const double before = snapshot.probability[5];
    copy.probability[5] = 0.25;
    QVERIFY(!copy.probability.derived() && copy.native.derived());
    QCOMPARE(copy.probability[5], 0.25);
    QCOMPARE(copy.probability[6], snapshot.probability[6]);
    QCOMPARE(snapshot.probability[5], before);
    QCOMPARE(copy.bytesPerCell(), std::size_t{2 + 8});
  }
}

void TstMapper::snapshotReadWhileMapping() {
  // One thread reads a snapshot's layers while another maps on, as the view and the metrics read
  // the map on show while the worker maps the next batch: the mapper copies the cells the snapshot
  // shares before writing them, so the reader sees the same bits throughout. Then a second reader
  // lets its snapshot go while the mapper waits (with no ordering of its own, a relaxed flag) and
  // the mapper writes the cells in place: the reader's end is ordered before those writes by the
  // grid's count of readers. Under ThreadSanitizer (the sanitizer job, SONARGRID_THREADS=4) no
  // write races with a read on either path.
  const Dataset d = corridor(300);
  MapperSettings s;
  s.rule = "bayes";
  // The grid the whole log fits: it never grows (growth would give the mapper new cells anyway).
  Mapper m(d.ring, d.fittingGrid(PoseSource::Odometry, 0.05), s);
  for (std::size_t k = 0; k < 100; ++k) m.integrate(d.scans[k]);
  const OccupancyMap shown = m.liveMap();
  OccupancyMap expected = shown;
  expected.hold();
  std::atomic<bool> done{false};
  std::atomic<int> reads{0};
  bool same = true;
  std::thread reader([&] {
    do {
      same = same && sameLayers(shown, expected);
      reads.fetch_add(1);
    } while (!done.load());
  });
  for (std::size_t k = 100; k < 200; ++k) {
    m.integrate(d.scans[k]);
    if (k % 20 == 0) m.liveMap();
  }
  done.store(true);
  reader.join();
  QVERIFY(same);
  QVERIFY(reads.load() >= 1);
  QVERIFY(!sameLayers(m.snapshot(), expected));  // the mapper went on

  // The second reader: its snapshot is the grid's present cells, read and then let go.
  auto lent = std::make_unique<OccupancyMap>(m.snapshot());
  const Grid& grid = m.storage();
  const BayesCell* const cells = grid.cells<BayesCell>();
  QVERIFY(grid.shared());
  std::atomic<bool> letGo{false};
  double sum = 0.0;
  std::thread borrower([&, owned = std::move(lent)]() mutable {
    for (std::size_t i = 0; i < owned->probability.size(); ++i) sum += owned->probability[i];
    owned.reset();
    letGo.store(true, std::memory_order_relaxed);
  });
  while (!letGo.load(std::memory_order_relaxed)) std::this_thread::yield();
  QVERIFY(!grid.shared());
  for (std::size_t k = 200; k < 300; ++k) m.integrate(d.scans[k]);
  QCOMPARE(grid.cells<BayesCell>(), cells);  // written in place, not copied
  borrower.join();
  QVERIFY(sum > 0.0);
}

void TstMapper::growthKeepsEveryValue_data() {
  QTest::addColumn<QString>("model");
  QTest::addColumn<QString>("rule");
  for (const std::string& r : updateRuleNames()) {
    const std::string m = r == "himm" ? "himm" : "hpf";
    QTest::newRow(r.c_str()) << QString::fromStdString(m) << QString::fromStdString(r);
  }
}

void TstMapper::growthKeepsEveryValue() {
  // The corridor mapped on its fitting grid, then the grid grown 3 m to the left, 2 m down and
  // 4 m up (or more: growth has slack): at every old cell's world position the grown map has the
  // same five layers, bit for bit; every new cell is what a cell nobody has seen is (a fresh
  // map's), and unobserved.
  QFETCH(QString, model);
  QFETCH(QString, rule);
  const Dataset d = corridor();
  MapperSettings s = settingsOf(model, rule);
  const GridSpec before = d.fittingGrid(PoseSource::Odometry, 0.05);
  Mapper m(d.ring, before, s);
  m.mapDataset(d);
  const OccupancyMap old = m.snapshot();
  const OccupancyMap unknown = Mapper(d.ring, before, s).snapshot();
  const Position lo = before.origin - Position(3.0, 2.0);
  const Position hi = before.origin + Position(1.0, before.heightMetres() + 4.0);
  QVERIFY(m.reserve(lo, hi));
  QVERIFY(!m.reserve(lo, hi));  // covered now
  const GridSpec& after = m.grid();
  // The origin moved by whole cells, at least the 60 and 40 asked for (more with the slack).
  const Position moved = (before.origin - after.origin) / before.cellSize;
  QVERIFY(std::abs(moved.x() - std::round(moved.x())) < 1e-9 && moved.x() >= 60.0 - 1e-9);
  QVERIFY(std::abs(moved.y() - std::round(moved.y())) < 1e-9 && moved.y() >= 40.0 - 1e-9);
  const OccupancyMap grown = m.snapshot();
  std::vector<char> fromOld(grown.level.size(), 0);
  for (std::size_t i = 0; i < old.level.size(); ++i) {
    const CellIndex c = after.worldToCell(before.cellCentre(before.fromLinear(i)));
    QVERIFY(after.contains(c));
    const std::size_t j = after.linear(c);
    fromOld[j] = 1;
    QCOMPARE(std::bit_cast<std::uint64_t>(grown.probability[j]),
             std::bit_cast<std::uint64_t>(old.probability[i]));
    QCOMPARE(std::bit_cast<std::uint64_t>(grown.native[j]),
             std::bit_cast<std::uint64_t>(old.native[i]));
    QCOMPARE(grown.level[j], old.level[i]);
    QCOMPARE(grown.filled[j], old.filled[i]);
    QCOMPARE(grown.observed[j], old.observed[i]);
  }
  for (std::size_t j = 0; j < grown.level.size(); ++j) {
    if (fromOld[j]) continue;
    QCOMPARE(std::bit_cast<std::uint64_t>(grown.probability[j]),
             std::bit_cast<std::uint64_t>(unknown.probability[0]));
    QCOMPARE(std::bit_cast<std::uint64_t>(grown.native[j]),
             std::bit_cast<std::uint64_t>(unknown.native[0]));
    QCOMPARE(grown.level[j], unknown.level[0]);
    QCOMPARE(grown.filled[j], std::uint8_t{0});
    QCOMPARE(grown.observed[j], std::uint8_t{0});
  }
  QVERIFY(old.filledCount() > 0);
}

void TstMapper::dirtyRowsAreTheRowsWritten_data() {
  QTest::addColumn<QString>("model");
  QTest::addColumn<QString>("rule");
  QTest::addColumn<unsigned>("threads");
  // One thread scan by scan, and a batch above the threshold for threads: stripes of rows
  // (Bayes), stripes in step (addition normalises), the ordered pipeline (HIMM's axis line); on
  // one thread and on three (which do not divide the stripes evenly).
  for (const auto& [m, r] :
       {std::pair{"hpf", "bayes"}, std::pair{"hpf", "addition"}, std::pair{"himm", "himm"}})
    for (unsigned threads : {1u, 3u})
      QTest::addRow("%s x %s, threads %u", m, r, threads) << m << r << threads;
}

void TstMapper::dirtyRowsAreTheRowsWritten() {
  QFETCH(QString, model);
  QFETCH(QString, rule);
  QFETCH(unsigned, threads);
  const ScopedThreadCount policy(threads);
  MapperSettings s = settingsOf(model, rule);
  const Dataset& d = room();
  const std::span<const Scan> all(d.scans);
  Mapper m(d.ring, seedGrid(d), s);
  QVERIFY(m.append(all));  // grows to hold every footprint of the log
  const OccupancyMap& first = m.liveMap();
  QVERIFY(sameLayers(first, m.snapshot()));
  QVERIFY(m.storage().dirtyRows().empty());

  // One scan, then three: the dirty rows are exactly those of their footprints, and the live map
  // rewrites them (one band from the first to the last) and equals a full snapshot.
  for (const std::span<const Scan> part : {all.subspan(40, 1), all.subspan(200, 3)}) {
    const std::set<int> rows = rowsWritten(m, part);
    QVERIFY(!m.reserve(m.grid().origin, m.grid().origin));
    QVERIFY(m.append(part));
    const std::vector<int> dirty = m.storage().dirtyRows();
    QCOMPARE(dirty, std::vector<int>(rows.begin(), rows.end()));
    RowBand band;
    const OccupancyMap& refreshed = m.liveMap(&band);
    QCOMPARE(band, (RowBand{*rows.begin(), *rows.rbegin() + 1}));
    QVERIFY(sameLayers(refreshed, m.snapshot()));
    QVERIFY(m.storage().dirtyRows().empty());
  }
  // The whole log again (11 888 readings, on several threads): every row any footprint writes.
  const std::set<int> rows = rowsWritten(m, all);
  const GridSpec spec = m.grid();
  QVERIFY(m.append(all));
  QCOMPARE(m.grid(), spec);
  const std::vector<int> dirty = m.storage().dirtyRows();
  QCOMPARE(dirty, std::vector<int>(rows.begin(), rows.end()));
  QVERIFY(sameLayers(m.liveMap(), m.snapshot()));
}

void TstMapper::streamFromAnotherThread() {
  // A link thread appends the room log to a scan source a few scans at a time while this thread
  // maps whatever has arrived: the map equals the batch map of the whole log on the final limits.
  const Dataset& d = room();
  MapperSettings s;
  s.model = "murphy";
  s.rule = "logodds";
  auto source = std::make_shared<ScanSource>(d.name, d.ring);
  std::thread link([source, &d] {
    for (std::size_t k = 0; k < d.scans.size(); k += 5) {
      const auto end =
          d.scans.begin() + static_cast<std::ptrdiff_t>(std::min(k + 5, d.scans.size()));
      source->append(std::vector<Scan>(d.scans.begin() + static_cast<std::ptrdiff_t>(k), end));
    }
    source->finish();
  });
  Mapper m(d.ring, seedGrid(d), s);
  std::size_t done = 0;
  for (bool complete = false; !complete;) {
    complete = source->complete();
    const ScanPrefix p = source->prefix();
    for (const std::span<const Scan> part : p.spans(done, p.size())) QVERIFY(m.append(part));
    done = p.size();
    m.liveMap();
  }
  link.join();
  QCOMPARE(done, d.scans.size());
  Mapper batch(d.ring, m.grid(), s);
  QVERIFY(batch.mapDataset(d));
  QVERIFY(sameLayers(batch.snapshot(), m.liveMap()));
}

// A simulator's first SIP before its first SIMSTAT leaves that scan without a true pose
// (data/scan_poses.h): mapped with true poses, it is left out (never placed by its odometry, which
// is another frame), the same in batch, appended and scan by scan, and counted.
void TstMapper::scansWithoutTruthAreLeftOut() {
  const Dataset d = corridor(3);
  Dataset partial = d;
  partial.scans[0].truth.reset();
  Dataset without = d;  // the same log without its first scan
  without.scans.erase(without.scans.begin());
  QCOMPARE(scansWithoutPose(partial, PoseSource::Truth), std::size_t{1});
  QCOMPARE(scansWithoutPose(partial, PoseSource::Odometry), std::size_t{0});
  MapperSettings s;
  s.pose = PoseSource::Truth;
  // The fitting grid leaves it out too: the first scan's odometry is not in it.
  QVERIFY(partial.fittingGrid(PoseSource::Truth, 0.05) ==
          without.fittingGrid(PoseSource::Truth, 0.05));
  const GridSpec grid = without.fittingGrid(PoseSource::Truth, 0.05);
  Mapper batch(d.ring, grid, s);
  QVERIFY(batch.mapDataset(partial));
  QCOMPARE(batch.readingsIntegrated(), std::size_t{32});  // 2 scans x 16 sonars
  Mapper expected(d.ring, grid, s);
  QVERIFY(expected.mapDataset(without));
  QVERIFY(sameLayers(batch.snapshot(), expected.snapshot()));
  Mapper streamed(d.ring, seedGrid(d), s);
  QVERIFY(streamed.append(std::span(partial.scans).first(1)));  // nothing to map yet
  QCOMPARE(streamed.readingsIntegrated(), std::size_t{0});
  QVERIFY(streamed.append(std::span(partial.scans).subspan(1)));
  QCOMPARE(streamed.readingsIntegrated(), std::size_t{32});
  Mapper onItsGrid(d.ring, streamed.grid(), s);
  QVERIFY(onItsGrid.mapDataset(partial));
  QVERIFY(sameLayers(streamed.snapshot(), onItsGrid.snapshot()));
  Mapper oneByOne(d.ring, grid, s);
  for (const Scan& scan : partial.scans) oneByOne.integrate(scan);
  QVERIFY(sameLayers(oneByOne.snapshot(), expected.snapshot()));
}

void TstMapper::appendErrors() {
  const Dataset d = corridor(3);
  MapperSettings s;
  // Truth asked for, no scan has it: refused before anything is integrated.
  s.pose = PoseSource::Truth;
  Dataset noTruth = d;
  for (Scan& scan : noTruth.scans) scan.truth.reset();
  Mapper m(d.ring, seedGrid(d), s);
  try {
    m.mapDataset(noTruth);
    QFAIL("a log without a true pose was mapped with true poses");
  } catch (const MapperError& e) {
    QVERIFY2(std::string(e.what()).find("no true pose") != std::string::npos, e.what());
  }
  QCOMPARE(m.readingsIntegrated(), std::size_t{0});
  // A pose 10 000 km away would need a grid past the limit (docs/cli.md, --cell).
  Dataset far = d;
  far.scans[1].odometry = Pose2D(1e7, 0.0, 0.0);
  s.pose = PoseSource::Odometry;
  Mapper m2(d.ring, seedGrid(d), s);
  const GridSpec seed = m2.grid();
  try {
    m2.append(far.scans);
    QFAIL("a grid past the limit was grown");
  } catch (const MapperError& e) {
    QVERIFY2(std::string(e.what()).find("limit of 200000000 cells") != std::string::npos, e.what());
  }
  QCOMPARE(m2.grid(), seed);
  Dataset nan = d;
  nan.scans[1].odometry = Pose2D(std::nan(""), 0.0, 0.0);
  QVERIFY_THROWS_EXCEPTION(MapperError, m2.append(nan.scans));
  // An observer counts cells of the limits it was reset with: growth is refused while one is set.
  struct Counter final : FootprintObserver {
    void reset(std::size_t) override {}
    void observe(const Footprint&) override {}
  } counter;
  m2.setObserver(&counter);
  QVERIFY_THROWS_EXCEPTION(MapperError, m2.append(d.scans));
  m2.setObserver(nullptr);
  QVERIFY(m2.append(d.scans));
  QCOMPARE(m2.readingsIntegrated(), d.readingCount());
}

QTEST_GUILESS_MAIN(TstMapper)
#include "tst_mapper.moc"
