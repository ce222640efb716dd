// SPDX-License-Identifier: BSD-3-Clause
// Goodness without a reference (paper 002 §5; docs/metrics.md): VSDNS streamed through the
// mapper's footprint observer, derivative noise with a 3 x 3 window, and the two-run comparison.
// Every expected number is worked by hand in the row's comment.

#include <QtTest>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "sonargrid/engine/mapper.h"
#include "sonargrid/io/sglog.h"
#include "sonargrid/metrics/derivative_noise.h"
#include "sonargrid/metrics/two_run_comparison.h"
#include "sonargrid/metrics/vsdns.h"

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

sg::GridSpec grid(int w, int h) {
  sg::GridSpec s;
  s.origin = sg::Position(0.0, 0.0);
  s.cellSize = 0.1;
  s.width = w;
  s.height = h;
  return s;
}

// Cells in linear order (iy = 0 first), space-separated; "-" is a never-observed cell (p 0.5).
sg::OccupancyMap mapOf(const sg::GridSpec& spec, const QString& values) {
  sg::OccupancyMap m = sg::OccupancyMap::unobserved(spec);
  const std::size_t n = spec.cellCount();
  const QStringList parts = values.split(' ', Qt::SkipEmptyParts);
  if (parts.size() != static_cast<int>(n)) qFatal("mapOf: wrong number of cells");
  for (int i = 0; i < parts.size(); ++i) {
    if (parts[i] == "-") continue;
    const auto k = static_cast<std::size_t>(i);
    m.probability[k] = parts[i].toDouble();
    m.level[k] = sg::levelOfProbability(m.probability[k]);
    m.filled[k] = m.probability[k] > 0.5 ? 1 : 0;
    m.observed[k] = 1;
  }
  return m;
}

double sampleSd(const std::vector<double>& v) {
  double mean = 0;
  for (double x : v) mean += x;
  mean /= static_cast<double>(v.size());
  double ss = 0;
  for (double x : v) ss += (x - mean) * (x - mean);
  return std::sqrt(ss / static_cast<double>(v.size() - 1));
}

}  // namespace

class TstGoodness : public QObject {
  Q_OBJECT

 private slots:
  void vsdnsByHand_data();
  void vsdnsByHand();
  void vsdnsThroughFootprints();
  void vsdnsStreamedByTheMapperMatchesBruteForce();
  void derivativeNoiseByHand_data();
  void derivativeNoiseByHand();
  void twoRunsByHand_data();
  void twoRunsByHand();
  void twoRunsNeedOneGrid();
};

void TstGoodness::vsdnsByHand_data() {
  // Each cell's sequence of model values, cells separated by ';'.
  QTest::addColumn<QString>("cells");
  QTest::addColumn<double>("vsdns");
  QTest::addColumn<int>("cellsWithSpread");
  // 0.2, 0.4, 0.9: mean 0.5, squared deviations 0.09 + 0.01 + 0.16 = 0.26, σ = √(0.26 / 2) =
  // 0.360555.
  QTest::newRow("one cell") << "0.2,0.4,0.9" << std::sqrt(0.13) << 1;
  // A constant cell (σ = 0) and a cell written once (N − 1 = 0) are not in the mean.
  QTest::newRow("zero sigma left out") << "0.2,0.4,0.9;0.7,0.7,0.7;0.5" << std::sqrt(0.13) << 1;
  // 0.1, 0.3: mean 0.2, σ = √((0.01 + 0.01) / 1) = 0.141421; mean of the two σ = 0.250988.
  QTest::newRow("two cells") << "0.2,0.4,0.9;0.1,0.3" << (std::sqrt(0.13) + std::sqrt(0.02)) / 2.0
                             << 2;
  QTest::newRow("nothing varies") << "0.5,0.5;0.3" << kNaN << 0;
  QTest::newRow("no cell written") << "" << kNaN << 0;
}

void TstGoodness::vsdnsByHand() {
  QFETCH(QString, cells);
  QFETCH(double, vsdns);
  QFETCH(int, cellsWithSpread);
  sg::VsdnsAccumulator acc;
  acc.reset(8);
  const QStringList list = cells.split(';', Qt::SkipEmptyParts);
  for (int c = 0; c < list.size(); ++c) {
    for (const QString& v : list[c].split(',')) acc.add(static_cast<std::size_t>(c), v.toDouble());
  }
  const sg::VsdnsAccumulator::Result r = acc.result();
  QCOMPARE(static_cast<int>(r.cellsWithSpread), cellsWithSpread);
  if (std::isnan(vsdns)) {
    QVERIFY(!r.vsdns.has_value());
  } else {
    QVERIFY(r.vsdns.has_value());
    QVERIFY2(std::abs(*r.vsdns - vsdns) < 1e-12, qPrintable(QString::number(*r.vsdns, 'g', 15)));
  }
}

void TstGoodness::vsdnsThroughFootprints() {
  // observe() takes each entry's CellEvidence::probability (the model's P(occ | reading)), not the
  // empty/occupied evidence (0.9 / 0 here, which would give another σ).
  sg::VsdnsAccumulator acc;
  acc.reset(4);
  for (double p : {0.2, 0.4, 0.9}) {
    sg::Footprint fp;
    fp.cells.push_back(sg::CellEvidence{2, 0.9, 0.0, p});
    fp.cells.push_back(sg::CellEvidence{3, 0.5, 0.5, 0.5});
    acc.observe(fp);
  }
  // Footprints hold single-precision values (footprint.h): 0.2f, 0.4f, 0.9f are within 1e-8 of
  // the decimals, so the hand values hold to 1e-7.
  QCOMPARE(acc.samples(2), std::uint32_t{3});
  QVERIFY(std::abs(acc.mean(2) - 0.5) < 1e-7);
  QVERIFY(std::abs(acc.sigma(2) - std::sqrt(0.13)) < 1e-7);
  QCOMPARE(acc.sigma(3), 0.0);
  QVERIFY(std::abs(*acc.result().vsdns - std::sqrt(0.13)) < 1e-7);
  // 1000 values alternating 0.2 / 0.8: mean 0.5, Σ(x − x̄)² = 1000 · 0.09, σ = √(90 / 999).
  acc.reset(1);
  for (int k = 0; k < 1000; ++k) acc.add(0, k % 2 == 0 ? 0.2 : 0.8);
  QVERIFY(std::abs(acc.sigma(0) - std::sqrt(90.0 / 999.0)) < 1e-12);
  QVERIFY_THROWS_EXCEPTION(std::out_of_range, acc.add(5, 0.1));
}

void TstGoodness::vsdnsStreamedByTheMapperMatchesBruteForce() {
  // The first 80 scans of the room, mapped with HPF × Bayes: the observer's VSDNS equals the one
  // computed from every stored footprint (the L × M × N cube the accumulator avoids).
  sg::Dataset data = sg::readSglog(SONARGRID_DATASETS "/room/room.sglog");
  data.scans.resize(80);
  sg::MapperSettings settings;
  settings.model = "hpf";
  settings.rule = "bayes";
  settings.parameters = sg::defaultParameters("hpf", "bayes");
  sg::Mapper mapper(data.ring, data.fittingGrid(sg::PoseSource::Odometry, 0.1), settings);
  sg::VsdnsAccumulator acc;
  mapper.setObserver(&acc);
  mapper.mapDataset(data);

  std::map<std::uint32_t, std::vector<double>> values;
  for (const sg::Scan& scan : data.scans) {
    for (const sg::Reading& r : scan.readings) {
      for (const sg::CellEvidence& c : mapper.footprintOf(scan.odometry, r).cells)
        values[c.cell].push_back(c.probability);
    }
  }
  double sum = 0;
  std::size_t count = 0;
  for (const auto& [cell, v] : values) {
    if (v.size() < 2) continue;
    const double s = sampleSd(v);
    if (s == 0.0) continue;
    sum += s;
    ++count;
    QVERIFY(std::abs(acc.sigma(cell) - s) < 1e-9);
  }
  QVERIFY(count > 100);
  QCOMPARE(acc.result().cellsWithSpread, count);
  QVERIFY(std::abs(*acc.result().vsdns - sum / static_cast<double>(count)) < 1e-12);

  // Mapping again resets the observer with the mapper: the same result, not twice the samples.
  const double first = *acc.result().vsdns;
  mapper.mapDataset(data);
  QCOMPARE(*acc.result().vsdns, first);
}

void TstGoodness::derivativeNoiseByHand_data() {
  QTest::addColumn<int>("width");
  QTest::addColumn<int>("height");
  QTest::addColumn<QString>("p");
  QTest::addColumn<double>("sum");
  QTest::addColumn<double>("mean");
  QTest::addColumn<int>("scored");
  // A checkerboard: each interior cell differs by 1 from its 4 side neighbours and equals its 4
  // diagonal ones: D = 4 / 8 = 0.5. 4 x 4 has 2 x 2 interior cells: D_map = 2.
  QTest::newRow("checkerboard 4x4")
      << 4 << 4 << "0 1 0 1  1 0 1 0  0 1 0 1  1 0 1 0" << 2.0 << 0.5 << 4;
  // 5 x 3: 3 x 1 interior cells: 1.5.
  QTest::newRow("checkerboard 5x3")
      << 5 << 3 << "0 1 0 1 0  1 0 1 0 1  0 1 0 1 0" << 1.5 << 0.5 << 3;
  QTest::newRow("uniform") << 3 << 3 << "0.3 0.3 0.3  0.3 0.3 0.3  0.3 0.3 0.3" << 0.0 << 0.0 << 1;
  // One occupied cell among free ones: its 8 neighbours all differ by 1: D = 8 / 8.
  QTest::newRow("spike") << 3 << 3 << "0 0 0  0 1 0  0 0 0" << 1.0 << 1.0 << 1;
  // p = 0.1·x: the centre (0.1) differs by 0.1 from the 3 cells left and the 3 right: 0.6 / 8.
  QTest::newRow("gradient") << 3 << 3 << "0 0.1 0.2  0 0.1 0.2  0 0.1 0.2" << 0.075 << 0.075 << 1;
  // 6 x 3 checkerboard with (0, 0) never observed: the window of (1, 1) holds it and is skipped;
  // (2, 1), (3, 1), (4, 1) score 0.5 each.
  QTest::newRow("unobserved neighbour")
      << 6 << 3 << "- 1 0 1 0 1  1 0 1 0 1 0  0 1 0 1 0 1" << 1.5 << 0.5 << 3;
  // No interior cell at all.
  QTest::newRow("2x2") << 2 << 2 << "0 1 1 0" << 0.0 << kNaN << 0;
}

void TstGoodness::derivativeNoiseByHand() {
  QFETCH(int, width);
  QFETCH(int, height);
  QFETCH(QString, p);
  QFETCH(double, sum);
  QFETCH(double, mean);
  QFETCH(int, scored);
  const sg::DerivativeNoise d = sg::derivativeNoise(mapOf(grid(width, height), p));
  QVERIFY2(std::abs(d.sum - sum) < 1e-12, qPrintable(QString::number(d.sum, 'g', 15)));
  QCOMPARE(static_cast<int>(d.cellsScored), scored);
  if (std::isnan(mean)) {
    QVERIFY(!d.mean.has_value());
  } else {
    QVERIFY(d.mean.has_value());
    QVERIFY(std::abs(*d.mean - mean) < 1e-12);
  }
}

void TstGoodness::twoRunsByHand_data() {
  QTest::addColumn<QString>("a");
  QTest::addColumn<QString>("b");
  QTest::addColumn<int>("positive");
  QTest::addColumn<int>("negative");
  // Binary (p > 0.5):  A = 1 0 1 0 1 - 0 0 1,  B = 1 1 0 0 1 0 - 0 1.
  // Cells 5 and 6 are unobserved in one run and not compared; of the other 7, cells 1 and 2
  // differ: 5 positive, 2 negative. (Cell 7: 0.4 and 0.49 are both free; cell 8: 0.7 and 0.51
  // both occupied.)
  QTest::newRow("crafted") << "0.9 0.1 0.6 0.2 0.8 - 0.5 0.4 0.7"
                           << "0.8 0.7 0.4 0.1 0.9 0.3 - 0.49 0.51" << 5 << 2;
  // p = 0.5 is not occupied (the threshold is strict).
  QTest::newRow("one half is free") << "0.5 0.5 0.5 0.5 0.5 0.5 0.5 0.5 0.5"
                                    << "0 0 0 0 0 0 0 0 0.51" << 8 << 1;
  QTest::newRow("identical") << "0.9 0.1 0.6 0.2 0.8 - 0.5 0.4 0.7"
                             << "0.9 0.1 0.6 0.2 0.8 - 0.5 0.4 0.7" << 8 << 0;
  QTest::newRow("never both observed") << "0.9 - 0.1 - 0.9 - 0.1 - 0.9"
                                       << "- 0.9 - 0.1 - 0.9 - 0.1 -" << 0 << 0;
}

void TstGoodness::twoRunsByHand() {
  QFETCH(QString, a);
  QFETCH(QString, b);
  QFETCH(int, positive);
  QFETCH(int, negative);
  const sg::TwoRunComparison c = sg::compareTwoRuns(mapOf(grid(3, 3), a), mapOf(grid(3, 3), b));
  QCOMPARE(static_cast<int>(c.positive), positive);
  QCOMPARE(static_cast<int>(c.negative), negative);
}

void TstGoodness::twoRunsNeedOneGrid() {
  const sg::OccupancyMap a = mapOf(grid(3, 1), "0 0 0");
  const sg::OccupancyMap b = mapOf(grid(1, 3), "0 0 0");
  QVERIFY_THROWS_EXCEPTION(std::invalid_argument, sg::compareTwoRuns(a, b));
}

QTEST_GUILESS_MAIN(TstGoodness)
#include "tst_goodness.moc"
