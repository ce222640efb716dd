// SPDX-License-Identifier: BSD-3-Clause
// The batch path where the model hands its cells to the rule as runs (SensorModel::evidenceRuns,
// UpdateRule::applyRuns; no Footprint in between) against the footprint path, the oracle: every
// cone model × every probabilistic rule, on 1, 2 and 3 threads, with the rows in eight lanes built
// for AVX-512 and for AVX2 (on a CPU with them) and in four, must leave every plane of the grid and
// every observed mark with the same bits. The same for HIMM's axis with every rule, whose batch
// path lists each reading's axis cells and folds them into the grid with one
// UpdateRule::applyUniform call per value (the HIMM rule: a table look-up per cell;
// SensorModel::listDirect, applyDirect), on 1, 2 and 3 threads. And applyUniform and applyRuns on
// their own against apply(), for evidence and cell values the models never give (both kinds of
// evidence at once, out of range, NaN) and lists and runs of every length around the lanes' four
// and eight.
//
// Where the expectations come from: the grid of the footprint path itself. A mapper with a
// FootprintObserver maps through footprint() and UpdateRule::apply() one reading at a time (the
// observer must see whole footprints: Mapper::integrateBeams), which is the code every other suite
// pins (tst_rules' hand-computed updates, tst_models' values, tst_mapper's batch = incremental);
// Mapper::integrate() scan by scan is that same path, and is checked to agree with it first.

#include <QtTest>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>

#include "sonargrid/base/concurrency.h"
#include "sonargrid/engine/mapper.h"
#include "sonargrid/models/cone_model.h"
#include "sonargrid/rules/rule_classes.h"
#include "sonargrid/testing/registry_hooks.h"

using namespace sg;

namespace {

// Sees every footprint and does nothing: makes the mapper use the footprint path.
struct NullObserver final : FootprintObserver {
  void reset(std::size_t) override {}
  void observe(const Footprint&) override {}
};

// A 4 × 3 m grid at 5 cm, smaller than the sonar's 5 m reach, so that most cones are cut by its
// edges.
GridSpec smallGrid() {
  GridSpec g;
  g.origin = Position(-2.0, -1.5);
  g.cellSize = 0.05;
  g.width = 80;
  g.height = 60;
  return g;
}

// A fixed linear congruential sequence: uniform(lo, hi) is the same every run.
struct Uniform {
  std::uint64_t state;
  double operator()(double lo, double hi) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return lo + (hi - lo) * static_cast<double>(state >> 11) * 0x1p-53;
  }
};

// `scans` scans of the 16-sonar Pioneer ring (270 by default: 4320 readings, above the mapper's
// 4096 below which it keeps to one thread): scan k at poseOf(k, uniform), each range drawn from
// [0.05, 5.6) m, and a no-echo at or beyond the maximum range and where noEcho(k, sonar) says.
template <class PoseOf, class NoEcho>
Dataset ringLog(const char* name, std::uint64_t seed, PoseOf poseOf, NoEcho noEcho,
                int scans = 270) {
  Dataset d;
  d.name = name;
  d.ring = SonarRing::pioneer3dx();
  Uniform uniform{seed};
  for (int k = 0; k < scans; ++k) {
    Scan s;
    s.time = 0.1 * k;
    s.odometry = poseOf(k, uniform);
    s.truth = s.odometry;
    for (std::uint16_t i = 0; i < d.ring.size(); ++i) {
      double range = uniform(0.05, 5.6);
      if (noEcho(k, i) || range >= d.ring.maxRange) range = Reading::kNoEcho;
      s.readings.push_back(Reading{i, range, s.time + 0.002 * i});
    }
    d.scans.push_back(std::move(s));
  }
  return d;
}

// A generated log (a fixed linear congruential sequence, so the same every run): 270 scans of the
// 16-sonar Pioneer ring, 4320 readings, above the mapper's 4096 below which it keeps to one thread.
// The robot is placed anywhere in the grid, every ninth scan within 5 cm of an edge or a corner
// (rows and columns at the grid's edge; cones leaving it), at any heading, every eighth scan at a
// heading of exactly ±π (sonars whose cones straddle the ±π bearing line; the front sonar's axis
// on it). Ranges run from 0.05 m to beyond the maximum: every fifth reading, and any beyond 5 m,
// is a no-echo.
Dataset generated() {
  const GridSpec g = smallGrid();
  const double x0 = g.origin.x(), x1 = x0 + g.widthMetres();
  const double y0 = g.origin.y(), y1 = y0 + g.heightMetres();
  return ringLog(
      "generated", 12345,
      [&](int k, Uniform& uniform) {
        double x = uniform(x0 + 0.3, x1 - 0.3), y = uniform(y0 + 0.3, y1 - 0.3);
        if (k % 9 == 0) {  // at an edge or in a corner
          x = (k / 9) % 3 == 0 ? x0 + 0.03 : (k / 9) % 3 == 1 ? x1 - 0.03 : x;
          y = (k / 9) % 2 == 0 ? y0 + 0.02 : y1 - 0.04;
        }
        double heading = uniform(-std::numbers::pi, std::numbers::pi);
        if (k % 8 == 0) heading = k % 16 == 0 ? std::numbers::pi : -std::numbers::pi;
        return Pose2D(x, y, heading);
      },
      [](int k, int sonar) { return (k * 16 + sonar) % 5 == 0; });
}

const Dataset& workload() {
  static const Dataset d = generated();
  return d;
}

// A 2 × 30 m grid at 5 cm (600 rows), six times the sonar's reach: on several threads each
// thread's band of rows (row_bands.h) is far from most beams, which it passes over before the
// model sets them up (Mapper::integrateBands).
GridSpec tallGrid() {
  GridSpec g;
  g.origin = Position(-1.0, 0.0);
  g.cellSize = 0.05;
  g.width = 40;
  g.height = 600;
  return g;
}

// ringLog()'s scans at random places along the tall grid, at any heading, no-echo readings only
// at or beyond the maximum range.
Dataset tallGenerated() {
  return ringLog(
      "tall", 777,
      [](int, Uniform& uniform) {
        const double x = uniform(-0.7, 0.7), y = uniform(0.3, 29.7);
        return Pose2D(x, y, uniform(-3.14, 3.14));
      },
      [](int, int) { return false; });
}

// Whether two grids of one rule hold the same bits in every plane, and the same observed marks.
template <class... Cells>
bool samePlanes(const Grid& a, const Grid& b) {
  if (a.cellCount() != b.cellCount()) return false;
  const std::size_t n = a.cellCount();
  std::size_t plane = 0;
  const bool planes =
      ((std::memcmp(a.cells<Cells>(plane), b.cells<Cells>(plane), n * sizeof(Cells)) == 0 &&
        ++plane) &&
       ...);
  std::vector<std::uint8_t> ma(n), mb(n);
  a.copyObserved(0, n, ma.data());
  b.copyObserved(0, n, mb.data());
  return planes && ma == mb;
}

bool sameGrid(const std::string& rule, const Grid& a, const Grid& b) {
  if (rule == "addition") return samePlanes<EmptyEvidence, OccupiedEvidence>(a, b);
  if (rule == "bayes" || rule == "bayes-recursive") return samePlanes<BayesCell>(a, b);
  if (rule == "log") return samePlanes<LogCell>(a, b);
  if (rule == "logodds") return samePlanes<LogOddsCell>(a, b);
  if (rule == "dempster-shafer") return samePlanes<DempsterShaferCell>(a, b);
  if (rule == "himm") return samePlanes<HimmCell>(a, b);
  return false;
}

// Settings of a row: true poses (the workload's odometry is its truth), the pair's defaults, and
// no-echo updates on or off.
MapperSettings rowSettings(const std::string& model, const std::string& rule, bool noEchoFree) {
  MapperSettings settings;
  settings.model = model;
  settings.rule = rule;
  settings.pose = PoseSource::Truth;
  settings.parameters = defaultParameters(model, rule);
  settings.parameters.set("no_echo", noEchoFree ? 1.0 : 0.0);
  return settings;
}

// Maps `d` on grid `g` with `settings` by the footprint path, one reading at a time on one thread
// (the oracle), then on 2 and 3 threads: what differs first, or nothing.
QString threadsAgainstFootprintPath(const Dataset& d, const GridSpec& g,
                                    const MapperSettings& settings) {
  Mapper oracle(d.ring, g, settings);
  NullObserver observer;
  oracle.setObserver(&observer);
  {
    ScopedThreadCount one(1);
    if (!oracle.mapDataset(d)) return "the footprint path stopped";
  }
  for (const unsigned threads : {2u, 3u}) {
    ScopedThreadCount count(threads);
    Mapper runs(d.ring, g, settings);
    if (!runs.mapDataset(d) || runs.readingsIntegrated() != d.readingCount())
      return QString("%1 threads: not every reading was mapped").arg(threads);
    if (!sameGrid(settings.rule, oracle.storage(), runs.storage()))
      return QString("%1 threads: the grid differs from the footprint path's").arg(threads);
  }
  return {};
}

}  // namespace

// testing::limitConeLanes for its lifetime: the cone rows' lanes and the run kernels' (masked
// eight where the CPU has AVX-512, else four), so that a machine with AVX-512 checks both.
struct LaneLimit {
  explicit LaneLimit(ConeLanes widest) : previous(testing::limitConeLanes(widest)) {}
  ~LaneLimit() { testing::limitConeLanes(previous); }
  LaneLimit(const LaneLimit&) = delete;
  LaneLimit& operator=(const LaneLimit&) = delete;
  ConeLanes previous;
};
constexpr ConeLanes kRunLanes[] = {ConeLanes::Avx512, ConeLanes::Four};

class TstFusedRuns : public QObject {
  Q_OBJECT

 private slots:
  void runsGiveTheFootprintPathsBits_data();
  void runsGiveTheFootprintPathsBits();
  void himmAxisGivesTheFootprintPathsBits_data();
  void himmAxisGivesTheFootprintPathsBits();
  void uniformGivesApplysBits_data();
  void uniformGivesApplysBits();
  void runsGiveApplysBits_data();
  void runsGiveApplysBits();
  void deferredRunsGiveApplysBits();
  void occupiedTotalAtEveryWidth();
  void tallGridThreadsPassOverFarBeams_data();
  void tallGridThreadsPassOverFarBeams();
  void additionInChunksKeepsTheBits_data();
  void additionInChunksKeepsTheBits();
};

void TstFusedRuns::runsGiveTheFootprintPathsBits_data() {
  QTest::addColumn<QString>("model");
  QTest::addColumn<QString>("rule");
  QTest::addColumn<bool>("noEchoFree");
  QTest::addColumn<bool>("normalise");
  QTest::addColumn<double>("prior");
  const char* const models[] = {"hpf", "konolige", "murphy", "parameterized"};
  const char* const rules[] = {"addition", "bayes",   "bayes-recursive",
                               "log",      "logodds", "dempster-shafer"};
  for (const char* m : models) {
    for (const char* r : rules) {
      // No-echo readings write nothing by default and free space with no_echo = 1 (every model
      // declares the switch: noEchoParameter); addition defers its occupied cells until the
      // reading's total is known when it normalises (its default) and applies them at once when
      // not.
      for (const bool noEcho : {false, true}) {
        for (const bool normalise : {true, false}) {
          if (!normalise && std::string(r) != "addition") continue;
          QTest::addRow("%s/%s%s%s", m, r, noEcho ? " no_echo=1" : "",
                        normalise ? "" : " normalise=0")
              << QString(m) << QString(r) << noEcho << normalise << 0.5;
        }
      }
    }
    // Log-odds' prior other than 0.5: its 1/prior odds is then not 1, so the order of the
    // product o · p/(1 − p) · 1/prior_odds shows in the bits.
    QTest::addRow("%s/logodds prior=0.3", m)
        << QString(m) << QString("logodds") << false << true << 0.3;
  }
}

void TstFusedRuns::runsGiveTheFootprintPathsBits() {
  QFETCH(QString, model);
  QFETCH(QString, rule);
  QFETCH(bool, noEchoFree);
  QFETCH(bool, normalise);
  QFETCH(double, prior);
  const Dataset& d = workload();
  MapperSettings settings = rowSettings(model.toStdString(), rule.toStdString(), noEchoFree);
  if (settings.rule == "addition") settings.parameters.set("normalise", normalise ? 1.0 : 0.0);
  if (settings.rule == "logodds") settings.parameters.set("prior", prior);

  // The oracle: the footprint path, one reading at a time.
  Mapper oracle(d.ring, smallGrid(), settings);
  NullObserver observer;
  oracle.setObserver(&observer);
  {
    ScopedThreadCount one(1);
    QVERIFY(oracle.mapDataset(d));
  }
  QCOMPARE(oracle.readingsIntegrated(), d.readingCount());
  Mapper incremental(d.ring, smallGrid(), settings);
  for (const Scan& s : d.scans) incremental.integrate(s);
  QVERIFY(sameGrid(settings.rule, oracle.storage(), incremental.storage()));
  // The workload reaches the cases it is meant to: cells written in the grid's edge rows and
  // columns.
  const GridSpec g = smallGrid();
  bool bottom = false, top = false, left = false, right = false;
  for (int i = 0; i < g.width; ++i) {
    bottom = bottom || oracle.storage().observed(static_cast<std::size_t>(i));
    top = top || oracle.storage().observed(static_cast<std::size_t>((g.height - 1) * g.width + i));
  }
  for (int j = 0; j < g.height; ++j) {
    left = left || oracle.storage().observed(static_cast<std::size_t>(j * g.width));
    right = right || oracle.storage().observed(static_cast<std::size_t>(j * g.width + g.width - 1));
  }
  QVERIFY(bottom && top && left && right);

  // Rows in eight lanes built for AVX-512 and for AVX2, where the CPU has them (else the next
  // narrower again), and in the baseline's four.
  const struct {
    ConeLanes lanes;
    const char* name;
  } widths[] = {
      {ConeLanes::Avx512, "AVX-512"}, {ConeLanes::Avx2, "AVX2"}, {ConeLanes::Four, "four"}};
  for (const auto& width : widths) {
    const ConeLanes previous = testing::limitConeLanes(width.lanes);
    for (const unsigned threads : {1u, 2u, 3u}) {
      ScopedThreadCount count(threads);
      Mapper runs(d.ring, smallGrid(), settings);
      QVERIFY(runs.mapDataset(d));
      QCOMPARE(runs.readingsIntegrated(), d.readingCount());
      if (!sameGrid(settings.rule, oracle.storage(), runs.storage())) {
        testing::limitConeLanes(previous);
        QFAIL(qPrintable(
            QString("%1 threads, lanes up to %2: the grid differs from the footprint path's")
                .arg(threads)
                .arg(width.name)));
      }
    }
    testing::limitConeLanes(previous);
  }
}

void TstFusedRuns::himmAxisGivesTheFootprintPathsBits_data() {
  QTest::addColumn<QString>("rule");
  QTest::addColumn<bool>("noEchoFree");
  QTest::addColumn<double>("pHit");
  QTest::addColumn<double>("pMiss");
  QTest::addColumn<double>("prior");
  // OctoMap's hit and miss (0.7, 0.4: the model's defaults), and the parameters' limits: certain
  // evidence (p 1 and 0), where Bayes meets 0/0 in a cell already certain the other way and keeps
  // it, and log-odds clamps to its floor; a miss of p 0.5 says nothing.
  // With its own rule too, whose one-byte cells take a table look-up (UpdateRule::byteTransition):
  // on one thread fused with the trace, on several listed and folded.
  const char* const rules[] = {"bayes",   "bayes-recursive", "log",
                               "logodds", "dempster-shafer", "himm"};
  for (const char* r : rules) {
    for (const bool noEcho : {false, true}) {
      QTest::addRow("himm/%s%s", r, noEcho ? " no_echo=1" : "")
          << QString(r) << noEcho << 0.7 << 0.4 << 0.5;
    }
    QTest::addRow("himm/%s certain", r) << QString(r) << true << 1.0 << 0.0 << 0.5;
    QTest::addRow("himm/%s miss 0.5", r) << QString(r) << true << 0.9 << 0.5 << 0.5;
  }
  // Log-odds' prior other than 0.5 (see runsGiveTheFootprintPathsBits_data).
  QTest::addRow("himm/logodds prior=0.3") << QString("logodds") << false << 0.7 << 0.4 << 0.3;
}

void TstFusedRuns::himmAxisGivesTheFootprintPathsBits() {
  QFETCH(QString, rule);
  QFETCH(bool, noEchoFree);
  QFETCH(double, pHit);
  QFETCH(double, pMiss);
  QFETCH(double, prior);
  const Dataset& d = workload();
  MapperSettings settings = rowSettings("himm", rule.toStdString(), noEchoFree);
  settings.parameters.set("p_hit", pHit);
  settings.parameters.set("p_miss", pMiss);
  if (settings.rule == "logodds") settings.parameters.set("prior", prior);
  // The oracle, which also counts the footprints' cells and their echo cells (the one cell of a
  // footprint that carries p_hit, the last) in the grid.
  struct Counter final : FootprintObserver {
    std::size_t cells = 0, echoes = 0;
    double pHit = 0.0;
    void reset(std::size_t) override {}
    void observe(const Footprint& fp) override {
      cells += fp.cells.size();
      for (const CellEvidence& c : fp.cells) echoes += c.probability == static_cast<float>(pHit);
    }
  } counter;
  counter.pHit = pHit;
  Mapper oracle(d.ring, smallGrid(), settings);
  oracle.setObserver(&counter);
  {
    ScopedThreadCount one(1);
    QVERIFY(oracle.mapDataset(d));
  }
  // Not an empty comparison: the axes wrote cells, hundreds of them echoes.
  QVERIFY(counter.cells > 10000);
  QVERIFY(counter.echoes > 100);
  for (const unsigned threads : {1u, 2u, 3u}) {
    ScopedThreadCount count(threads);
    Mapper direct(d.ring, smallGrid(), settings);
    QVERIFY(direct.mapDataset(d));
    QCOMPARE(direct.readingsIntegrated(), d.readingCount());
    QVERIFY2(
        sameGrid(settings.rule, oracle.storage(), direct.storage()),
        qPrintable(QString("%1 threads: the grid differs from the footprint path's").arg(threads)));
  }
}

namespace {

// A one-row grid of `cells` cells of `rule` that hold every kind of value: certain occupied,
// certain empty, some evidence of either kind, unknown.
Grid preparedGrid(const UpdateRule& rule, std::uint32_t cells) {
  GridSpec spec;
  spec.width = static_cast<int>(cells);
  spec.height = 1;
  Grid g(spec, rule.layout());
  for (std::uint32_t i = 0; i < cells; ++i) {
    const float x = 0.2f + 0.025f * static_cast<float>(i % 24);
    Footprint f;
    switch (i % 5) {
      case 0:
        f.cells = {CellEvidence(i, 0.0, 1.0, 1.0)};
        break;
      case 1:
        f.cells = {CellEvidence(i, 1.0, 0.0, 0.0)};
        break;
      case 2:
        f.cells = {CellEvidence(i, x, 0.0, 0.5 - x / 2)};
        break;
      case 3:
        f.cells = {CellEvidence(i, 0.0, x, 0.5 + x / 2)};
        break;
      default:
        break;
    }
    rule.apply(f, g);
  }
  return g;
}

// A rule configured with its defaults, log-odds with a prior of 0.3 (1/prior_odds not 1) and
// addition without normalising (so that it has no totals).
std::unique_ptr<UpdateRule> configuredRule(const QString& name) {
  std::unique_ptr<UpdateRule> r = makeUpdateRule(name.toStdString());
  ParameterSet parameters(r->info().parameters);
  if (name == "logodds") parameters.set("prior", 0.3);
  if (name == "addition") parameters.set("normalise", 0.0);
  r->configure(parameters);
  return r;
}

// Appends `c` to one reading's runs (its three values; the run itself is the caller's) and to the
// footprint that is their oracle.
void appendCell(const CellEvidence& c, EvidenceRuns& runs, Footprint& footprint) {
  runs.empty.push_back(c.empty);
  runs.occupied.push_back(c.occupied);
  runs.probability.push_back(c.probability);
  footprint.cells.push_back(c);
}

// The values past the last run that the kernels' last lanes may read: kRunPadding (footprint.h),
// which the cone models and addition's deferral keep too.
void padRuns(EvidenceRuns& runs) {
  for (std::size_t k = 0; k < kRunPadding; ++k) {
    runs.empty.push_back(0.0f);
    runs.occupied.push_back(0.0f);
    runs.probability.push_back(0.5f);
  }
  // No capacity past the padding, so that AddressSanitizer sees a lane that reads further.
  runs.empty.shrink_to_fit();
  runs.occupied.shrink_to_fit();
  runs.probability.shrink_to_fit();
}

}  // namespace

void TstFusedRuns::uniformGivesApplysBits_data() {
  QTest::addColumn<QString>("rule");
  QTest::addColumn<float>("empty");
  QTest::addColumn<float>("occupied");
  QTest::addColumn<float>("probability");
  const float nan = std::numeric_limits<float>::quiet_NaN();
  // (pE, pO, P) as a model gives them (paper 001 §3.2: P = 0.5 + (pO − pE)/2), certain evidence,
  // both kinds at once (Dempster–Shafer's general case, which no model gives), and values outside
  // [0, 1] or NaN, which the rules clamp or pass on.
  const struct {
    const char* name;
    float empty, occupied, probability;
  } evidence[] = {{"nothing", 0.0f, 0.0f, 0.5f},          {"empty 0.6", 0.6f, 0.0f, 0.2f},
                  {"occupied 0.8", 0.0f, 0.8f, 0.9f},     {"both", 0.3f, 0.4f, 0.55f},
                  {"certain occupied", 0.0f, 1.0f, 1.0f}, {"certain empty", 1.0f, 0.0f, 0.0f},
                  {"out of range", -0.2f, 1.3f, 1.2f},    {"nan", nan, 0.0f, nan}};
  for (const char* r : {"bayes", "bayes-recursive", "log", "logodds", "dempster-shafer"}) {
    for (const auto& e : evidence) {
      QTest::addRow("%s %s", r, e.name) << QString(r) << e.empty << e.occupied << e.probability;
    }
  }
}

void TstFusedRuns::uniformGivesApplysBits() {
  QFETCH(QString, rule);
  QFETCH(float, empty);
  QFETCH(float, occupied);
  QFETCH(float, probability);
  const std::unique_ptr<UpdateRule> r = configuredRule(rule);
  constexpr std::uint32_t kCells = 24;
  auto prepared = [&] { return preparedGrid(*r, kCells); };
  const CellEvidence value(0, empty, occupied, probability);
  // Around the kernels' four lanes and Dempster–Shafer's eight: up to two groups of eight and a
  // padded tail.
  for (const std::size_t n : {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 15, 16, 17, 23}) {
    // n distinct cells out of order: 7 is prime to 24.
    std::vector<std::uint32_t> cells(n);
    Footprint f;
    for (std::size_t k = 0; k < n; ++k) {
      cells[k] = static_cast<std::uint32_t>((7 * k + 3) % kCells);
      CellEvidence c = value;
      c.cell = cells[k];
      f.cells.push_back(c);
    }
    Grid oracle = prepared(), uniform = prepared();
    r->apply(f, oracle);
    QVERIFY(r->applyUniform(value, cells, uniform));
    QVERIFY2(sameGrid(rule.toStdString(), oracle, uniform),
             qPrintable(QString("%1 cells: the grid differs from apply()'s").arg(n)));
  }
}

void TstFusedRuns::runsGiveApplysBits_data() {
  // The values taken in turn cell by cell, or one value for all the cells of a run, as a cone's
  // runs mostly have (Dempster–Shafer's masked groups of one kind of evidence).
  QTest::addColumn<QString>("rule");
  QTest::addColumn<bool>("valuePerRun");
  for (const char* r :
       {"addition", "bayes", "bayes-recursive", "log", "logodds", "dempster-shafer"}) {
    QTest::addRow("%s", r) << QString(r) << false;
    QTest::addRow("%s, a value per run", r) << QString(r) << true;
  }
}

void TstFusedRuns::runsGiveApplysBits() {
  // One reading's runs of every length around the kernels' four lanes and Dempster–Shafer's eight
  // (up to two groups of eight and a tail of seven), each cell with its own
  // evidence: of one kind as the cone models give it, of both kinds at once (Dempster–Shafer's
  // general case, which no model gives), none, certain, out of [0, 1] and NaN; against apply() of
  // the same cells in the same order.
  QFETCH(QString, rule);
  QFETCH(bool, valuePerRun);
  const std::unique_ptr<UpdateRule> r = configuredRule(rule);
  QVERIFY(!r->needsTotals());
  constexpr std::uint32_t kCells = 136;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const CellEvidence kinds[] = {CellEvidence(0, 0.6, 0.0, 0.2),  CellEvidence(0, 0.0, 0.8, 0.9),
                                CellEvidence(0, 0.3, 0.4, 0.55), CellEvidence(0, 0.0, 0.0, 0.5),
                                CellEvidence(0, 0.0, 1.0, 1.0),  CellEvidence(0, 1.0, 0.0, 0.0),
                                CellEvidence(0, 0.1, 0.0, 0.45), CellEvidence(0, -0.2, 1.3, 1.2),
                                CellEvidence(0, 0.0, 0.25, 0.6), CellEvidence(0, 0.5, 0.5, 0.5),
                                CellEvidence(0, nan, 0.0, nan)};
  constexpr std::size_t kKinds = sizeof kinds / sizeof kinds[0];
  // Five times, the cells one further along each time: every value then meets each of the five
  // kinds of cell preparedGrid() makes (certain evidence against a certain cell among them). With
  // the masked kernels and with the four lanes.
  for (const ConeLanes lanes : kRunLanes)
    for (std::uint32_t shift = 0; shift < 5; ++shift) {
      const LaneLimit limit(lanes);
      EvidenceRuns runs;
      Footprint footprint;
      std::uint32_t cell = 1 + shift;
      std::size_t v = 0;
      for (const int count : {1, 2, 3, 4, 5, 6, 7, 8, 9, 15, 16, 17, 19}) {
        const std::size_t run = runs.runs.size();
        runs.runs.push_back(EvidenceRuns::Run{cell, count, static_cast<std::uint32_t>(v)});
        for (int k = 0; k < count; ++k, ++v) {
          // 7 is prime to the 11 kinds; the 13 runs take each of them.
          CellEvidence c = kinds[((valuePerRun ? run : v) * 7) % kKinds];
          c.cell = cell + static_cast<std::uint32_t>(k);
          appendCell(c, runs, footprint);
        }
        cell += static_cast<std::uint32_t>(count) + 1;  // a cell left out between runs
      }
      QVERIFY(cell <= kCells);
      padRuns(runs);
      Grid oracle = preparedGrid(*r, kCells), viaRuns = preparedGrid(*r, kCells);
      r->apply(footprint, oracle);
      EvidenceRuns deferred;
      r->applyRuns(runs, viaRuns, &deferred);
      QVERIFY(deferred.runs.empty());
      QVERIFY2(sameGrid(rule.toStdString(), oracle, viaRuns),
               qPrintable(QString("shift %1, lanes %2: the grid differs from apply()'s")
                              .arg(shift)
                              .arg(static_cast<int>(lanes))));
    }
}

void TstFusedRuns::deferredRunsGiveApplysBits() {
  // Normalising addition (paper 001 §3.1): applyRuns() applies the empty evidence and defers each
  // run's span from its first to its last cell of non-zero occupied evidence; applyDeferred() then
  // scales by the reading's total. Against apply() of the same cells, which sums the whole
  // footprint itself. The runs hold spans that start and end inside, zeros within a span, whole
  // runs of zeros (one longer than the eight values tested at a time), ±0, a negative value
  // (which counts in the total), NaN (which counts 0), a denormal, runs of 1 to 19 cells, and a
  // span of 7 (its last cells in the kernel's tail lanes). One `deferred` serves all five
  // readings, cleared between them as the mapper clears it, so later ones meet the values left.
  const std::unique_ptr<UpdateRule> r = makeUpdateRule("addition");
  r->configure(ParameterSet(r->info().parameters));  // normalise = 1, the default
  QVERIFY(r->needsTotals());
  constexpr std::uint32_t kCells = 160;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<std::vector<float>> occupiedOf{
      {0.0f},
      {0.4f},
      {0.0f, 0.3f, 0.0f},
      {-0.0f, 0.0f, 0.25f, 0.0f, 0.5f, -0.0f},
      std::vector<float>(19, 0.0f),
      {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.6f, 0.0f},
      {0.2f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f,
       0.0f, 0.0f, 0.0f, 0.0f},
      {0.0f, -0.1f, 0.0f, 0.0f, 0.7f},
      {nan, 0.0f, 0.0f},
      {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.1f, 0.9f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f,
       0.0f, 0.0f, 0.0f, 0.0f},
      {0.3f, 0.0f, 0.0f, 1e-40f, 0.0f, 0.0f, 0.2f},
  };
  // The cells' values before: made by the rule without normalising, so that the occupied plane
  // holds values other than 0 and 1 (normalised, a one-cell footprint's evidence scales to 1).
  const std::unique_ptr<UpdateRule> preparing = configuredRule("addition");
  EvidenceRuns deferred;
  for (const ConeLanes lanes : kRunLanes)
    for (std::uint32_t shift = 0; shift < 5; ++shift) {
      const LaneLimit limit(lanes);
      EvidenceRuns runs;
      Footprint footprint;
      std::uint32_t cell = 1 + shift;
      std::size_t v = 0;
      std::size_t nonZero = 0;
      for (const std::vector<float>& occupied : occupiedOf) {
        const int count = static_cast<int>(occupied.size());
        runs.runs.push_back(EvidenceRuns::Run{cell, count, static_cast<std::uint32_t>(v)});
        for (int k = 0; k < count; ++k, ++v) {
          // The cone's empty evidence before the arc, none on it.
          const float o = occupied[static_cast<std::size_t>(k)];
          const bool arc = o != 0.0f;
          nonZero += arc ? 1 : 0;
          CellEvidence c(cell + static_cast<std::uint32_t>(k), arc ? 0.0 : 0.3, 0.0, 0.5);
          c.occupied = o;
          appendCell(c, runs, footprint);
        }
        cell += static_cast<std::uint32_t>(count) + 1;
      }
      QVERIFY(cell <= kCells);
      padRuns(runs);
      Grid oracle = preparedGrid(*preparing, kCells), viaRuns = preparedGrid(*preparing, kCells);
      r->apply(footprint, oracle);
      deferred.clear();
      r->applyRuns(runs, viaRuns, &deferred);
      // The spans, counted by hand from occupiedOf: runs 2, 3, 4, 6, 7, 8, 9, 10 and 11 have one,
      // of 1, 1, 3, 1, 1, 4, 1, 2 and 7 cells (21); the 14 values other than ±0 (NaN, −0.1 and the
      // denormal among them) lie in them, with 7 zeros between.
      QCOMPARE(deferred.runs.size(), std::size_t{9});
      std::size_t deferredCells = 0;
      for (const EvidenceRuns::Run& run : deferred.runs)
        deferredCells += static_cast<std::size_t>(run.count);
      QCOMPARE(deferredCells, std::size_t{21});
      QCOMPARE(nonZero, std::size_t{14});
      QCOMPARE(occupiedFixedPoint(deferred), occupiedFixedPoint(footprint));
      r->applyDeferred(deferred, FootprintTotals{occupiedFixedPoint(deferred)}, viaRuns);
      QVERIFY2(sameGrid("addition", oracle, viaRuns),
               qPrintable(QString("shift %1, lanes %2: the grid differs from apply()'s")
                              .arg(shift)
                              .arg(static_cast<int>(lanes))));
    }
}

void TstFusedRuns::occupiedTotalAtEveryWidth() {
  // A reading's occupied total from its runs (occupiedFixedPoint, in eight masked lanes where the
  // CPU has AVX-512), on values at the conversion's edges: each share is the value times 2^40
  // truncated, NaN 0, clamped to ±2^22 first; the sum is modulo 2^64.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float values[] = {nan, 0.5f, 1e30f, -1e30f, -0.0f, 1e-40f, 0.25f, -0.5f, 3.0f};
  // By hand, one of each: 0 + 2^39 + 2^62 − 2^62 + 0 + 0 (1e-40 × 2^40 < 1) + 2^38 − 2^39 +
  // 3 × 2^40 = 13 × 2^38. Runs of 1, 8, 9, 17 and 2 cells (37 = 4 × 9 + 1) hold each value four
  // times and NaN once more: 52 × 2^38, the four 2^62 having wrapped the sum past 2^64 on the way.
  // (An odd count of NaN: a NaN converted without the check gives 2^63, and an even count of those
  // would cancel modulo 2^64.)
  constexpr std::int64_t kExpected = std::int64_t{52} << 38;
  EvidenceRuns runs;
  std::size_t v = 0;
  std::uint32_t cell = 0;
  for (const int count : {1, 8, 9, 17, 2}) {
    runs.runs.push_back(EvidenceRuns::Run{cell, count, static_cast<std::uint32_t>(v)});
    for (int k = 0; k < count; ++k, ++v) runs.occupied.push_back(values[v % 9]);
    cell += static_cast<std::uint32_t>(count) + 3;
  }
  QCOMPARE(v, std::size_t{37});
  runs.empty.assign(runs.occupied.size(), 0.0f);
  runs.probability.assign(runs.occupied.size(), 0.5f);
  padRuns(runs);
  for (const ConeLanes lanes : kRunLanes) {
    const LaneLimit limit(lanes);
    QCOMPARE(occupiedFixedPoint(runs), kExpected);
  }
  // And the scalar share of each, which the footprint path sums.
  QCOMPARE(occupiedFixedPoint(1e30f), std::int64_t{1} << 62);
  QCOMPARE(occupiedFixedPoint(-1e30f), -(std::int64_t{1} << 62));
  QCOMPARE(occupiedFixedPoint(1e-40f), std::int64_t{0});
}

void TstFusedRuns::tallGridThreadsPassOverFarBeams_data() {
  QTest::addColumn<QString>("model");
  QTest::addColumn<QString>("rule");
  QTest::addColumn<bool>("noEchoFree");
  // Rules without totals and normalising addition, whose threads both take bands; with no-echo
  // updates on too, whose cones reach the maximum range, as far as any beam of the model can.
  for (const char* m : {"hpf", "konolige", "murphy", "parameterized"}) {
    for (const char* r : {"bayes", "log", "dempster-shafer", "addition"}) {
      for (const bool noEcho : {false, true}) {
        QTest::addRow("%s/%s%s", m, r, noEcho ? " no_echo=1" : "")
            << QString(m) << QString(r) << noEcho;
      }
    }
  }
}

void TstFusedRuns::tallGridThreadsPassOverFarBeams() {
  QFETCH(QString, model);
  QFETCH(QString, rule);
  QFETCH(bool, noEchoFree);
  static const Dataset d = tallGenerated();
  const MapperSettings settings = rowSettings(model.toStdString(), rule.toStdString(), noEchoFree);
  const QString difference = threadsAgainstFootprintPath(d, tallGrid(), settings);
  QVERIFY2(difference.isEmpty(), qPrintable(difference));
}

void TstFusedRuns::additionInChunksKeepsTheBits_data() {
  QTest::addColumn<QString>("model");
  QTest::addColumn<bool>("noEchoFree");
  for (const char* m : {"hpf", "konolige", "murphy", "parameterized"}) {
    for (const bool noEcho : {false, true})
      QTest::addRow("%s%s", m, noEcho ? " no_echo=1" : "") << QString(m) << noEcho;
  }
}

void TstFusedRuns::additionInChunksKeepsTheBits() {
  // Normalising addition on several threads maps kTotalsChunk readings at a time, each chunk with
  // bands of its own (Mapper::integrateBands). Two chunks and a part of a third: the first in the
  // grid's lower half, the second anywhere, the rest in the upper half, so that the chunks' bands
  // differ and many cells are written in each of them.
  QFETCH(QString, model);
  QFETCH(bool, noEchoFree);
  const int perChunk = static_cast<int>(kTotalsChunk / 16);  // scans of the 16-sonar ring
  const GridSpec g = smallGrid();
  const double x0 = g.origin.x() + 0.3, x1 = g.origin.x() + g.widthMetres() - 0.3;
  const double y0 = g.origin.y() + 0.3, y1 = g.origin.y() + g.heightMetres() - 0.3;
  const double mid = 0.5 * (y0 + y1);
  static const Dataset d = ringLog(
      "chunks", 4242,
      [&](int k, Uniform& uniform) {
        const double lo = k < perChunk || k >= 2 * perChunk ? mid : y0;
        const double hi = k < 2 * perChunk ? mid : y1;
        const double x = uniform(x0, x1), y = k < perChunk ? uniform(y0, mid) : uniform(lo, hi);
        return Pose2D(x, y, uniform(-3.14, 3.14));
      },
      [](int k, int sonar) { return (k * 16 + sonar) % 7 == 0; }, 2 * perChunk + 40);
  QVERIFY(d.readingCount() > 2 * kTotalsChunk);
  const MapperSettings settings = rowSettings(model.toStdString(), "addition", noEchoFree);
  QCOMPARE(settings.parameters.get("normalise"), 1.0);  // the rule's default: totals
  const QString difference = threadsAgainstFootprintPath(d, g, settings);
  QVERIFY2(difference.isEmpty(), qPrintable(difference));
}

QTEST_APPLESS_MAIN(TstFusedRuns)
#include "tst_fused_runs.moc"
