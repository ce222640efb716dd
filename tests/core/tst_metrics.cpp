// SPDX-License-Identifier: BSD-3-Clause
// Metrics against a reference (docs/metrics.md): IOP (paper 000 eq 9), correlation, map scores,
// the Moravec–Blackwell match, cross-entropy, Brier, ROC AUC, precision / recall / F1 / IoU and the
// path comparison. Expected values are worked by hand on tiny grids; each row says how.

#include <QtTest>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <string>
#include <vector>

#include "sonargrid/engine/mapper.h"
#include "sonargrid/io/sglog.h"
#include "sonargrid/metrics/grid_path_planner.h"
#include "sonargrid/metrics/ideal_map.h"
#include "sonargrid/metrics/index_of_performance.h"
#include "sonargrid/metrics/map_agreement.h"
#include "sonargrid/metrics/occupancy_classification.h"
#include "sonargrid/metrics/path_comparison.h"
#include "sonargrid/metrics/reference_score.h"
#include "sonargrid/metrics/seeded_random.h"
#include "sonargrid/reference/actual_position_grid.h"
#include "sonargrid/reference/reference_json.h"
#include "sonargrid/rules/rule_classes.h"

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

sg::GridSpec grid(int w, int h, double cell = 0.1, double ox = 0.0, double oy = 0.0) {
  sg::GridSpec s;
  s.origin = sg::Position(ox, oy);
  s.cellSize = cell;
  s.width = w;
  s.height = h;
  return s;
}

// A map where nothing was observed: p 0.5, level 8, nothing filled.
sg::OccupancyMap blankMap(const sg::GridSpec& spec) {
  return sg::OccupancyMap::unobserved(spec);
}

// Cells in linear order (iy = 0 first), space-separated; "-" is a never-observed cell.
sg::OccupancyMap mapOf(const sg::GridSpec& spec, const QString& values) {
  sg::OccupancyMap m = blankMap(spec);
  const QStringList parts = values.split(' ', Qt::SkipEmptyParts);
  if (parts.size() != static_cast<int>(spec.cellCount())) qFatal("mapOf: wrong number of cells");
  for (int i = 0; i < parts.size(); ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (parts[i] == "-") continue;
    m.probability[k] = parts[i].toDouble();
    m.level[k] = sg::levelOfProbability(m.probability[k]);
    m.filled[k] = m.probability[k] > 0.5 ? 1 : 0;
    m.observed[k] = 1;
  }
  return m;
}

// Letters in linear order: F free, O occupied, U unknown.
sg::IdealMap idealOf(const sg::GridSpec& spec, const QString& letters) {
  sg::IdealMap ideal;
  ideal.spec = spec;
  for (QChar c : letters) {
    if (c == 'F')
      ideal.cells.push_back(sg::IdealCell::Free);
    else if (c == 'O')
      ideal.cells.push_back(sg::IdealCell::Occupied);
    else if (c == 'U')
      ideal.cells.push_back(sg::IdealCell::Unknown);
  }
  if (ideal.cells.size() != spec.cellCount()) qFatal("idealOf: wrong number of cells");
  return ideal;
}

sg::ActualPositionGrid apgOfSegment(const sg::GridSpec& spec, sg::Position a, sg::Position b) {
  sg::ActualPositionGrid apg;
  apg.spec = spec;
  apg.cells.assign(spec.cellCount(), 0);
  sg::markSupercover(spec, a, b, apg.cells);
  return apg;
}

void compareOptional(const std::optional<double>& actual, double expected, double tolerance,
                     const char* what) {
  if (std::isnan(expected)) {
    QVERIFY2(
        !actual.has_value(),
        qPrintable(QString("%1: expected undefined, got %2").arg(what).arg(actual.value_or(0))));
    return;
  }
  QVERIFY2(actual.has_value(),
           qPrintable(QString("%1: undefined, expected %2").arg(what).arg(expected)));
  QVERIFY2(std::abs(*actual - expected) <= tolerance, qPrintable(QString("%1: %2, expected %3")
                                                                     .arg(what)
                                                                     .arg(*actual, 0, 'g', 10)
                                                                     .arg(expected, 0, 'g', 10)));
}

// −log2 of the clamped probabilities of docs/metrics.md (floor 0.001).
const double kRight = -std::log2(0.999);  // 0.00144342 bits: a certain and correct cell
const double kWrong = -std::log2(0.001);  // 9.96578 bits: a certain and wrong cell

}  // namespace

class TstMetrics : public QObject {
  Q_OBJECT

 private slots:
  void iopByHand_data();
  void iopByHand();
  void iopIgnoresUnfilledAndNeedsAnApg();
  void iopWeights_data();
  void iopWeights();
  void ruleEvidence();
  void snapshotCarriesEvidence();
  void distanceTransformIsExact();
  void iopIsInsensitiveToCellSize_data();
  void iopIsInsensitiveToCellSize();
  void agreementByHand_data();
  void agreementByHand();
  void matchIsCellsTimesOneMinusCrossEntropy();
  void classificationByHand_data();
  void classificationByHand();
  void seededRandomIsPortable();
  void plannerFindsShortestLegalPaths();
  void pathComparisonByHand_data();
  void pathComparisonByHand();
  void pathComparisonReactsToWalls();
  void metricListParsing();
  void scoreOfAPerfectMap();
  void scoreRestrictsMetrics();
  void scoreRejectsADisjointReference();
  void scoreOnACellMask_data();
  void scoreOnACellMask();
  void scoreOfTheRoomDataset();
  void commonObservedCells_data();
  void commonObservedCells();
  void scoreOnACellMaskOfTheWallMap();
  void scoreWarnsWhenNoReferenceEdgeWasObserved();
};

// ---------------------------------------------------------------------------------------------
// IOP

void TstMetrics::iopByHand_data() {
  // A wall along x = 0.05 m from y = 0.05 to 0.45 on 10 cm cells: the APG is column 0, rows 0..4.
  // Filled cells "x,y,cv;..." and the IOP in mm.
  QTest::addColumn<double>("wx0");
  QTest::addColumn<double>("wy0");
  QTest::addColumn<double>("wx1");
  QTest::addColumn<double>("wy1");
  QTest::addColumn<QString>("filled");
  QTest::addColumn<double>("iopMm");
  // The issue's example: CVs 15, 3, 1 at 0, 1 and 2 cells: (0·15 + 100·3 + 200·1) / 19 = 26.3158.
  QTest::newRow("0, 1, 2 cells away")
      << 0.05 << 0.05 << 0.05 << 0.45 << "0,2,15;1,2,3;2,2,1" << 500.0 / 19.0;
  QTest::newRow("on the wall") << 0.05 << 0.05 << 0.05 << 0.45 << "0,1,15" << 0.0;
  QTest::newRow("one cell away") << 0.05 << 0.05 << 0.05 << 0.45 << "1,4,7" << 100.0;
  QTest::newRow("five cells away") << 0.05 << 0.05 << 0.05 << 0.45 << "5,0,2;5,3,2" << 500.0;
  // (0·1 + 300·3) / (1 + 3) = 225.
  QTest::newRow("weighted by CV") << 0.05 << 0.05 << 0.05 << 0.45 << "0,0,1;3,0,3" << 225.0;
  // The wall a point in cell (0, 0): (1, 1) is √2 cells away, (3, 4) is 5 cells (3-4-5):
  // (141.421·5 + 500·1) / 6 = 201.184.
  QTest::newRow("diagonal distances") << 0.05 << 0.05 << 0.05 << 0.05 << "1,1,5;3,4,1"
                                      << (100.0 * std::sqrt(2.0) * 5.0 + 500.0) / 6.0;
}

void TstMetrics::iopByHand() {
  QFETCH(double, wx0);
  QFETCH(double, wy0);
  QFETCH(double, wx1);
  QFETCH(double, wy1);
  QFETCH(QString, filled);
  QFETCH(double, iopMm);
  const sg::GridSpec spec = grid(10, 5);
  sg::OccupancyMap map = blankMap(spec);
  double cvSum = 0;
  for (const QString& cell : filled.split(';')) {
    const QStringList f = cell.split(',');
    const std::size_t i = spec.linear(sg::CellIndex(f[0].toInt(), f[1].toInt()));
    map.level[i] = static_cast<std::uint8_t>(f[2].toInt());
    map.filled[i] = 1;
    map.observed[i] = 1;
    cvSum += f[2].toInt();
  }
  const sg::IndexOfPerformance iop = sg::indexOfPerformance(
      map, apgOfSegment(spec, sg::Position(wx0, wy0), sg::Position(wx1, wy1)));
  compareOptional(iop.mm, iopMm, 1e-3, "IOP");
  QCOMPARE(iop.filledCells, static_cast<std::size_t>(filled.count(';') + 1));
  QCOMPARE(iop.cvSum, cvSum);
}

void TstMetrics::iopIgnoresUnfilledAndNeedsAnApg() {
  const sg::GridSpec spec = grid(10, 5);
  const sg::ActualPositionGrid apg =
      apgOfSegment(spec, sg::Position(0.05, 0.05), sg::Position(0.05, 0.45));
  sg::OccupancyMap map = blankMap(spec);
  // A high level on a cell that is not filled does not count (IOP is over filled cells).
  map.level[spec.linear(sg::CellIndex(9, 4))] = 15;
  QVERIFY(!sg::indexOfPerformance(map, apg).mm.has_value());  // no filled cell: undefined
  // Filled with CV 0 (possible for a rule whose filled flag and level disagree): no weight.
  map.filled[spec.linear(sg::CellIndex(9, 4))] = 1;
  map.level[spec.linear(sg::CellIndex(9, 4))] = 0;
  QVERIFY(!sg::indexOfPerformance(map, apg).mm.has_value());
  map.filled[spec.linear(sg::CellIndex(2, 0))] = 1;
  map.level[spec.linear(sg::CellIndex(2, 0))] = 4;
  compareOptional(sg::indexOfPerformance(map, apg).mm, 200.0, 1e-3, "IOP");  // 2 cells, CV 4

  sg::ActualPositionGrid empty = apg;
  std::fill(empty.cells.begin(), empty.cells.end(), std::uint8_t{0});
  QVERIFY_THROWS_EXCEPTION(std::invalid_argument, sg::indexOfPerformance(map, empty));
  sg::ActualPositionGrid other =
      apgOfSegment(grid(10, 6), sg::Position(0.05, 0.05), sg::Position(0.05, 0.45));
  QVERIFY_THROWS_EXCEPTION(std::invalid_argument, sg::indexOfPerformance(map, other));
}

void TstMetrics::iopWeights_data() {
  // A wall along column 0 of a 10 x 5 grid of 10 cm cells (APG column 0). Cell A = (0, 2), on the
  // wall, and cell B = (3, 2), 3 cells (300 mm) off it, both filled. Columns: A's and B's level
  // and evidence, the weight, the filled threshold, the IOP in mm and the cells counted.
  QTest::addColumn<int>("levelA");
  QTest::addColumn<double>("evidenceA");
  QTest::addColumn<int>("levelB");
  QTest::addColumn<double>("evidenceB");
  QTest::addColumn<QString>("weight");
  QTest::addColumn<double>("threshold");
  QTest::addColumn<double>("iopMm");
  QTest::addColumn<int>("counted");
  // Addition: A Occ 1 (p 1, level 15), B a faint outlier Occ 0.2 (p 0.6, level round(9) = 9).
  // Level: (0·15 + 300·9) / (15 + 9) = 112.5. Evidence: weights 15·1 and 15·0.2 = 3:
  // (0·15 + 300·3) / 18 = 50.
  QTest::newRow("addition, level") << 15 << 1.0 << 9 << 0.2 << "level" << 0.0 << 112.5 << 2;
  QTest::newRow("addition, evidence") << 15 << 1.0 << 9 << 0.2 << "evidence" << 0.0 << 50.0 << 2;
  // Threshold 5 leaves B out under evidence (3 < 5): A alone, 0 mm; under level B stays (9 ≥ 5).
  QTest::newRow("evidence, threshold 5") << 15 << 1.0 << 9 << 0.2 << "evidence" << 5.0 << 0.0 << 1;
  QTest::newRow("level, threshold 5") << 15 << 1.0 << 9 << 0.2 << "level" << 5.0 << 112.5 << 2;
  // A threshold equal to a weight keeps the cell ("at least"): B's level 9 with threshold 9.
  QTest::newRow("level, threshold 9") << 15 << 1.0 << 9 << 0.2 << "level" << 9.0 << 112.5 << 2;
  QTest::newRow("level, threshold 10") << 15 << 1.0 << 9 << 0.2 << "level" << 10.0 << 0.0 << 1;
  // Bayes: A p 0.9 (level round(13.5) = 14, evidence 2·0.9 − 1 = 0.8 → 12), B p 0.6 (level 9,
  // evidence 0.2 → 3). Level: 300·9 / 23 = 117.391; evidence: 300·3 / 15 = 60.
  QTest::newRow("bayes, level") << 14 << 0.8 << 9 << 0.2 << "level" << 0.0 << 2700.0 / 23.0 << 2;
  QTest::newRow("bayes, evidence") << 14 << 0.8 << 9 << 0.2 << "evidence" << 0.0 << 60.0 << 2;
  // HIMM: CV 12 and 3; level and evidence (CV / 15) weigh the same: 300·3 / 15 = 60.
  QTest::newRow("himm, level") << 12 << 0.8 << 3 << 0.2 << "level" << 0.0 << 60.0 << 2;
  QTest::newRow("himm, evidence") << 12 << 0.8 << 3 << 0.2 << "evidence" << 0.0 << 60.0 << 2;
}

void TstMetrics::iopWeights() {
  QFETCH(int, levelA);
  QFETCH(double, evidenceA);
  QFETCH(int, levelB);
  QFETCH(double, evidenceB);
  QFETCH(QString, weight);
  QFETCH(double, threshold);
  QFETCH(double, iopMm);
  QFETCH(int, counted);
  const sg::GridSpec spec = grid(10, 5);
  sg::OccupancyMap map = blankMap(spec);
  map.evidence.assign(spec.cellCount(), 0.0);
  const std::size_t a = spec.linear(sg::CellIndex(0, 2)), b = spec.linear(sg::CellIndex(3, 2));
  map.level[a] = static_cast<std::uint8_t>(levelA);
  map.level[b] = static_cast<std::uint8_t>(levelB);
  map.evidence[a] = evidenceA;
  map.evidence[b] = evidenceB;
  map.filled[a] = map.filled[b] = 1;
  map.observed[a] = map.observed[b] = 1;
  sg::IopOptions options;
  QVERIFY(sg::parseIopWeight(weight.toStdString(), options.weight));
  options.filledThreshold = threshold;
  const sg::IndexOfPerformance iop = sg::indexOfPerformance(
      map, apgOfSegment(spec, sg::Position(0.05, 0.05), sg::Position(0.05, 0.45)), options);
  compareOptional(iop.mm, iopMm, 1e-9, "IOP");
  QCOMPARE(iop.filledCells, static_cast<std::size_t>(counted));
  QCOMPARE(QString(sg::iopWeightName(options.weight)), weight);

  // Without an evidence layer (a map read from a ROS map) the evidence weight is the level.
  map.evidence.clear();
  options.weight = sg::IopWeight::Evidence;
  options.filledThreshold = 0.0;
  const double byLevel = 300.0 * levelB / (levelA + levelB);
  compareOptional(
      sg::indexOfPerformance(
          map, apgOfSegment(spec, sg::Position(0.05, 0.05), sg::Position(0.05, 0.45)), options)
          .mm,
      byLevel, 1e-9, "IOP without evidence");
}

void TstMetrics::ruleEvidence() {
  // Each rule's certainty of occupancy (docs/metrics.md, "IOP weights"), from its cell values.
  sg::AdditionRule addition;
  addition.configure(sg::defaultParameters("hpf", "addition"));
  // Addition: Occ itself (paper 000 eq 7), whatever Emp is; the cell keeps it as a float.
  QCOMPARE(addition.evidenceOf(sg::EmptyEvidence{0.1f}, sg::OccupiedEvidence{0.6f}), double(0.6f));
  QCOMPARE(addition.evidenceOf(sg::EmptyEvidence{0.0f}, sg::OccupiedEvidence{0.2f}), double(0.2f));
  sg::BayesRule bayes(sg::BayesRule::Input::Evidence);
  // Probabilistic: 2p − 1 above 0.5, 0 below: p 0.8 → 0.6; p 0.3 → 0.
  QVERIFY(std::abs(bayes.evidenceOf(sg::BayesCell{0.8}) - 0.6) < 1e-15);
  QCOMPARE(bayes.evidenceOf(sg::BayesCell{0.3}), 0.0);
  sg::HimmRule himm;
  himm.configure(sg::defaultParameters("himm", "himm"));
  // HIMM: CV / 15, so 15 × evidence is the CV: CV 9 → 0.6.
  QCOMPARE(himm.evidenceOf(sg::HimmCell{9}), 9.0 / 15.0);
  // Dempster–Shafer: m(occ); m(occ) 0.75, m(emp) 0.125, m(unk) 0.125 → 0.75 (its p is 0.8125,
  // 2p − 1 would say 0.625). All three are exact in binary, so the m(occ) the cell leaves out comes
  // back exactly as 1 − 0.125 − 0.125.
  sg::DempsterShaferRule ds;
  QCOMPARE(ds.evidenceOf(sg::DempsterShaferCell::of({0.75f, 0.125f, 0.125f})), 0.75);
}

void TstMetrics::snapshotCarriesEvidence() {
  // A mapped snapshot fills the evidence layer with the rule's own values: for addition a filled
  // cell's evidence is its Occ, which is also its native value (eq 7: Occ when Occ ≥ Emp).
  const sg::Dataset data = sg::readSglog(SONARGRID_DATASETS "/room/room.sglog");
  sg::MapperSettings settings;
  settings.model = "hpf";
  settings.rule = "addition";
  settings.parameters = sg::defaultParameters("hpf", "addition");
  sg::Mapper mapper(data.ring, data.fittingGrid(sg::PoseSource::Odometry, 0.1), settings);
  mapper.mapDataset(data, 20.0);
  const sg::OccupancyMap map = mapper.snapshot();
  QCOMPARE(map.evidence.size(), map.spec.cellCount());
  std::size_t filled = 0;
  for (std::size_t i = 0; i < map.spec.cellCount(); ++i) {
    if (map.filled[i] == 0) continue;
    ++filled;
    QCOMPARE(map.evidence[i], map.native[i]);
  }
  QVERIFY(filled > 0);
}

void TstMetrics::distanceTransformIsExact() {
  // Against brute force on a random sparse APG: every distance is the true Euclidean one.
  const sg::GridSpec spec = grid(37, 23);
  sg::ActualPositionGrid apg;
  apg.spec = spec;
  apg.cells.assign(spec.cellCount(), 0);
  sg::SeededRandom random(7);
  for (int k = 0; k < 12; ++k) apg.cells[random.below(spec.cellCount())] = 1;
  const std::vector<float> d = sg::distanceToApg(apg);
  double worst = 0.0;
  for (std::size_t i = 0; i < spec.cellCount(); ++i) {
    const sg::CellIndex a = spec.fromLinear(i);
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < spec.cellCount(); ++j) {
      if (apg.cells[j] == 0) continue;
      const sg::CellIndex b = spec.fromLinear(j);
      best = std::min(best, std::hypot(a.x() - b.x(), a.y() - b.y()));
    }
    worst = std::max(worst, std::abs(best - static_cast<double>(d[i])));
  }
  QVERIFY2(worst < 1e-4, qPrintable(QString("largest error %1 cells").arg(worst)));
}

void TstMetrics::iopIsInsensitiveToCellSize_data() {
  // Paper 000 §4.3: the IOP "stays consistent" and "is expressed in measurement units". One
  // physical configuration — a wall and points of obstacle evidence, each with a CV, in metres — is
  // scored on 5 cm and on 10 cm cells (each point fills the cell that holds it); the two IOPs must
  // agree within half a 10 cm cell, 50 mm.
  QTest::addColumn<double>("wx0");
  QTest::addColumn<double>("wy0");
  QTest::addColumn<double>("wx1");
  QTest::addColumn<double>("wy1");
  QTest::addColumn<QString>("points");  // "x,y,cv;..."
  QTest::newRow("wall on a cell boundary, evidence beside it")
      << 1.0 << 0.2 << 1.0 << 2.8
      << "1.02,0.5,15;1.07,0.9,10;1.13,1.3,5;0.96,1.7,12;0.88,2.1,3;1.31,2.5,2";
  QTest::newRow("wall between boundaries")
      << 1.234 << 0.2 << 1.234 << 2.8
      << "1.25,0.5,15;1.30,0.9,10;1.11,1.3,5;1.43,1.7,12;1.02,2.1,3;1.6,2.5,2";
  QTest::newRow("diagonal wall, evidence along its normal")
      << 0.3 << 0.3 << 2.7 << 2.1 << "1.1,0.9,15;1.53,1.03,9;1.62,0.84,4;2.28,1.5,6;0.72,0.86,3";
  QTest::newRow("evidence 40 cm off the wall")
      << 1.0 << 0.2 << 1.0 << 2.8 << "1.4,0.6,15;1.4,1.2,15;0.6,2.0,15";
}

void TstMetrics::iopIsInsensitiveToCellSize() {
  QFETCH(double, wx0);
  QFETCH(double, wy0);
  QFETCH(double, wx1);
  QFETCH(double, wy1);
  QFETCH(QString, points);
  std::array<double, 2> iop{};
  const std::array<double, 2> cells{0.05, 0.10};
  for (std::size_t k = 0; k < 2; ++k) {
    const double c = cells[k];
    const sg::GridSpec spec =
        grid(static_cast<int>(std::lround(3.0 / c)), static_cast<int>(std::lround(3.0 / c)), c);
    sg::OccupancyMap map = blankMap(spec);
    for (const QString& p : points.split(';')) {
      const QStringList f = p.split(',');
      const std::size_t i =
          spec.linear(spec.worldToCell(sg::Position(f[0].toDouble(), f[1].toDouble())));
      // Two points in one cell: the cell keeps the larger CV.
      const auto cv = static_cast<std::uint8_t>(f[2].toInt());
      map.level[i] = map.filled[i] != 0 ? std::max(map.level[i], cv) : cv;
      map.filled[i] = 1;
    }
    iop[k] = *sg::indexOfPerformance(
                  map, apgOfSegment(spec, sg::Position(wx0, wy0), sg::Position(wx1, wy1)))
                  .mm;
  }
  qInfo("IOP at 5 cm %.1f mm, at 10 cm %.1f mm", iop[0], iop[1]);
  QVERIFY2(std::abs(iop[0] - iop[1]) <= 50.0,
           qPrintable(QString("%1 vs %2 mm").arg(iop[0]).arg(iop[1])));
}

// ---------------------------------------------------------------------------------------------
// Correlation, map scores, match, cross-entropy, Brier

void TstMetrics::agreementByHand_data() {
  // 3 x 3 grids in linear order (iy = 0 first). NaN = undefined.
  QTest::addColumn<QString>("ideal");
  QTest::addColumn<QString>("p");
  QTest::addColumn<int>("evaluated");
  QTest::addColumn<double>("correlation");
  QTest::addColumn<double>("mapScore");
  QTest::addColumn<double>("mapScoreOccupied");
  QTest::addColumn<double>("match");
  QTest::addColumn<double>("crossEntropy");
  QTest::addColumn<double>("brier");
  // Column x = 1 is a wall; the map has it but for cell 7. Σp = 2, Σy = 3, Σpy = 2, Σp² = 2,
  // Σy² = 3, n = 9: r = (9·2 − 2·3) / √((9·2 − 4)(9·3 − 9)) = 12 / √252 = 0.755929.
  // Map score 1/9. Occupied cells (p > 0.5 or wall): 1, 4, 7 → 1/3. Cross-entropy:
  // (8·0.00144342 + 9.96578) / 9; match 9 − that sum.
  QTest::newRow("one wall cell missed")
      << "FOFFOFFOF"
      << "0 1 0 0 1 0 0 0 0" << 9 << 100.0 * 12.0 / std::sqrt(252.0) << 100.0 / 9.0 << 100.0 / 3.0
      << 9.0 - (8 * kRight + kWrong) << (8 * kRight + kWrong) / 9.0 << 1.0 / 9.0;
  // p = 0.2 + 0.6·ideal: r = 1; every cell 0.2 off: 0.04; match 9·(1 + log2 0.8).
  QTest::newRow("linear in the ideal")
      << "FOFFOFFOF"
      << "0.2 0.8 0.2 0.2 0.8 0.2 0.2 0.8 0.2" << 9 << 100.0 << 4.0 << 4.0
      << 9.0 * (1.0 + std::log2(0.8)) << -std::log2(0.8) << 0.04;
  // Cell 7 never observed: it is not evaluated, and the other 8 agree exactly.
  QTest::newRow("unobserved cell excluded")
      << "FOFFOFFOF"
      << "0 1 0 0 1 0 0 - 0" << 8 << 100.0 << 0.0 << 0.0 << 8.0 * (1.0 - kRight) << kRight << 0.0;
  // Cell 0 unknown in the ideal map (inside an object): not evaluated however wrong it looks.
  QTest::newRow("unknown ideal cell excluded")
      << "UOFFOFFOF"
      << "1 1 0 0 1 0 0 1 0" << 8 << 100.0 << 0.0 << 0.0 << 8.0 * (1.0 - kRight) << kRight << 0.0;
  // p = 1 − ideal: r = −1, every cell off by 1, every cell occupied in one of the maps.
  QTest::newRow("inverted") << "FOFFOFFOF"
                            << "1 0 1 1 0 1 1 0 1" << 9 << -100.0 << 100.0 << 100.0
                            << 9.0 * (1.0 - kWrong) << kWrong << 1.0;
  // p = 0.5 everywhere (observed): no variance, r undefined; (0.5)² = 0.25 per cell; one bit per
  // cell of cross-entropy and a match of 0 (a coin knows nothing).
  QTest::newRow("constant one half")
      << "FOFFOFFOF"
      << "0.5 0.5 0.5 0.5 0.5 0.5 0.5 0.5 0.5" << 9 << kNaN << 25.0 << 25.0 << 0.0 << 1.0 << 0.25;
  QTest::newRow("nothing observed")
      << "FOFFOFFOF"
      << "- - - - - - - - -" << 0 << kNaN << kNaN << kNaN << kNaN << kNaN << kNaN;
  // Map score of occupied cells counts cells occupied in either map: the wall (1, 4, 7) and the
  // false obstacle at 0: (0.8² + 0.1² + 0.1² + 0.1²) / 4 = 0.67 / 4.
  QTest::newRow("occupied in either map")
      << "FOFFOFFOF"
      << "0.8 0.9 0.1 0.1 0.9 0.1 0.1 0.9 0.1" << 9
      << kNaN /* checked below */ << 100.0 * (0.64 + 8 * 0.01) / 9.0 << 100.0 * 0.67 / 4.0 << kNaN
      << kNaN << (0.64 + 8 * 0.01) / 9.0;
}

void TstMetrics::agreementByHand() {
  QFETCH(QString, ideal);
  QFETCH(QString, p);
  QFETCH(int, evaluated);
  QFETCH(double, correlation);
  QFETCH(double, mapScore);
  QFETCH(double, mapScoreOccupied);
  QFETCH(double, match);
  QFETCH(double, crossEntropy);
  QFETCH(double, brier);
  const sg::GridSpec spec = grid(3, 3);
  const sg::MapAgreement a = sg::mapAgreement(mapOf(spec, p), idealOf(spec, ideal));
  QCOMPARE(static_cast<int>(a.cellsEvaluated), evaluated);
  if (QByteArray(QTest::currentDataTag()) == "occupied in either map") {
    // Only the map scores matter in this row.
    compareOptional(a.mapScorePct, mapScore, 1e-9, "map score");
    compareOptional(a.mapScoreOccupiedPct, mapScoreOccupied, 1e-9, "map score occupied");
    compareOptional(a.brier, brier, 1e-12, "Brier");
    return;
  }
  compareOptional(a.correlationPct, correlation, 1e-9, "correlation");
  compareOptional(a.mapScorePct, mapScore, 1e-9, "map score");
  compareOptional(a.mapScoreOccupiedPct, mapScoreOccupied, 1e-9, "map score occupied");
  compareOptional(a.matchBits, match, 1e-9, "match");
  compareOptional(a.crossEntropyBits, crossEntropy, 1e-9, "cross-entropy");
  compareOptional(a.brier, brier, 1e-12, "Brier");
}

void TstMetrics::matchIsCellsTimesOneMinusCrossEntropy() {
  const sg::GridSpec spec = grid(4, 3);
  const sg::MapAgreement a = sg::mapAgreement(
      mapOf(spec, "0 0.3 1 0.99 - 0.5 0.7 0.01 0.2 1 0 0.45"), idealOf(spec, "FOOFFFOFUOFF"));
  QCOMPARE(a.cellsEvaluated, std::size_t{10});
  QVERIFY(std::abs(*a.matchBits - 10.0 * (1.0 - *a.crossEntropyBits)) < 1e-9);
  QVERIFY(std::abs(*a.mapScorePct - 100.0 * *a.brier) < 1e-9);
}

// ---------------------------------------------------------------------------------------------
// AUC, precision, recall, F1, IoU

void TstMetrics::classificationByHand_data() {
  QTest::addColumn<QString>("ideal");
  QTest::addColumn<QString>("p");
  QTest::addColumn<double>("auc");
  QTest::addColumn<double>("precision");
  QTest::addColumn<double>("recall");
  QTest::addColumn<double>("f1");
  QTest::addColumn<double>("iou");
  // Positives 0.9, 0.4; negatives 0.6, 0.1, 0.4. Pairs won: 0.9 beats all 3; 0.4 beats 0.1, ties
  // 0.4 (½), loses to 0.6: (3 + 1.5) / 6 = 0.75. Predicted (p > 0.5): cells 0 (TP) and 2 (FP);
  // cell 1 is a FN: precision ½, recall ½, F1 2/4, IoU 1/3.
  QTest::newRow("mixed") << "OOFFF"
                         << "0.9 0.4 0.6 0.1 0.4" << 0.75 << 0.5 << 0.5 << 0.5 << 1.0 / 3.0;
  QTest::newRow("perfect") << "OOFFF"
                           << "1 1 0 0 0" << 1.0 << 1.0 << 1.0 << 1.0 << 1.0;
  // Every score tied: AUC ½; nothing predicted occupied: precision undefined, recall 0.
  QTest::newRow("all tied") << "OOFFF"
                            << "0.5 0.5 0.5 0.5 0.5" << 0.5 << kNaN << 0.0 << 0.0 << 0.0;
  // One class only: AUC undefined; recall undefined (nothing occupied); one false positive.
  QTest::newRow("no obstacle") << "FFFFF"
                               << "0.9 0 0 0 0" << kNaN << 0.0 << kNaN << 0.0 << 0.0;
  // Unobserved and unknown cells are left out: what remains is the "perfect" row's 0, 2, 3.
  QTest::newRow("left out") << "OUFFU"
                            << "1 0 0 0 -" << 1.0 << 1.0 << 1.0 << 1.0 << 1.0;
}

void TstMetrics::classificationByHand() {
  QFETCH(QString, ideal);
  QFETCH(QString, p);
  QFETCH(double, auc);
  QFETCH(double, precision);
  QFETCH(double, recall);
  QFETCH(double, f1);
  QFETCH(double, iou);
  const sg::GridSpec spec = grid(5, 1);
  const sg::OccupancyClassification c = sg::classifyOccupancy(mapOf(spec, p), idealOf(spec, ideal));
  compareOptional(c.auc, auc, 1e-12, "AUC");
  compareOptional(c.precision, precision, 1e-12, "precision");
  compareOptional(c.recall, recall, 1e-12, "recall");
  compareOptional(c.f1, f1, 1e-12, "F1");
  compareOptional(c.iou, iou, 1e-12, "IoU");
}

// ---------------------------------------------------------------------------------------------
// Path comparison

void TstMetrics::seededRandomIsPortable() {
  // mt19937_64 is specified by the standard: its first output for the default seed 5489 is
  // 14514284786278117030. below(2^64 − 1) rejects only a 0 draw and returns the rest unchanged.
  sg::SeededRandom r(5489);
  QCOMPARE(r.below(std::numeric_limits<std::uint64_t>::max()),
           std::uint64_t{14514284786278117030ull});
  // Roughly uniform: 60 000 draws of a die, each face within 3 % of 10 000.
  sg::SeededRandom die(1990);
  std::array<int, 6> faces{};
  for (int k = 0; k < 60000; ++k) ++faces[die.below(6)];
  for (int f : faces) QVERIFY2(std::abs(f - 10000) < 300, qPrintable(QString::number(f)));
  QCOMPARE(sg::SeededRandom(3).below(1), std::uint64_t{0});
}

void TstMetrics::plannerFindsShortestLegalPaths() {
  // A* against Dijkstra with the same moves and costs on random grids: same cost, legal steps.
  const int w = 40, h = 30;
  sg::SeededRandom random(42);
  for (int trial = 0; trial < 5; ++trial) {
    std::vector<std::uint8_t> passable(static_cast<std::size_t>(w * h));
    for (auto& c : passable) c = random.below(100) < 28 ? 0 : 1;
    sg::GridPathPlanner planner(w, h, passable);
    const auto& comp = planner.components();
    for (int pair = 0; pair < 40; ++pair) {
      const std::size_t s = random.below(passable.size()), g = random.below(passable.size());
      // Dijkstra, moves as the planner: 8-connected, no corner cutting, 1000 / 1414.
      std::vector<std::int64_t> dist(passable.size(), std::numeric_limits<std::int64_t>::max());
      using Item = std::pair<std::int64_t, std::size_t>;
      std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
      if (passable[s]) {
        dist[s] = 0;
        queue.emplace(0, s);
      }
      auto ok = [&](int x, int y) {
        return x >= 0 && y >= 0 && x < w && y < h && passable[static_cast<std::size_t>(y * w + x)];
      };
      while (!queue.empty()) {
        const auto [d, c] = queue.top();
        queue.pop();
        if (d != dist[c]) continue;
        const int x = static_cast<int>(c) % w, y = static_cast<int>(c) / w;
        for (int dx = -1; dx <= 1; ++dx) {
          for (int dy = -1; dy <= 1; ++dy) {
            if ((dx == 0 && dy == 0) || !ok(x + dx, y + dy)) continue;
            if (dx != 0 && dy != 0 && !(ok(x + dx, y) && ok(x, y + dy))) continue;
            const std::size_t n = static_cast<std::size_t>((y + dy) * w + x + dx);
            const std::int64_t nd = d + (dx != 0 && dy != 0 ? 1414 : 1000);
            if (nd < dist[n]) {
              dist[n] = nd;
              queue.emplace(nd, n);
            }
          }
        }
      }
      const std::vector<std::size_t> path = planner.findPath(s, g);
      const bool reachable = passable[s] && dist[g] != std::numeric_limits<std::int64_t>::max();
      QCOMPARE(!path.empty(), reachable);
      QCOMPARE(reachable, comp[s] >= 0 && comp[s] == comp[g]);
      if (!reachable) continue;
      QCOMPARE(path.front(), s);
      QCOMPARE(path.back(), g);
      std::int64_t cost = 0;
      for (std::size_t k = 1; k < path.size(); ++k) {
        const int ax = static_cast<int>(path[k - 1]) % w, ay = static_cast<int>(path[k - 1]) / w;
        const int bx = static_cast<int>(path[k]) % w, by = static_cast<int>(path[k]) / w;
        QVERIFY(std::abs(ax - bx) <= 1 && std::abs(ay - by) <= 1 && path[k] != path[k - 1]);
        QVERIFY(ok(bx, by));
        if (ax != bx && ay != by) QVERIFY(ok(bx, ay) && ok(ax, by));
        cost += ax != bx && ay != by ? 1414 : 1000;
      }
      QCOMPARE(cost, dist[g]);
    }
  }
}

void TstMetrics::pathComparisonByHand_data() {
  // 3 x 2 cells, linear order (bottom row first). The ideal bottom row is free | wall | free, the
  // top row free: a robot must go over the top. Only (0, 0) and (2, 0) are observed ideal-free
  // cells, so every pair joins them (in one direction or the other).
  QTest::addColumn<QString>("p");
  QTest::addColumn<int>("found");
  QTest::addColumn<int>("collisions");
  QTest::addColumn<double>("falsePositive");
  QTest::addColumn<double>("falseNegative");
  // The map missed the wall (p 0 there) and never saw the top row: the straight path (cost 2000,
  // against 2828 over the top) runs through the wall — every path collides.
  QTest::newRow("missing wall") << "0 0 0 - - -" << 10 << 10 << 100.0 << 0.0;
  // The map has the wall: the path goes over the top (no corner cutting past it) and is safe.
  QTest::newRow("wall present") << "0 1 0 - - -" << 10 << 0 << 0.0 << 0.0;
  // A spurious obstacle in the top row closes the way: no path, every pair a false negative.
  QTest::newRow("spurious obstacle") << "0 1 0 - 1 -" << 0 << 0 << kNaN << 100.0;
}

void TstMetrics::pathComparisonByHand() {
  QFETCH(QString, p);
  QFETCH(int, found);
  QFETCH(int, collisions);
  QFETCH(double, falsePositive);
  QFETCH(double, falseNegative);
  const sg::GridSpec spec = grid(3, 2);
  const sg::PathComparison c = sg::comparePaths(mapOf(spec, p), idealOf(spec, "FOFFFF"), 10, 5);
  QCOMPARE(static_cast<int>(c.pairs), 10);
  QCOMPARE(static_cast<int>(c.pathsFound), found);
  QCOMPARE(static_cast<int>(c.collisions), collisions);
  compareOptional(c.falsePositivePct, falsePositive, 1e-12, "false positives");
  compareOptional(c.falseNegativePct, falseNegative, 1e-12, "false negatives");
}

void TstMetrics::pathComparisonReactsToWalls() {
  // A 4 m x 2.4 m room (10 cm cells) split by an inner wall from the floor to 1.8 m at x = 2 m,
  // leaving a 0.6 m gap at the top. The built maps start from the ideal map itself (p 1 on the
  // APG, 0 elsewhere, all observed): perfect, then with the inner wall's lower part missing, then
  // with the gap closed by a spurious wall.
  const char* json = R"({"format": "sonargrid-reference", "version": 1, "units": "m", "objects": [
      {"name": "walls", "closed": true, "corners": [[0.05, 0.05], [3.95, 0.05], [3.95, 2.35], [0.05, 2.35]]},
      {"name": "inner", "closed": false, "corners": [[2.05, 0.05], [2.05, 1.85]]}]})";
  const sg::ReferenceMap ref = sg::parseReferenceJson(json, "split.json");
  const sg::GridSpec spec = grid(40, 24);
  const sg::ActualPositionGrid apg = sg::ActualPositionGrid::rasterise(ref, spec);
  const sg::IdealMap ideal = sg::IdealMap::fromReference(ref, apg);
  sg::OccupancyMap perfect = blankMap(spec);
  for (std::size_t i = 0; i < spec.cellCount(); ++i) {
    perfect.observed[i] = 1;
    perfect.probability[i] = apg.cells[i] ? 1.0 : 0.0;
  }
  sg::OccupancyMap missing = perfect;  // the inner wall (column 20) below y = 1.2 m is not mapped
  for (int iy = 1; iy < 12; ++iy) missing.probability[spec.linear(sg::CellIndex(20, iy))] = 0.0;
  sg::OccupancyMap spurious = perfect;  // the gap (column 20, rows 19..22) is mapped as a wall
  for (int iy = 19; iy <= 22; ++iy) spurious.probability[spec.linear(sg::CellIndex(20, iy))] = 1.0;

  const sg::PathComparison p = sg::comparePaths(perfect, ideal, 300, 11);
  const sg::PathComparison m = sg::comparePaths(missing, ideal, 300, 11);
  const sg::PathComparison s = sg::comparePaths(spurious, ideal, 300, 11);
  qInfo(
      "perfect FP %.1f %% FN %.1f %%; missing wall FP %.1f %% FN %.1f %%; spurious wall FP %.1f %% "
      "FN %.1f %%",
      *p.falsePositivePct, *p.falseNegativePct, *m.falsePositivePct, *m.falseNegativePct,
      *s.falsePositivePct, *s.falseNegativePct);
  QCOMPARE(*p.falsePositivePct, 0.0);
  QCOMPARE(*p.falseNegativePct, 0.0);
  // A missing wall lets paths through it: false positives rise (pairs on opposite sides).
  QVERIFY(*m.falsePositivePct > 10.0);
  QCOMPARE(*m.falseNegativePct, 0.0);
  // A spurious wall cuts the room: false negatives rise, and no path found collides.
  QVERIFY(*s.falseNegativePct > 10.0);
  QCOMPARE(*s.falsePositivePct, 0.0);
  // The same seed draws the same pairs: the numbers repeat exactly.
  const sg::PathComparison again = sg::comparePaths(missing, ideal, 300, 11);
  QCOMPARE(again.collisions, m.collisions);
  QCOMPARE(again.pathsFound, m.pathsFound);
  // No pairs asked: nothing drawn, both undefined.
  const sg::PathComparison none = sg::comparePaths(perfect, ideal, 0, 11);
  QVERIFY(!none.falsePositivePct && !none.falseNegativePct);
}

// ---------------------------------------------------------------------------------------------
// The aggregate

void TstMetrics::metricListParsing() {
  const std::set<sg::Metric> s = sg::parseMetricList("iop,correlation,path");
  QCOMPARE(s.size(), std::size_t{4});
  QVERIFY(s.count(sg::Metric::PathFalsePositive) && s.count(sg::Metric::PathFalseNegative));
  QCOMPARE(sg::parseMetricList("f1,iou,f1").size(), std::size_t{2});
  QCOMPARE(sg::parseMetricList("map_score_occupied").count(sg::Metric::MapScoreOccupied),
           std::size_t{1});
  for (const sg::Metric m : sg::allMetrics())
    QCOMPARE(sg::parseMetricList(sg::metricName(m)).count(m), std::size_t{1});
  QVERIFY_THROWS_EXCEPTION(std::invalid_argument, sg::parseMetricList("iop,bogus"));
  QVERIFY_THROWS_EXCEPTION(std::invalid_argument, sg::parseMetricList(""));
  QVERIFY_THROWS_EXCEPTION(std::invalid_argument, sg::parseMetricList("iop,"));
}

void TstMetrics::scoreOfAPerfectMap() {
  // The ideal map itself, fully observed, scores perfectly on every metric.
  const char* json = R"({"format": "sonargrid-reference", "version": 1, "units": "cm", "objects": [
      {"name": "walls", "closed": true, "corners": [[5, 5], [295, 5], [295, 195], [5, 195]]},
      {"name": "box", "closed": true, "corners": [[105, 55], [155, 55], [155, 95], [105, 95]]}]})";
  const sg::ReferenceMap ref = sg::parseReferenceJson(json, "perfect.json");
  const sg::GridSpec spec = grid(32, 22);
  const sg::ActualPositionGrid apg = sg::ActualPositionGrid::rasterise(ref, spec);
  const sg::IdealMap ideal = sg::IdealMap::fromReference(ref, apg);
  sg::OccupancyMap map = blankMap(spec);
  for (std::size_t i = 0; i < spec.cellCount(); ++i) {
    if (ideal.cells[i] == sg::IdealCell::Unknown) continue;
    map.observed[i] = 1;
    map.probability[i] = apg.cells[i] ? 1.0 : 0.0;
    map.filled[i] = apg.cells[i];
    map.level[i] = apg.cells[i] ? 15 : 0;
  }
  const sg::ReferenceScore s = sg::scoreAgainstReference(map, ref);
  QCOMPARE(s.cellsEvaluated,
           ideal.count(sg::IdealCell::Free) + ideal.count(sg::IdealCell::Occupied));
  QCOMPARE(*s.value(sg::Metric::Iop), 0.0);
  QCOMPARE(*s.value(sg::Metric::Correlation), 100.0);
  QCOMPARE(*s.value(sg::Metric::MapScore), 0.0);
  QCOMPARE(*s.value(sg::Metric::MapScoreOccupied), 0.0);
  QCOMPARE(*s.value(sg::Metric::PathFalsePositive), 0.0);
  QCOMPARE(*s.value(sg::Metric::PathFalseNegative), 0.0);
  QCOMPARE(*s.value(sg::Metric::Auc), 1.0);
  QCOMPARE(*s.value(sg::Metric::Precision), 1.0);
  QCOMPARE(*s.value(sg::Metric::Recall), 1.0);
  QCOMPARE(*s.value(sg::Metric::F1), 1.0);
  QCOMPARE(*s.value(sg::Metric::Iou), 1.0);
  QCOMPARE(*s.value(sg::Metric::Brier), 0.0);
  QVERIFY(std::abs(*s.value(sg::Metric::CrossEntropy) - kRight) < 1e-12);
  QCOMPARE(s.paths.pairs, std::size_t{sg::kDefaultPathPairs});
}

void TstMetrics::scoreRestrictsMetrics() {
  const char* json = R"({"format": "sonargrid-reference", "version": 1, "units": "m", "objects": [
      {"name": "wall", "closed": false, "corners": [[0.05, 0.05], [0.05, 0.45]]}]})";
  const sg::ReferenceMap ref = sg::parseReferenceJson(json, "wall.json");
  sg::OccupancyMap map = mapOf(grid(3, 5), "1 0 0 1 0 0 1 0.9 0 1 0 0 1 0 0");
  sg::ScoreOptions options;
  options.metrics = sg::parseMetricList("iop,auc");
  const sg::ReferenceScore s = sg::scoreAgainstReference(map, ref, options);
  QVERIFY(s.value(sg::Metric::Iop).has_value());
  QVERIFY(s.value(sg::Metric::Auc).has_value());
  QVERIFY(!s.value(sg::Metric::Correlation).has_value());
  QVERIFY(!s.value(sg::Metric::PathFalsePositive).has_value());
  QCOMPARE(s.paths.pairs, std::size_t{0});
  QCOMPARE(s.cellsEvaluated, std::size_t{15});
  // IOP: CV 15 on the wall (5 cells, distance 0) and CV round(13.5) = 14 one cell off:
  // 100·14 / (5·15 + 14) = 15.73 mm.
  QVERIFY(std::abs(*s.value(sg::Metric::Iop) - 1400.0 / 89.0) < 1e-3);
}

void TstMetrics::scoreRejectsADisjointReference() {
  const char* json = R"({"format": "sonargrid-reference", "version": 1, "units": "m", "objects": [
      {"name": "far", "closed": false, "corners": [[50, 50], [60, 50]]}]})";
  const sg::ReferenceMap ref = sg::parseReferenceJson(json, "far.json");
  QVERIFY_THROWS_EXCEPTION(sg::MetricsError,
                           sg::scoreAgainstReference(blankMap(grid(10, 10)), ref));
}

void TstMetrics::scoreOnACellMask_data() {
  // The map of scoreRestrictsMetrics: 3 x 5 cells of 10 cm, a wall on column 0 (APG and map p = 1,
  // CV 15), one spurious cell (1, 2) with p 0.9 (CV 14, one cell off the wall), p = 0 elsewhere;
  // every cell is known to the ideal map. The mask lists the 15 cells in linear order (iy = 0
  // first, three per row).
  QTest::addColumn<QString>("mask");
  QTest::addColumn<double>("iopMm");
  QTest::addColumn<double>("mapScorePct");
  QTest::addColumn<int>("cells");
  // Empty mask: every cell. IOP 100·14 / (5·15 + 14); map score 100 · 0.9² / 15 = 5.4 %.
  QTest::newRow("no mask") << "" << 1400.0 / 89.0 << 5.4 << 15;
  // Without (1, 2): only the wall is filled (IOP 0) and every scored cell is exact (score 0).
  QTest::newRow("all but the spurious cell") << "111 111 101 111 111" << 0.0 << 0.0 << 14;
  // Only (1, 2) and (2, 2): IOP 100·14 / 14 = 100 mm; map score 100 · (0.81 + 0) / 2 = 40.5 %.
  QTest::newRow("the spurious row's free cells") << "000 000 011 000 000" << 100.0 << 40.5 << 2;
  // Wall rows 0 and 1 and the whole of column 2: 2 + 5 cells, all exact.
  QTest::newRow("two wall cells and column 2") << "101 101 001 001 001" << 0.0 << 0.0 << 7;
  // Nothing: no filled cell (IOP undefined) and no evaluated cell (map score undefined).
  QTest::newRow("no cell") << "000 000 000 000 000" << kNaN << kNaN << 0;
}

void TstMetrics::scoreOnACellMask() {
  QFETCH(QString, mask);
  QFETCH(double, iopMm);
  QFETCH(double, mapScorePct);
  QFETCH(int, cells);
  const char* json = R"({"format": "sonargrid-reference", "version": 1, "units": "m", "objects": [
      {"name": "wall", "closed": false, "corners": [[0.05, 0.05], [0.05, 0.45]]}]})";
  const sg::ReferenceMap ref = sg::parseReferenceJson(json, "wall.json");
  const sg::OccupancyMap map = mapOf(grid(3, 5), "1 0 0 1 0 0 1 0.9 0 1 0 0 1 0 0");
  sg::ScoreOptions options;
  options.metrics = sg::parseMetricList("iop,map_score");
  for (QChar c : mask)
    if (c != ' ') options.cellMask.push_back(c == '1' ? 1 : 0);
  const sg::ReferenceScore s = sg::scoreAgainstReference(map, ref, options);
  compareOptional(s.value(sg::Metric::Iop), iopMm, 1e-9, "IOP");
  compareOptional(s.value(sg::Metric::MapScore), mapScorePct, 1e-9, "map score");
  QCOMPARE(s.cellsEvaluated, static_cast<std::size_t>(cells));
  // A mask of another grid's size is refused.
  options.cellMask.assign(14, 1);
  QVERIFY_THROWS_EXCEPTION(std::invalid_argument, sg::scoreAgainstReference(map, ref, options));
}

void TstMetrics::scoreOfTheRoomDataset() {
  // End to end on the bundled room: the numbers are printed for the record (docs/metrics.md quotes
  // them); the test only asks that they are defined and plausible.
  const sg::Dataset data = sg::readSglog(SONARGRID_DATASETS "/room/room.sglog");
  const sg::ReferenceMap ref = sg::readReferenceJson(SONARGRID_DATASETS "/room/room.json");
  for (const auto& [model, rule] :
       std::vector<std::pair<std::string, std::string>>{{"himm", "himm"}, {"hpf", "addition"}}) {
    sg::MapperSettings settings;
    settings.model = model;
    settings.rule = rule;
    settings.parameters = sg::defaultParameters(model, rule);
    sg::Mapper mapper(data.ring, data.fittingGrid(sg::PoseSource::Odometry, 0.1), settings);
    mapper.mapDataset(data);
    const sg::ReferenceScore s = sg::scoreAgainstReference(mapper.snapshot(), ref);
    qInfo(
        "%s x %s at 10 cm: IOP %.1f mm, correlation %.1f %%, map score %.2f %%, path FP %.1f %%, "
        "FN %.1f %%",
        model.c_str(), rule.c_str(), *s.value(sg::Metric::Iop), *s.value(sg::Metric::Correlation),
        *s.value(sg::Metric::MapScore), *s.value(sg::Metric::PathFalsePositive),
        *s.value(sg::Metric::PathFalseNegative));
    QVERIFY(*s.value(sg::Metric::Iop) > 0.0 && *s.value(sg::Metric::Iop) < 1000.0);
    QVERIFY(s.cellsEvaluated > 1000);
    QCOMPARE(s.paths.pairs, std::size_t{sg::kDefaultPathPairs});
  }
}

// ---------------------------------------------------------------------------------------------
// Scoring several maps on the same cells

void TstMetrics::commonObservedCells_data() {
  // Observed layers of 1 x 4 maps as "1101" strings, and the cells all of them observed.
  QTest::addColumn<QStringList>("observed");
  QTest::addColumn<QString>("common");
  QTest::newRow("one map") << QStringList{"1101"} << "1101";
  QTest::newRow("two maps") << QStringList{"1101", "0111"} << "0101";
  QTest::newRow("three maps") << QStringList{"1111", "0111", "1110"} << "0110";
  QTest::newRow("nothing shared") << QStringList{"1100", "0011"} << "0000";
}

void TstMetrics::commonObservedCells() {
  QFETCH(QStringList, observed);
  QFETCH(QString, common);
  std::vector<sg::OccupancyMap> maps;
  for (const QString& o : observed) {
    sg::OccupancyMap m = blankMap(grid(4, 1));
    for (int k = 0; k < 4; ++k) m.observed[static_cast<std::size_t>(k)] = o[k] == '1' ? 1 : 0;
    maps.push_back(m);
  }
  std::vector<const sg::OccupancyMap*> pointers;
  for (const sg::OccupancyMap& m : maps) pointers.push_back(&m);
  const std::vector<std::uint8_t> mask = sg::commonObservedCells(pointers);
  QString got;
  for (std::uint8_t c : mask) got += c ? '1' : '0';
  QCOMPARE(got, common);

  const sg::OccupancyMap other = blankMap(grid(5, 1));
  pointers.push_back(&other);
  QVERIFY_THROWS_EXCEPTION(std::invalid_argument, sg::commonObservedCells(pointers));
  QVERIFY_THROWS_EXCEPTION(std::invalid_argument, sg::commonObservedCells({}));
}

void TstMetrics::scoreOnACellMaskOfTheWallMap() {
  // The map of scoreRestrictsMetrics: a wall along column 0 of a 3 x 5 grid, p 1 on it, p 0.9 at
  // (1, 2), 0 elsewhere, all observed.
  const char* json = R"({"format": "sonargrid-reference", "version": 1, "units": "m", "objects": [
      {"name": "wall", "closed": false, "corners": [[0.05, 0.05], [0.05, 0.45]]}]})";
  const sg::ReferenceMap ref = sg::parseReferenceJson(json, "wall.json");
  const sg::OccupancyMap map = mapOf(grid(3, 5), "1 0 0 1 0 0 1 0.9 0 1 0 0 1 0 0");
  sg::ScoreOptions options;
  options.metrics = sg::parseMetricList("iop,precision");
  options.iop.weight = sg::IopWeight::Level;
  // Every cell (empty mask): 100·14 / (5·15 + 14) = 15.73 mm over 15 cells; precision 5 / 6.
  sg::ReferenceScore s = sg::scoreAgainstReference(map, ref, options);
  QCOMPARE(s.cellsEvaluated, std::size_t{15});
  compareOptional(s.value(sg::Metric::Iop), 1400.0 / 89.0, 1e-9, "IOP, every cell");
  compareOptional(s.value(sg::Metric::Precision), 5.0 / 6.0, 1e-12, "precision, every cell");
  // Leave out (1, 2), linear 7: the wall alone, IOP 0, precision 5 / 5, 14 cells.
  options.cellMask.assign(15, 1);
  options.cellMask[7] = 0;
  s = sg::scoreAgainstReference(map, ref, options);
  QCOMPARE(s.cellsEvaluated, std::size_t{14});
  compareOptional(s.value(sg::Metric::Iop), 0.0, 1e-12, "IOP, masked");
  compareOptional(s.value(sg::Metric::Precision), 1.0, 1e-12, "precision, masked");
  // Only column 2 (linear 2, 5, 8, 11, 14): no filled cell, IOP undefined; 5 cells evaluated.
  options.cellMask.assign(15, 0);
  for (int i : {2, 5, 8, 11, 14}) options.cellMask[static_cast<std::size_t>(i)] = 1;
  s = sg::scoreAgainstReference(map, ref, options);
  QCOMPARE(s.cellsEvaluated, std::size_t{5});
  QVERIFY(!s.value(sg::Metric::Iop).has_value());
  // A mask of another size is an error.
  options.cellMask.assign(14, 1);
  QVERIFY_THROWS_EXCEPTION(std::invalid_argument, sg::scoreAgainstReference(map, ref, options));
}

void TstMetrics::scoreWarnsWhenNoReferenceEdgeWasObserved() {
  // A wall along column 0 of a 10 x 10 grid; the map observed only cell (9, 9), far from it.
  const char* json = R"({"format": "sonargrid-reference", "version": 1, "units": "m", "objects": [
      {"name": "wall", "closed": false, "corners": [[0.05, 0.05], [0.05, 0.95]]}]})";
  const sg::ReferenceMap ref = sg::parseReferenceJson(json, "wall.json");
  sg::OccupancyMap map = blankMap(grid(10, 10));
  map.observed[99] = 1;
  map.probability[99] = 0.0;
  map.level[99] = 0;
  sg::ReferenceScore s = sg::scoreAgainstReference(map, ref);
  QCOMPARE(s.apgCells, std::size_t{10});
  QCOMPARE(s.apgCellsObserved, std::size_t{0});
  QCOMPARE(s.warnings.size(), std::size_t{1});
  QVERIFY(s.warnings.front().find("none of the 10 cells") != std::string::npos);
  // Observing one cell of the wall, (0, 4): no warning.
  map.observed[40] = 1;
  s = sg::scoreAgainstReference(map, ref);
  QCOMPARE(s.apgCellsObserved, std::size_t{1});
  QVERIFY(s.warnings.empty());
}

QTEST_GUILESS_MAIN(TstMetrics)
#include "tst_metrics.moc"
