// SPDX-License-Identifier: BSD-3-Clause
// Map entropy (Martin & Moravec 1996; docs/metrics.md, "Map entropy"): H = −p log2 p − (1 − p)
// log2 (1 − p) per cell, summed. Every expected number is worked by hand in the row's comment.

#include <QtTest>
#include <cmath>
#include <limits>

#include "sonargrid/metrics/map_entropy.h"

namespace {

sg::GridSpec grid(int w, int h) {
  sg::GridSpec s;
  s.origin = sg::Position(0.0, 0.0);
  s.cellSize = 0.1;
  s.width = w;
  s.height = h;
  return s;
}

// Cells in linear order, space-separated; "-" is a never-observed cell (p 0.5).
sg::OccupancyMap mapOf(const sg::GridSpec& spec, const QString& values) {
  sg::OccupancyMap m = sg::OccupancyMap::unobserved(spec);
  const QStringList parts = values.split(' ', Qt::SkipEmptyParts);
  if (parts.size() != static_cast<int>(spec.cellCount())) qFatal("mapOf: wrong number of cells");
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

}  // namespace

class TstMapEntropy : public QObject {
  Q_OBJECT

 private slots:
  void cell_data() {
    QTest::addColumn<double>("p");
    QTest::addColumn<double>("bits");
    QTest::newRow("unknown") << 0.5 << 1.0;             // −½ log2 ½ − ½ log2 ½ = ½ + ½
    QTest::newRow("certainly free") << 0.0 << 0.0;      // 0 log 0 = 0, 1 log 1 = 0
    QTest::newRow("certainly occupied") << 1.0 << 0.0;  // the same
    // −0.25 log2 0.25 − 0.75 log2 0.75 = 0.5 + 0.75 · 0.415037… = 0.811278…
    QTest::newRow("quarter") << 0.25 << 0.8112781244591328;
    QTest::newRow("three quarters") << 0.75 << 0.8112781244591328;  // symmetric in p and 1 − p
    // −0.9 log2 0.9 − 0.1 log2 0.1 = 0.9 · 0.152003… + 0.1 · 3.321928… = 0.468996…
    QTest::newRow("0.9") << 0.9 << 0.4689955935892812;
    QTest::newRow("below 0 clamps") << -0.1 << 0.0;
  }
  void cell() {
    QFETCH(double, p);
    QFETCH(double, bits);
    QVERIFY(std::abs(sg::cellEntropyBits(p) - bits) < 1e-12);
  }

  void map_data() {
    QTest::addColumn<int>("w");
    QTest::addColumn<int>("h");
    QTest::addColumn<QString>("cells");
    QTest::addColumn<double>("total");
    QTest::addColumn<double>("observed");
    QTest::addColumn<int>("count");
    QTest::addColumn<double>("mean");  // NaN: undefined
    // p = 0.5, 0.5, 1, 0, all observed: 1 + 1 + 0 + 0 = 2 bits; mean 2 / 4.
    QTest::newRow("2x2 half half one zero") << 2 << 2 << "0.5 0.5 1 0" << 2.0 << 2.0 << 4 << 0.5;
    // Two cells never observed hold p 0.5: 1 bit each in the total, nothing in the observed sum.
    QTest::newRow("2x2 two unobserved") << 2 << 2 << "- - 1 0" << 2.0 << 0.0 << 2 << 0.0;
    // Nothing observed: 6 cells × 1 bit; the mean is undefined.
    QTest::newRow("3x2 blank") << 3 << 2 << "- - - - - -" << 6.0 << 0.0 << 0
                               << std::numeric_limits<double>::quiet_NaN();
    // 0.25 and 0.75 (0.811278… each) plus a certain cell: 1.622556…; mean over 3 cells.
    QTest::newRow("3x1 quarters") << 3 << 1 << "0.25 0.75 1" << 1.6225562489182657
                                  << 1.6225562489182657 << 3 << 0.5408520829727552;
  }
  void map() {
    QFETCH(int, w);
    QFETCH(int, h);
    QFETCH(QString, cells);
    QFETCH(double, total);
    QFETCH(double, observed);
    QFETCH(int, count);
    QFETCH(double, mean);
    const sg::MapEntropy e = sg::mapEntropy(mapOf(grid(w, h), cells));
    QVERIFY(std::abs(e.totalBits - total) < 1e-12);
    QVERIFY(std::abs(e.observedBits - observed) < 1e-12);
    QCOMPARE(e.cellsObserved, static_cast<std::size_t>(count));
    if (std::isnan(mean)) {
      QVERIFY(!e.meanBits.has_value());
    } else {
      QVERIFY(e.meanBits.has_value());
      QVERIFY(std::abs(*e.meanBits - mean) < 1e-12);
    }
  }

  void mismatchedLayersThrow() {
    sg::OccupancyMap m = sg::OccupancyMap::unobserved(grid(2, 2));
    m.probability.pop_back();
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, sg::mapEntropy(m));
  }
};

QTEST_GUILESS_MAIN(TstMapEntropy)
#include "tst_map_entropy.moc"
