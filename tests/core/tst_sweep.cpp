// SPDX-License-Identifier: BSD-3-Clause
// The parameter sweep of paper 002 Table 1 and its optimal-set rules (core/sonargrid/sweep/).

#include <QtTest>
#include <cmath>
#include <set>
#include <tuple>

#include "sonargrid/base/concurrency.h"
#include "sonargrid/engine/mapper.h"
#include "sonargrid/sim/ray_sonar.h"
#include "sonargrid/sweep/optimal_sets.h"
#include "sonargrid/sweep/parameter_sweep.h"

using namespace sg;

namespace {

ParameterSet base() {
  return defaultParameters("parameterized", "bayes-recursive");
}

// Paper 002 Table 2: the 28 sets of the histogram's first bar, (P5, P4, 2·P3, P2, VSDNS).
struct Table2Row {
  double p5, p4, twoP3, p2, vsdns;
};
const Table2Row kTable2[] = {
    {6, 0.98, 0.5, 0.2, 0.054079},  {6, 0.97, 0.5, 0.2, 0.054256},  {6, 0.96, 0.5, 0.2, 0.054435},
    {6, 0.95, 0.5, 0.2, 0.054615},  {6, 0.98, 0.5, 0.15, 0.055861}, {6, 0.97, 0.5, 0.15, 0.056043},
    {6, 0.96, 0.5, 0.15, 0.056228}, {6, 0.95, 0.5, 0.15, 0.056414}, {6, 0.98, 1, 0.2, 0.056517},
    {6, 0.97, 1, 0.2, 0.056663},    {6, 0.96, 1, 0.2, 0.056811},    {6, 0.95, 1, 0.2, 0.056961},
    {7, 0.98, 0.5, 0.2, 0.057684},  {6, 0.98, 0.5, 0.1, 0.057705},  {7, 0.97, 0.5, 0.2, 0.05787},
    {6, 0.97, 0.5, 0.1, 0.057893},  {7, 0.96, 0.5, 0.2, 0.058058},  {6, 0.96, 0.5, 0.1, 0.058082},
    {6, 0.98, 1, 0.15, 0.058194},   {7, 0.95, 0.5, 0.2, 0.058248},  {6, 0.95, 0.5, 0.1, 0.058273},
    {6, 0.97, 1, 0.15, 0.058347},   {6, 0.96, 1, 0.15, 0.0585},     {6, 0.95, 1, 0.15, 0.058655},
    {6, 0.98, 1.5, 0.2, 0.058682},  {6, 0.97, 1.5, 0.2, 0.058801},  {6, 0.96, 1.5, 0.2, 0.058922},
    {6, 0.95, 1.5, 0.2, 0.059045},
};

ParameterSet setOf(double p5, double p4, double twoP3, double p2) {
  ParameterSet s = base();
  s.set("p1", 1.0 - p4);
  s.set("p2", p2);
  s.set("p3", twoP3 / 2.0);
  s.set("p4", p4);
  s.set("p5", p5);
  return s;
}

// A 3 m x 2 m box driven along its middle: a few hundred readings, enough for every measure.
Dataset tinyRun(std::uint64_t seed) {
  const std::vector<Position> corners{{0, 0}, {3, 0}, {3, 2}, {0, 2}};
  const std::vector<Segment> world = polygonSegments(corners, true);
  std::vector<TimedPose> route;
  for (int k = 0; k < 12; ++k) route.push_back({k * 0.1, Pose2D(0.8 + 0.1 * k, 1.0, 0.0)});
  SonarPhysics physics;
  physics.seed = seed;
  return simulateRoute(world, route, SonarRing::amigobot(), physics, "tiny");
}

}  // namespace

class TestSweep : public QObject {
  Q_OBJECT

 private slots:
  // Paper 002 Table 1: P2 4 values, 2·P3 6, P4 4, P5 the 15 of footnote **, P1 = 1 − P4.
  void gridHas1440DistinctSetsWithTheTableValues() {
    const std::vector<ParameterSet> sets = paper002Table1Sets(base());
    QCOMPARE(sets.size(), std::size_t(1440));  // 4 · 6 · 4 · 15
    std::set<std::tuple<double, double, double, double, double>> distinct;
    std::set<double> p2, twoP3, p4, p5;
    for (const ParameterSet& s : sets) {
      distinct.insert({s.get("p1"), s.get("p2"), s.get("p3"), s.get("p4"), s.get("p5")});
      QCOMPARE(s.get("p1"), 1.0 - s.get("p4"));
      p2.insert(s.get("p2"));
      twoP3.insert(2.0 * s.get("p3"));
      p4.insert(s.get("p4"));
      p5.insert(s.get("p5"));
      // Everything but p1..p5 stays at the base set's value.
      QCOMPARE(s.get("no_echo"), base().get("no_echo"));
      QCOMPARE(s.get("prior"), base().get("prior"));
    }
    QCOMPARE(distinct.size(), std::size_t(1440));
    QCOMPARE(p2, (std::set<double>{0.05, 0.10, 0.15, 0.20}));
    QCOMPARE(twoP3, (std::set<double>{0.5, 1.0, 1.5, 2.0, 2.5, 3.0}));
    QCOMPARE(p4, (std::set<double>{0.95, 0.96, 0.97, 0.98}));
    QCOMPARE(p5, (std::set<double>{6, 7, 8, 10, 13, 14, 15, 16, 17, 18, 20, 25, 27, 35, 40}));
    // Order: P5 outermost, P2 innermost (the column order of Table 2).
    QCOMPARE(sets[0].get("p5"), 6.0);
    QCOMPARE(sets[0].get("p2"), 0.05);
    QCOMPARE(sets[1].get("p2"), 0.10);
    QCOMPARE(sets[1439].get("p5"), 40.0);
    QCOMPARE(sets[1439].get("p4"), 0.98);
    QCOMPARE(sets[1439].get("p3"), 1.5);
  }

  void histogramBinsByHand() {
    // min 0, max 1.4, 14 bins of width 0.1: 0 → bin 0, 0.05 → 0, 0.1 → 1 (a lower edge belongs
    // to its bin), 0.75 → 7, 1.4 → 13 (the maximum closes the last bin); the empty value → -1.
    const std::vector<std::optional<double>> v{0.0, 0.05, 0.1, std::nullopt, 0.75, 1.4};
    const Histogram h = histogramOf(v);
    QCOMPARE(h.counts.size(), std::size_t(14));
    QCOMPARE(h.binOf, (std::vector<int>{0, 0, 1, -1, 7, 13}));
    QCOMPARE(h.counts[0], std::size_t(2));
    QCOMPARE(h.counts[1], std::size_t(1));
    QCOMPARE(h.counts[7], std::size_t(1));
    QCOMPARE(h.counts[13], std::size_t(1));
    QCOMPARE(h.upperEdge(13), 1.4);
    // All equal: one bin holds everything.
    const std::vector<std::optional<double>> same{0.3, 0.3};
    QCOMPARE(histogramOf(same).counts[0], std::size_t(2));
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                             histogramOf(std::vector<std::optional<double>>{std::nullopt}));
  }

  // Table 2's 28 sets plus two sets far above them: with min 0.054079 and max 0.124079 the bins
  // are 0.005 wide, so the first bar holds exactly Table 2 (its largest value, 0.059045, is below
  // 0.059079). Averaging them gives Table 1's 5th column, computed by hand from Table 2:
  // P5 = (24·6 + 4·7)/28 = 6.142857 (paper 6.14), P2 = (16·0.2 + 8·0.15 + 4·0.1)/28 = 0.171429
  // (0.171), 2·P3 = (16·0.5 + 8·1 + 4·1.5)/28 = 0.785714 (0.786), P4 = 0.965 (0.97), P1 = 0.035
  // (0.03). The minimum is Table 2's first row, Table 1's 6th column.
  void lowestBinAndMinimumReproduceTable1FromTable2() {
    std::vector<ParameterSet> sets;
    std::vector<std::optional<double>> v;
    for (const Table2Row& r : kTable2) {
      sets.push_back(setOf(r.p5, r.p4, r.twoP3, r.p2));
      v.push_back(r.vsdns);
    }
    sets.push_back(setOf(40, 0.95, 3.0, 0.05));
    v.push_back(0.124079);
    sets.push_back(setOf(35, 0.95, 3.0, 0.05));
    v.push_back(0.07);

    const OptimalSet bin = lowestBinAverage(v, sets);
    QCOMPARE(bin.members.size(), std::size_t(28));
    QVERIFY(std::abs(bin.parameters.get("p5") - 172.0 / 28.0) < 1e-12);
    QVERIFY(std::abs(bin.parameters.get("p2") - 4.8 / 28.0) < 1e-12);
    QVERIFY(std::abs(2.0 * bin.parameters.get("p3") - 22.0 / 28.0) < 1e-12);
    QVERIFY(std::abs(bin.parameters.get("p4") - 0.965) < 1e-12);
    QVERIFY(std::abs(bin.parameters.get("p1") - 0.035) < 1e-12);
    QCOMPARE(bin.criterion, 0.059045);

    const OptimalSet min = minimumVsdns(v, sets);
    QCOMPARE(min.members, (std::vector<std::size_t>{0}));
    QCOMPARE(min.parameters.get("p5"), 6.0);
    QCOMPARE(min.parameters.get("p4"), 0.98);
    QCOMPARE(2.0 * min.parameters.get("p3"), 0.5);
    QCOMPARE(min.parameters.get("p2"), 0.2);
    QCOMPARE(min.criterion, 0.054079);
  }

  void nearestMeanByHand() {
    // Values 0.125, 0.625, 0.375, (undefined), 0.875 (exact in binary): mean 2/4 = 0.5; 0.625 and
    // 0.375 are both 0.125 away and the earlier set (index 1) wins the tie; the undefined one
    // takes no part.
    std::vector<ParameterSet> sets{setOf(6, 0.95, 0.5, 0.05), setOf(7, 0.95, 0.5, 0.05),
                                   setOf(8, 0.95, 0.5, 0.05), setOf(10, 0.95, 0.5, 0.05),
                                   setOf(13, 0.95, 0.5, 0.05)};
    const std::vector<std::optional<double>> v{0.125, 0.625, 0.375, std::nullopt, 0.875};
    const OptimalSet mean = nearestMeanVsdns(v, sets);
    QCOMPARE(mean.criterion, 0.5);
    QCOMPARE(mean.members, (std::vector<std::size_t>{1}));
    QCOMPARE(mean.parameters.get("p5"), 7.0);
    // A mismatch of sizes is refused.
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                             nearestMeanVsdns(std::vector<std::optional<double>>{0.1}, sets));
  }

  void lowestBinKeepsWholeNumbersSwept() {
    // Issue 49: HIMM's increments are whole numbers. A lowest bin holding decrement 0, 5, 10, 15
    // has the mean 7.5, which ParameterSet refuses (the sweep view then terminated the app); and
    // increment 1, 6, 10, 15 has the whole mean 8, a value never swept. Each takes the members'
    // value nearest the mean: 5 and 10 are both 2.5 from 7.5, and 6 and 10 both 2 from 8; the
    // earlier member wins the tie. The real parameter p_hit (0.6, 0.8) still averages to 0.7.
    std::vector<ParameterSet> sets;
    const double decrements[] = {0, 5, 10, 15};
    const double increments[] = {1, 6, 10, 15};
    const double hits[] = {0.6, 0.8, 0.6, 0.8};
    for (int k = 0; k < 4; ++k) {
      ParameterSet s = defaultParameters("himm", "himm");
      s.set("decrement", decrements[k]);
      s.set("increment", increments[k]);
      s.set("p_hit", hits[k]);
      sets.push_back(s);
    }
    const ParameterSet mean = averageParameters(sets, {0, 1, 2, 3});
    QCOMPARE(mean.get("decrement"), 5.0);
    QCOMPARE(mean.get("increment"), 6.0);
    QCOMPARE(mean.get("p_hit"), 0.7);
    // Through the rule: every set in the lowest bin (equal VSDNS), the same choice.
    const std::vector<std::optional<double>> v{0.25, 0.25, 0.25, 0.25};
    const OptimalSet best = lowestBinAverage(v, sets);
    QCOMPARE(best.members.size(), std::size_t{4});
    QCOMPARE(best.parameters.get("decrement"), 5.0);
  }

  void noiseAndTwoRunRulesByHand() {
    std::vector<ParameterSet> sets{setOf(6, 0.95, 0.5, 0.05), setOf(7, 0.95, 0.5, 0.05),
                                   setOf(8, 0.95, 0.5, 0.05)};
    std::vector<SweepRow> rows(3);
    // D_map 5, 3 and 1, but the third scored no cell: the second wins with 3.
    rows[0].noise = {5.0, 0.5, 10};
    rows[1].noise = {3.0, 0.3, 10};
    rows[2].noise = {1.0, std::nullopt, 0};
    // positive − negative: 90 − 10 = 80, 85 − 5 = 80 (fewer disagreements: wins), 50 − 0 = 50.
    rows[0].twoRuns = TwoRunComparison{90, 10};
    rows[1].twoRuns = TwoRunComparison{85, 5};
    rows[2].twoRuns = TwoRunComparison{50, 0};
    const OptimalSet noise = minimumDerivativeNoise(rows, sets);
    QCOMPARE(noise.members, (std::vector<std::size_t>{1}));
    QCOMPARE(noise.criterion, 3.0);
    const OptimalSet two = bestTwoRunAgreement(rows, sets);
    QCOMPARE(two.members, (std::vector<std::size_t>{1}));
    QCOMPARE(two.criterion, 80.0);
  }

  // Each set's row must not depend on how many sets run at once, nor on which thread maps it:
  // one thread and three threads give identical rows (bit for bit), and each row equals a map
  // built on its own by the Mapper.
  void rowsDoNotDependOnThreads() {
    const Dataset a = tinyRun(1);
    const Dataset b = tinyRun(2);
    const std::vector<ParameterSet> all = paper002Table1Sets(base());
    const std::vector<ParameterSet> sets{all[0], all[333], all[777], all[1439], all[1000]};
    SweepSettings s;
    s.grid = a.fittingGrid(PoseSource::Odometry, 0.1);
    std::size_t calls = 0;
    const SweepOutcome one = [&] {
      const ScopedThreadCount threads(1);
      return runSweep(a, &b, sets, s, [&](std::size_t done, std::size_t total) {
        ++calls;
        QCOMPARE(total, sets.size());
        QCOMPARE(done, calls);
      });
    }();
    QCOMPARE(calls, sets.size());
    const SweepOutcome three = [&] {
      const ScopedThreadCount threads(3);
      return runSweep(a, &b, sets, s);
    }();
    QVERIFY(one.completed && three.completed);
    for (std::size_t i = 0; i < sets.size(); ++i) {
      QVERIFY(one.rows[i].vsdns.has_value());
      QCOMPARE(*one.rows[i].vsdns, *three.rows[i].vsdns);
      QCOMPARE(one.rows[i].noise.sum, three.rows[i].noise.sum);
      QCOMPARE(one.rows[i].twoRuns->positive, three.rows[i].twoRuns->positive);
      QCOMPARE(one.rows[i].twoRuns->negative, three.rows[i].twoRuns->negative);
    }
    MapperSettings ms;
    ms.model = "parameterized";
    ms.rule = "bayes-recursive";
    ms.parameters = sets[2];
    Mapper m(a.ring, s.grid, ms);
    m.mapDataset(a);
    QCOMPARE(derivativeNoise(m.snapshot()).sum, one.rows[2].noise.sum);
  }

  void cancelledSweepSaysSo() {
    const Dataset a = tinyRun(1);
    const std::vector<ParameterSet> sets = paper002Table1Sets(base());
    SweepSettings s;
    s.grid = a.fittingGrid(PoseSource::Odometry, 0.1);
    std::atomic<bool> cancel{true};
    const SweepOutcome o = runSweep(a, nullptr, sets, s, {}, &cancel);
    QVERIFY(!o.completed);
    QCOMPARE(std::count(o.done.begin(), o.done.end(), true), 0);
  }
};

QTEST_APPLESS_MAIN(TestSweep)
#include "tst_sweep.moc"
