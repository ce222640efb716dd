// SPDX-License-Identifier: BSD-3-Clause
// Inverse sensor models at chosen (δ, θ) points. Every expected value is worked by hand from the
// formula the comment names (the papers, read as docs/models.md says).

#include <QtTest>
#include <cmath>
#include <cstring>
#include <numbers>
#include <random>
#include <type_traits>

#include "sonargrid/engine/sensor_model.h"
#include "sonargrid/engine/update_rule.h"
#include "sonargrid/models/cone_raster.h"
#include "sonargrid/simd/lanes.h"
#include "sonargrid/testing/registry_hooks.h"

using namespace sg;

namespace {
constexpr double kNoEcho = std::numeric_limits<double>::infinity();
constexpr double kTol = 1e-4;

std::unique_ptr<SensorModel> model(const char* name,
                                   std::initializer_list<std::pair<const char*, double>> set = {}) {
  auto m = makeSensorModel(name);
  ParameterSet p(m->info().parameters);
  for (const auto& [k, v] : set) p.set(k, v);
  m->configure(p);
  return m;
}
}  // namespace

class TstModels : public QObject {
  Q_OBJECT

 private slots:
  void hpf_data();
  void hpf();
  void murphy_data();
  void murphy();
  void parameterized_data();
  void parameterized();
  void konolige_data();
  void konolige();
  void konoligeFlatEndIsExact();
  void himmAxis();
  void evidenceAndProbabilityAgree();
  void footprintMatchesEvaluate();
  void footprintRowsAreItsRows();
  void spansInLanesAreTheRowsSpans();
  void reachBoundsTheFootprint();
  void declarationsAreComplete();
  void preferredRulesArePapersPairings_data();
  void preferredRulesArePapersPairings();
};

// Columns: delta (m), theta (deg), range (m or inf), expected region, pE, pO, P(occ).
static void addColumns() {
  QTest::addColumn<double>("delta");
  QTest::addColumn<double>("thetaDeg");
  QTest::addColumn<double>("range");
  QTest::addColumn<int>("region");
  QTest::addColumn<double>("pE");
  QTest::addColumn<double>("pO");
  QTest::addColumn<double>("p");
}

static void check(const SensorModel& m, double maxRange = 5.0) {
  QFETCH(double, delta);
  QFETCH(double, thetaDeg);
  QFETCH(double, range);
  QFETCH(int, region);
  QFETCH(double, pE);
  QFETCH(double, pO);
  QFETCH(double, p);
  const ModelValue v = m.evaluate(delta, degToRad(thetaDeg), range, maxRange);
  QCOMPARE(static_cast<int>(v.region), region);
  // Every row compares its three numbers, Outside rows too: where a model says nothing, pE and pO
  // are 0 and P is 0.5 (sensor_model.h, ModelValue), so a model that leaked evidence past its
  // cone would fail here.
  QVERIFY2(std::abs(v.empty - pE) < kTol, qPrintable(QString("pE %1 vs %2").arg(v.empty).arg(pE)));
  QVERIFY2(std::abs(v.occupied - pO) < kTol,
           qPrintable(QString("pO %1 vs %2").arg(v.occupied).arg(pO)));
  QVERIFY2(std::abs(v.probability - p) < kTol,
           qPrintable(QString("P %1 vs %2").arg(v.probability).arg(p)));
}

constexpr int kOut = static_cast<int>(BeamRegion::Outside);
constexpr int kOcc = static_cast<int>(BeamRegion::Occupied);
constexpr int kEmp = static_cast<int>(BeamRegion::Empty);

void TstModels::hpf_data() {
  addColumns();
  // ε = 0.1 m, ω = 25°, R_min = 0, reading R = 2 m. Paper 000 eqs 1–6; P = 0.5 + (pO − pE)/2
  // (paper 001 §3.2).
  QTest::newRow("peak") << 2.0 << 0.0 << 2.0 << kOcc << 0.0 << 1.0 << 1.0;
  // Or = 1 − (0.05/0.1)² = 0.75
  QTest::newRow("half eps") << 2.05 << 0.0 << 2.0 << kOcc << 0.0 << 0.75 << 0.875;
  // Oa = 1 − (2·6.25/25)² = 0.75
  QTest::newRow("quarter aperture") << 2.0 << 6.25 << 2.0 << kOcc << 0.0 << 0.75 << 0.875;
  // Er = 1 − (0.95/1.9)² = 0.75
  QTest::newRow("empty mid") << 0.95 << 0.0 << 2.0 << kEmp << 0.75 << 0.0 << 0.125;
  // 0.75 · 0.75 = 0.5625; P = 0.5 − 0.28125
  QTest::newRow("empty off axis") << 0.95 << 6.25 << 2.0 << kEmp << 0.5625 << 0.0 << 0.21875;
  // Outside: θ = 13° > ω/2 = 12.5°, and δ = 2.11 m > R + ε = 2.1 m: no information.
  QTest::newRow("outside cone") << 1.0 << 13.0 << 2.0 << kOut << 0.0 << 0.0 << 0.5;
  QTest::newRow("beyond R+eps") << 2.11 << 0.0 << 2.0 << kOut << 0.0 << 0.0 << 0.5;
  // No echo: empty region to R_max = 5: Er = 1 − (2.5/5)² = 0.75
  QTest::newRow("no echo") << 2.5 << 0.0 << kNoEcho << kEmp << 0.75 << 0.0 << 0.125;
}

void TstModels::hpf() {
  check(*model("hpf", {{"no_echo", 1.0}}));
}

void TstModels::murphy_data() {
  addColumns();
  // R = 10, β = 15°, tolerance 0.5, Max_occ = 0.98, reading s = 6 (paper 002 eqs 1–4).
  // Region I, r = 6, α = 5°: ((10−6)/10 + (15−5)/15)/2 · 0.98 = 0.533333 · 0.98 = 0.522667 (issue
  // 2).
  QTest::newRow("issue example") << 6.0 << 5.0 << 6.0 << kOcc << 0.0 << 0.522667 << 0.522667;
  // Region I edge, r = 6.4, α = 15°: (0.36 + 0)/2 · 0.98 = 0.1764 — below 0.5, the flaw paper 002
  // §3.2 shows.
  QTest::newRow("region I corner") << 6.4 << 15.0 << 6.0 << kOcc << 0.0 << 0.1764 << 0.1764;
  // Region II, r = 3, α = 0: P(s|Emp) = (0.7 + 1)/2 = 0.85, P(s|Occ) = 0.15.
  QTest::newRow("region II axis") << 3.0 << 0.0 << 6.0 << kEmp << 0.85 << 0.0 << 0.15;
  // Region II corner, r = 3, α = 15°: P(s|Emp) = 0.35, P(s|Occ) = 0.65 (paper 002 §3.2's red
  // cells).
  QTest::newRow("region II corner") << 3.0 << 15.0 << 6.0 << kEmp << 0.35 << 0.0 << 0.65;
  // r = 0.1: P(s|Emp) = (0.99 + 1)/2 = 0.995 → P(s|Occ) 0.005 clamped to 1 − 0.98; pE clamped to
  // 0.98.
  QTest::newRow("clamped") << 0.1 << 0.0 << 6.0 << kEmp << 0.98 << 0.0 << 0.02;
  // Region III (r = 7 > s + tolerance = 6.5) and α = 16° > β = 15°: no information (paper 002
  // §3.2: Region III is unknown).
  QTest::newRow("region III") << 7.0 << 0.0 << 6.0 << kOut << 0.0 << 0.0 << 0.5;
  QTest::newRow("outside cone") << 3.0 << 16.0 << 6.0 << kOut << 0.0 << 0.0 << 0.5;
}

void TstModels::murphy() {
  check(*model("murphy", {{"max_range", 10.0},
                          {"beta", 15.0},
                          {"tolerance", 0.5},
                          {"max_occupied", 0.98},
                          {"no_echo", 1.0}}),
        10.0);
}

void TstModels::parameterized_data() {
  addColumns();
  // P1 = 0.02, P2 = 0.15, P3 = 0.5 m, P4 = 0.98, P5 = 15°, reading s = 3 (paper 002 §4, eq 7).
  // pE, pO = the distance of P from 0.5, doubled.
  QTest::newRow("sensor") << 0.0 << 0.0 << 3.0 << kEmp << 0.96 << 0.0 << 0.02;
  // Region II halfway to s − P3 = 2.5: 0.02 + (0.35 − 0.02)/2 = 0.185
  QTest::newRow("region II mid") << 1.25 << 0.0 << 3.0 << kEmp << 0.63 << 0.0 << 0.185;
  // Region I starts at 0.5 + P2 = 0.65
  QTest::newRow("region I start") << 2.5 << 0.0 << 3.0 << kOcc << 0.0 << 0.3 << 0.65;
  QTest::newRow("peak") << 3.0 << 0.0 << 3.0 << kOcc << 0.0 << 0.96 << 0.98;
  // 0.98 − 0.33/2 = 0.815
  QTest::newRow("tent down") << 3.25 << 0.0 << 3.0 << kOcc << 0.0 << 0.63 << 0.815;
  // eq 7: (15 − 7.5)/15 · (0.98 − 0.5) + 0.5 = 0.74
  QTest::newRow("off axis peak") << 3.0 << 7.5 << 3.0 << kOcc << 0.0 << 0.48 << 0.74;
  // eq 7: 0.5 · (0.185 − 0.5) + 0.5 = 0.3425
  QTest::newRow("off axis empty") << 1.25 << 7.5 << 3.0 << kEmp << 0.315 << 0.0 << 0.3425;
  QTest::newRow("edge of focus") << 3.0 << 15.0 << 3.0 << kOcc << 0.0 << 0.0 << 0.5;
  // δ = 3.6 m > s + P3 = 3.5 m: past the tent, no information.
  QTest::newRow("beyond s+P3") << 3.6 << 0.0 << 3.0 << kOut << 0.0 << 0.0 << 0.5;
  // No echo: Region II from P1 to 0.35 over the 5 m maximum range: 0.02 + 0.33 · 2.5/5 = 0.185
  QTest::newRow("no echo") << 2.5 << 0.0 << kNoEcho << kEmp << 0.63 << 0.0 << 0.185;
}

void TstModels::parameterized() {
  check(*model(
      "parameterized",
      {{"p1", 0.02}, {"p2", 0.15}, {"p3", 0.5}, {"p4", 0.98}, {"p5", 15.0}, {"no_echo", 1.0}}));
}

void TstModels::konolige_data() {
  addColumns();
  // Paper 001 §2.2 defaults: F = 0.05, a(r) = 0.6(1 − min(1, 0.4 r)), d(r) = 0.01 + 0.015 r,
  // σθ = ω/2 = 12.5°. λ = g φ(z)/(d F) + 1 − g Φ(z), z = (D − r)/d, P = λ/(1 + λ) (model comment).
  // Reading D = 1 m, cell at r = 1, θ = 0: g = 0.36, d = 0.025, φ(0) = 0.398942, Φ(0) = 0.5:
  // λ = 0.143619/0.00125 + 0.82 = 115.715 → P = 0.991432.
  QTest::newRow("at reading") << 1.0 << 0.0 << 1.0 << kOcc << 0.0 << 0.982864 << 0.991432;
  // r = 0.5, θ = 0: g = 0.48, z = 28.6 so λ = 1 − g = 0.52 → P = 0.342105.
  QTest::newRow("free axis") << 0.5 << 0.0 << 1.0 << kEmp << 0.315789 << 0.0 << 0.342105;
  // θ = σ: g = 0.48 · e^−½ = 0.291135 → λ = 0.708865 → P = 0.414816.
  QTest::newRow("free at sigma") << 0.5 << 12.5 << 1.0 << kEmp << 0.170368 << 0.0 << 0.414816;
  // r = 1.02: a = 0.3552, d = 0.0253, z = −0.790514 → λ = 82.8824 → P = 0.988079.
  QTest::newRow("past reading") << 1.02 << 0.0 << 1.0 << kOcc << 0.0 << 0.976158 << 0.988079;
  // θ = 6°: g = 0.36 · exp(−(6/12.5)²/2) = 0.320624 → λ = 103.233 → P = 0.990406.
  QTest::newRow("off axis") << 1.0 << 6.0 << 1.0 << kOcc << 0.0 << 0.980812 << 0.990406;
  // No echo at r = 1: λ = 1 − 0.36 = 0.64 → P = 0.390244.
  QTest::newRow("no echo") << 1.0 << 0.0 << kNoEcho << kEmp << 0.219512 << 0.0 << 0.390244;
  // No echo at r = 2, θ = 10°: g = 0.12 · exp(−0.32) = 0.087138 → P = 0.477223.
  QTest::newRow("no echo far") << 2.0 << 10.0 << kNoEcho << kEmp << 0.045554 << 0.0 << 0.477223;
  // a(r) = 0 from r = 2.5 m: no information.
  QTest::newRow("past detection") << 2.6 << 0.0 << kNoEcho << kOut << 0.0 << 0.0 << 0.5;
  // θ = 13° > ω/2 = 12.5°: outside the cone, no information.
  QTest::newRow("outside cone") << 1.0 << 13.0 << 1.0 << kOut << 0.0 << 0.0 << 0.5;
}

void TstModels::konolige() {
  check(*model("konolige", {{"no_echo", 1.0}}));
}

void TstModels::konoligeFlatEndIsExact() {
  // Where a group of lanes lies well short of the echo (z = (D − r)/d >= 8), Konolige's float
  // lanes take λ = 1 − g instead of the whole formula, which gives the same bits there
  // (konolige.cpp, KonoligeShape::allAtFlatEnd). Compared with the whole formula everywhere
  // (testing::konoligeFlatEnd(false)): footprints (four lanes) and evidence runs (four lanes, or
  // eight with AVX2 or AVX-512 where the CPU has them), bit for bit, at the paper's values and at
  // the sliders' limits that make g φ/(d F) largest (d0 = F = 0.001, a0 = 1) or d widest.
  GridSpec grid;
  grid.cellSize = 0.05;
  grid.width = 240;
  grid.height = 200;
  struct Restore {
    ConeLanes lanes = testing::limitConeLanes(ConeLanes::Avx512);
    ~Restore() {
      testing::limitConeLanes(lanes);
      testing::konoligeFlatEnd(true);
    }
  } restore;
  const std::vector<std::vector<std::pair<const char*, double>>> settings = {
      {},
      {{"range_sd0", 0.001},
       {"range_sd1", 0.0},
       {"false_rate", 0.001},
       {"attenuation", 1.0},
       {"attenuation_slope", 0.0}},
      {{"range_sd0", 0.5}, {"range_sd1", 0.19}, {"omega", 90.0}},
      {{"attenuation", 1.0}, {"attenuation_slope", 0.2}, {"omega", 5.0}}};
  std::size_t compared = 0;
  for (const auto& set : settings) {
    auto m = makeSensorModel("konolige");
    ParameterSet p(m->info().parameters);
    for (const auto& [k, v] : set) p.set(k, v);
    m->configure(p);
    const double maxRange = 5.0;
    const auto tables = BeamTables::shared(grid.cellSize, m->reach(maxRange));
    for (const ConeLanes lanes : {ConeLanes::Four, ConeLanes::Avx2, ConeLanes::Avx512}) {
      testing::limitConeLanes(lanes);
      for (const double heading : {0.0, 0.7, 1.5707963, 2.9, -2.2, -0.4}) {
        for (const double range : {0.7, 2.03, 3.41, 4.9}) {
          Beam beam;
          beam.sensor = Pose2D(6.013 + 0.3 * heading, 5.031 - 0.1 * heading, heading);
          beam.range = range;
          beam.maxRange = maxRange;
          Footprint fp[2];
          EvidenceRuns runs[2];
          for (const bool flatEnd : {true, false}) {
            testing::konoligeFlatEnd(flatEnd);
            m->footprint(beam, grid, *tables, fp[flatEnd]);
            QVERIFY(m->evidenceRuns(beam, grid, *tables, RowWindow{}, runs[flatEnd]));
          }
          const QByteArray where = "setting " + QByteArray::number(&set - settings.data()) +
                                   " lanes " + QByteArray::number(static_cast<int>(lanes)) +
                                   " heading " + QByteArray::number(heading) + " range " +
                                   QByteArray::number(range);
          QVERIFY2(!fp[0].cells.empty() && fp[0].cells.size() == fp[1].cells.size(), where);
          QVERIFY2(std::memcmp(fp[0].cells.data(), fp[1].cells.data(),
                               fp[0].cells.size() * sizeof(CellEvidence)) == 0,
                   where);
          QVERIFY2(runs[0].runs.size() == runs[1].runs.size(), where);
          for (std::size_t i = 0; i < runs[0].runs.size(); ++i) {
            const EvidenceRuns::Run a = runs[0].runs[i], b = runs[1].runs[i];
            QVERIFY2(a.cell == b.cell && a.count == b.count && a.first == b.first, where);
            const auto bytes = static_cast<std::size_t>(a.count) * sizeof(float);
            QVERIFY2(std::memcmp(&runs[0].empty[a.first], &runs[1].empty[a.first], bytes) == 0 &&
                         std::memcmp(&runs[0].occupied[a.first], &runs[1].occupied[a.first],
                                     bytes) == 0 &&
                         std::memcmp(&runs[0].probability[a.first], &runs[1].probability[a.first],
                                     bytes) == 0,
                     where + " run " + QByteArray::number(static_cast<qulonglong>(i)));
          }
          compared += fp[0].cells.size();
        }
      }
    }
  }
  QVERIFY(compared > 10000);
}

void TstModels::himmAxis() {
  // Paper 000 §2.2: on a 10 × 3 grid of 0.1 m cells, a sensor at the centre of cell (0, 1) facing
  // +x with a 0.52 m echo ends in cell (5, 1) (x = 0.57): cells 0..4 get I⁻, cell 5 gets I⁺.
  auto m = model("himm");
  GridSpec grid;
  grid.cellSize = 0.1;
  grid.width = 10;
  grid.height = 3;
  const auto tables = BeamTables::shared(grid.cellSize, 1.0);
  Footprint fp;
  Beam beam;
  beam.sensor = Pose2D(0.05, 0.15, 0.0);
  beam.range = 0.52;
  beam.maxRange = 5.0;
  m->footprint(beam, grid, *tables, fp);
  QCOMPARE(fp.cells.size(), std::size_t{6});
  for (std::size_t i = 0; i < 5; ++i) {
    QCOMPARE(fp.cells[i].cell, static_cast<std::uint32_t>(10 + i));
    QVERIFY(fp.cells[i].empty > fp.cells[i].occupied);
  }
  QCOMPARE(fp.cells[5].cell, std::uint32_t{15});
  QVERIFY(fp.cells[5].occupied > fp.cells[5].empty);
  // OctoMap's hit 0.7 and miss 0.4 are what the probabilistic rules read.
  QVERIFY(std::abs(fp.cells[5].probability - 0.7) < 1e-6);
  QVERIFY(std::abs(fp.cells[0].probability - 0.4) < 1e-6);

  // A diagonal beam: from (0.05, 0.05) at 45° for 0.25 m ends at (0.227, 0.227), cell (2, 2); the
  // traversal steps one axis at a time, so it passes 2·2 + 1 = 5 cells, each once.
  fp.clear();
  beam.sensor = Pose2D(0.05, 0.05, std::numbers::pi / 4);
  beam.range = 0.25;
  m->footprint(beam, grid, *tables, fp);
  QCOMPARE(fp.cells.size(), std::size_t{5});
  QCOMPARE(fp.cells.back().cell, std::uint32_t{2 * 10 + 2});

  // No echo with no_echo = 0 (the default): nothing.
  auto quiet = model("himm");
  fp.clear();
  beam.range = kNoEcho;
  quiet->footprint(beam, grid, *tables, fp);
  QVERIFY(fp.cells.empty());
}

void TstModels::evidenceAndProbabilityAgree() {
  // For every model except Murphy (whose evidence is its own belief mass, see murphy.cpp), the
  // probability and the evidence obey P = 0.5 + (pO − pE)/2 at every point of the cone.
  for (const std::string name : {"hpf", "konolige", "parameterized"}) {
    auto m = model(name.c_str(), {{"no_echo", 1.0}});
    for (double d = 0.05; d < 3.5; d += 0.173) {
      for (double t = -20.0; t <= 20.0; t += 2.5) {
        for (const double range : {2.0, kNoEcho}) {
          const ModelValue v = m->evaluate(d, degToRad(t), range, 5.0);
          if (v.region == BeamRegion::Outside) continue;
          QVERIFY(v.empty >= 0.0 && v.empty <= 1.0 && v.occupied >= 0.0 && v.occupied <= 1.0);
          QVERIFY(std::abs(v.probability - (0.5 + 0.5 * (v.occupied - v.empty))) < 1e-9);
        }
      }
    }
  }
}

void TstModels::footprintMatchesEvaluate() {
  // A cone model's footprint is its evaluate() at each cell's table distance and angle, computed
  // in single precision a row at a time (cone_model.h): the same cells, in the same order, with the
  // same values to within float rounding. 1e-5 bounds it: the angle off the axis is kept to ~1e-8
  // rad (cone_model.h) and the steepest angular slope is below 10 per radian (HPF at ω = 25°);
  // values near 1 round to 6e-8, and Konolige's λ multiplies φ by 1/(d F) ≤ 500, so φ's float
  // rounding (3e-8) moves λ by 1e-5 and its values, (λ ∓ 1)/(λ + 1), by less.
  GridSpec grid;
  grid.cellSize = 0.05;
  grid.width = 240;
  grid.height = 200;
  for (const std::string name : {"hpf", "konolige", "murphy", "parameterized"}) {
    auto m = model(name.c_str(), {{"no_echo", 1.0}});
    const double maxRange = 5.0;
    const auto tables = BeamTables::shared(grid.cellSize, m->reach(maxRange));
    std::size_t compared = 0;
    for (const double heading : {0.0, 0.7, 1.5707963, 2.9, 3.1415926, -3.1415926, -2.2, -0.4}) {
      for (const double range : {0.7, 2.03, 3.41, kNoEcho}) {
        Beam beam;
        beam.sensor = Pose2D(6.013 + 0.3 * heading, 5.031 - 0.1 * heading, heading);
        beam.range = range;
        beam.maxRange = maxRange;
        Footprint fp;
        m->footprint(beam, grid, *tables, fp);
        // Every cell the widest cone of this model could touch (half-angles are at most 45°).
        std::vector<CellEvidence> want;
        forEachConeCell(beam.sensor, m->reach(maxRange), degToRad(45.0), grid, *tables,
                        [&](std::uint32_t cell, double delta, double theta) {
                          const ModelValue v = m->evaluate(delta, theta, range, maxRange);
                          if (v.region != BeamRegion::Outside)
                            want.emplace_back(cell, v.empty, v.occupied, v.probability);
                        });
        const QByteArray where = QByteArray::fromStdString(name) + " heading " +
                                 QByteArray::number(heading) + " range " +
                                 QByteArray::number(range);
        QVERIFY2(fp.cells.size() == want.size(), where);
        for (std::size_t i = 0; i < want.size(); ++i) {
          const CellEvidence& a = fp.cells[i];
          const CellEvidence& b = want[i];
          QVERIFY2(a.cell == b.cell, where);
          QVERIFY2(std::abs(a.empty - b.empty) <= 1e-5 &&
                       std::abs(a.occupied - b.occupied) <= 1e-5 &&
                       std::abs(a.probability - b.probability) <= 1e-5,
                   where + " cell " + QByteArray::number(a.cell));
        }
        compared += want.size();
      }
    }
    QVERIFY(compared > 10000);
  }
}

void TstModels::footprintRowsAreItsRows() {
  // footprintRows() is footprint() with only the window's rows kept, in the same order, with the
  // same values bit for bit (the mapper's threads each take a window and must together write what
  // one thread writes). Windows: a block of rows, and bands that share out the grid's rows two and
  // three ways, as the mapper's threads do; the cone models rasterise only those rows, HIMM keeps
  // them from its whole footprint. The bands of one split cover every cell exactly once.
  GridSpec grid;
  grid.cellSize = 0.05;
  grid.width = 240;
  grid.height = 200;
  for (const std::string name : {"hpf", "konolige", "murphy", "parameterized", "himm"}) {
    auto m = model(name.c_str(), {{"no_echo", 1.0}});
    QCOMPARE(m->rasterisesRows(), name != "himm");
    const double maxRange = 5.0;
    const auto tables = BeamTables::shared(grid.cellSize, m->reach(maxRange));
    for (const double heading : {0.0, 1.5707963, 2.9, -2.2}) {
      for (const double range : {0.7, 3.41, kNoEcho}) {
        Beam beam;
        beam.sensor = Pose2D(6.013 + 0.3 * heading, 5.031 - 0.1 * heading, heading);
        beam.range = range;
        beam.maxRange = maxRange;
        Footprint whole;
        m->footprint(beam, grid, *tables, whole);
        QVERIFY(!whole.cells.empty());
        const QByteArray where = QByteArray::fromStdString(name) + " heading " +
                                 QByteArray::number(heading) + " range " +
                                 QByteArray::number(range);
        // Whether the window's part is exactly the whole's cells in those rows; and its size.
        auto part = [&](const RowWindow& w) {
          Footprint got;
          m->footprintRows(beam, grid, *tables, w, got);
          std::vector<CellEvidence> want;
          for (const CellEvidence& c : whole.cells)
            if (w.contains(static_cast<int>(c.cell) / grid.width)) want.push_back(c);
          // (memcmp of an empty range would still be given a null pointer.)
          const bool same = got.cells.size() == want.size() &&
                            (want.empty() || std::memcmp(got.cells.data(), want.data(),
                                                         want.size() * sizeof(CellEvidence)) == 0);
          return std::pair{same, got.cells.size()};
        };
        QVERIFY2(part(RowWindow{95, 110}).first, where);
        // Split at the beam's own rows (about 100) and at either side of them.
        for (const std::vector<int>& ends : {std::vector<int>{101}, std::vector<int>{60, 137}}) {
          std::size_t covered = 0;
          int begin = 0;
          for (std::size_t k = 0; k <= ends.size(); ++k) {
            const int end = k < ends.size() ? ends[k] : grid.height;
            const auto [same, size] = part(RowWindow{begin, end});
            QVERIFY2(same, where + " band " + QByteArray::number(begin));
            covered += size;
            begin = end;
          }
          QCOMPARE(covered, whole.cells.size());
        }
      }
    }
  }
  // The window's rule by hand: rows 8–15 of a band [8, 16).
  const RowWindow w{8, 16};
  QVERIFY(!w.contains(7) && w.contains(8) && w.contains(15) && !w.contains(16));
  // forEachRow() lists the rows contains() accepts, by hand: of rows 5–26 those 8–15, of rows
  // 12–13 both, of rows −3–9 rows 8 and 9 (none below 0 in any window), of rows 16–23 none.
  auto listed = [](const RowWindow& window, int lo, int hi) {
    std::vector<int> rows;
    window.forEachRow(lo, hi, [&](int row) { rows.push_back(row); });
    return rows;
  };
  QCOMPARE(listed(w, 5, 26), (std::vector<int>{8, 9, 10, 11, 12, 13, 14, 15}));
  QCOMPARE(listed(w, 12, 13), (std::vector<int>{12, 13}));
  QCOMPARE(listed(w, -3, 9), (std::vector<int>{8, 9}));
  QCOMPARE(listed(RowWindow{}, -3, 2), (std::vector<int>{0, 1, 2}));
  QVERIFY(listed(w, 16, 23).empty());
}

void TstModels::spansInLanesAreTheRowsSpans() {
  // forEachConeRow finds its rows' spans four at a time in lanes in the AVX2 and AVX-512 builds of
  // the cone models (kSpanLanes); the spans must be those of the one-row loop. The spans bound the
  // cells that the per-cell test then picks, so a span wider than the loop's would leave the rows
  // the same: the cells the spans hold in all, which reserve() is told, are compared too. Cones of
  // every heading (a seventh of them on the ±π line or straight up or down), reach and half-angle
  // up to 80°, inside and across the grid's edges, a third in a band of rows.
  GridSpec grid;
  grid.cellSize = 0.05;
  grid.width = 240;
  grid.height = 180;
  const BeamTables tables(grid.cellSize, 130);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> x(-1.0, 13.0), y(-1.0, 10.0), heading(-3.2, 3.2),
      reach(0.05, 6.4), half(0.02, 1.4);
  struct Rows {
    std::size_t bound = 0;
    std::vector<std::pair<std::uint32_t, int>> rows;
  };
  auto run = [&](auto lanes, const Pose2D& sensor, double r, double h, RowWindow window) {
    Rows out;
    forEachConeRow<false, decltype(lanes)::value>(
        sensor, r, h, grid, tables, [&](std::size_t bound) { out.bound = bound; },
        [&](const ConeRow& row) { out.rows.emplace_back(row.cell, row.count); }, window);
    return out;
  };
  std::size_t rows = 0;
  for (int i = 0; i < 20000; ++i) {
    const double axis =
        i % 7 == 0 ? (i % 3 == 0 ? 0.5 : 1.0) * (i % 2 ? 1 : -1) * std::numbers::pi : heading(rng);
    const Pose2D sensor(x(rng), y(rng), axis);
    const double r = reach(rng), h = half(rng);
    RowWindow window;
    if (i % 3 == 0) {
      window.begin = static_cast<int>(y(rng) * 20.0);
      window.end = window.begin + 8 + i % 40;
    }
    const Rows one = run(std::false_type{}, sensor, r, h, window);
    const Rows four = run(std::true_type{}, sensor, r, h, window);
    QCOMPARE(four.bound, one.bound);
    QCOMPARE(four.rows, one.rows);
    rows += one.rows.size();
  }
  QVERIFY(rows > 100000);  // the cones met the grid
  // The window's first and last rows, by hand: rows 5–26 in [8, 16) are 8–15, rows −3–2 in the
  // whole grid 0–2.
  const RowWindow w{8, 16};
  QCOMPARE(w.firstRow(5), 8);
  QCOMPARE(w.lastRow(26), 15);
  QCOMPARE(RowWindow{}.firstRow(-3), 0);
  QCOMPARE(RowWindow{}.lastRow(2), 2);
}

void TstModels::reachBoundsTheFootprint() {
  // reach(maxRange) sizes the mapper's tables, so no footprint may go further: every cell centre
  // within reach + half a cell diagonal of the sensor. Murphy's R of 20 m with a 5 m transducer
  // does not take any beam past 5 m + tolerance (an echo is nearer than 5 m; no echo clears to
  // min(5, R)), so its reach is 5.1 m, not 20.1 m.
  GridSpec grid;
  grid.cellSize = 0.05;
  grid.width = 600;
  grid.height = 600;
  const double maxRange = 5.0;
  auto murphy = model("murphy", {{"max_range", 20.0}, {"no_echo", 1.0}});
  QCOMPARE(murphy->reach(maxRange), 5.0 + 0.1);
  for (const std::string name : {"hpf", "konolige", "murphy", "parameterized", "himm"}) {
    auto m = name == "murphy" ? std::move(murphy) : model(name.c_str(), {{"no_echo", 1.0}});
    const double reach = m->reach(maxRange);
    const auto tables = BeamTables::shared(grid.cellSize, reach);
    double furthest = 0.0;
    for (const double range : {0.4, 2.5, 4.99, kNoEcho}) {
      Beam beam;
      beam.sensor = Pose2D(15.02, 14.97, 0.3);
      beam.range = range;
      beam.maxRange = maxRange;
      Footprint fp;
      m->footprint(beam, grid, *tables, fp);
      for (const CellEvidence& c : fp.cells) {
        const double x = (c.cell % 600 + 0.5) * grid.cellSize,
                     y = (c.cell / 600 + 0.5) * grid.cellSize;
        furthest = std::max(furthest, std::hypot(x - 15.02, y - 14.97));
      }
    }
    QVERIFY2(furthest <= reach + grid.cellSize * std::sqrt(0.5),
             qPrintable(QString::fromStdString(name) + ": " + QString::number(furthest) + " > " +
                        QString::number(reach)));
    // And the bound is tight: some cell lies within 0.2 m of it (Konolige's reach is where its
    // attenuation ends, 1 / 0.4 = 2.5 m).
    QVERIFY2(furthest > reach - 0.2, name.c_str());
  }
}

void TstModels::declarationsAreComplete() {
  // The card's sliders exist under their names, and every declaration is usable as-is.
  QCOMPARE(sensorModelNames().size(), std::size_t{5});
  for (const char* p : {"p1", "p2", "p3", "p4", "p5"})
    QVERIFY(ParameterSet(sensorModelInfo("parameterized").parameters).has(p));
  QVERIFY(ParameterSet(sensorModelInfo("hpf").parameters).has("epsilon"));
  QVERIFY(ParameterSet(sensorModelInfo("hpf").parameters).has("omega"));
  for (const std::string& name : sensorModelNames()) {
    for (const ParameterSpec& s : sensorModelInfo(name).parameters) {
      QVERIFY2(s.min <= s.defaultValue && s.defaultValue <= s.max,
               qPrintable(QString::fromStdString(name + "." + s.name)));
      QVERIFY(!s.source.empty() && !s.symbol.empty());
    }
  }
}

void TstModels::preferredRulesArePapersPairings_data() {
  QTest::addColumn<QString>("model");
  QTest::addColumn<QString>("rule");
  QTest::addColumn<QString>("occupied");
  QTest::addColumn<QString>("beyond");
  // Paper 000 §2.1 eqs 7–8 (HPF, probability addition) and §2.2 (HIMM, its histogram); paper 001
  // §5.1 (models compared on the log update); paper 002 §3.3–§4 (recursive Bayes; its Figure 1
  // names Regions I, II and III).
  QTest::newRow("himm") << "himm"
                        << "himm"
                        << "I⁺ cell"
                        << "";
  QTest::newRow("hpf") << "hpf"
                       << "addition"
                       << "occupied arc"
                       << "";
  QTest::newRow("konolige") << "konolige"
                            << "log"
                            << "occupied (λ > 1)"
                            << "";
  QTest::newRow("murphy") << "murphy"
                          << "bayes-recursive"
                          << "Region I"
                          << "Region III";
  QTest::newRow("parameterized") << "parameterized"
                                 << "bayes-recursive"
                                 << "Region I"
                                 << "Region III";
}

void TstModels::preferredRulesArePapersPairings() {
  QFETCH(QString, model);
  QFETCH(QString, rule);
  QFETCH(QString, occupied);
  QFETCH(QString, beyond);
  const ModelInfo& info = sensorModelInfo(model.toStdString());
  QCOMPARE(QString::fromStdString(info.preferredRule), rule);
  QVERIFY(compatibility(info.name, info.preferredRule).allowed);
  QCOMPARE(QString::fromStdString(info.regions.occupied), occupied);
  QVERIFY(!info.regions.empty.empty());
  QCOMPARE(QString::fromStdString(info.regions.beyond), beyond);
}

QTEST_GUILESS_MAIN(TstModels)
#include "tst_models.moc"
