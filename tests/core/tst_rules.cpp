// SPDX-License-Identifier: BSD-3-Clause
// Update rules over short hand-worked sequences. Each step's number is computed by hand from the
// formula the comment names.

#include <QtTest>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "sonargrid/engine/update_rule.h"
#include "sonargrid/rules/cell_updates.h"
#include "sonargrid/rules/rule_classes.h"
#include "sonargrid/simd/lanes.h"
#include "sonargrid/testing/registry_hooks.h"

using namespace sg;

namespace {
constexpr double kTol = 1e-6;

// A rule and a one-row grid of `cells` cells made with its layout: the rule reads and writes only
// the grid's cells.
struct RuleOnGrid {
  std::unique_ptr<UpdateRule> rule;
  Grid grid;
  void apply(const Footprint& f) { rule->apply(f, grid); }
  void applyPart(const Footprint& f, const FootprintTotals& t) { rule->applyPart(f, t, grid); }
  bool needsTotals() const { return rule->needsTotals(); }
  double native(std::size_t i) const { return rule->native(grid, i); }
  double occupancy(std::size_t i) const { return rule->occupancy(grid, i); }
  bool filled(std::size_t i) const { return rule->filled(grid, i); }
  std::uint8_t level(std::size_t i) const { return rule->level(grid, i); }
};

std::unique_ptr<RuleOnGrid> rule(const char* name,
                                 std::initializer_list<std::pair<const char*, double>> set = {},
                                 std::size_t cells = 3) {
  auto r = makeUpdateRule(name);
  ParameterSet p(r->info().parameters);
  for (const auto& [k, v] : set) p.set(k, v);
  r->configure(p);
  GridSpec spec;
  spec.width = static_cast<int>(cells);
  spec.height = 1;
  Grid grid(spec, r->layout());
  return std::make_unique<RuleOnGrid>(RuleOnGrid{std::move(r), std::move(grid)});
}

// One reading's footprint: (cell, pE, pO, P).
Footprint fp(std::initializer_list<CellEvidence> cells) {
  Footprint f;
  f.cells.assign(cells.begin(), cells.end());
  return f;
}
CellEvidence empty(std::uint32_t cell, double pE) {
  return {cell, pE, 0.0, 0.5 - pE / 2};
}
CellEvidence occupied(std::uint32_t cell, double pO) {
  return {cell, 0.0, pO, 0.5 + pO / 2};
}
CellEvidence likelihood(std::uint32_t cell, double p) {
  return {cell, p < 0.5 ? 1 - 2 * p : 0.0, p > 0.5 ? 2 * p - 1 : 0.0, p};
}

#define NEAR(a, b)                     \
  QVERIFY2(std::abs((a) - (b)) < kTol, \
           qPrintable(QString("%1 vs %2").arg(a, 0, 'g', 10).arg(b, 0, 'g', 10)))
}  // namespace

class TstRules : public QObject {
  Q_OBJECT

 private slots:
  void addition();
  void additionPaper001Combine();
  void additionInParts();
  void bayesPaper001();
  void bayesRecursive();
  void logUpdate();
  void logOdds();
  void himmClamping();
  void dempsterShafer();
  void dempsterShaferCells();
  void dempsterShaferKeepsSmallMasses();
  void dempsterShaferFloorsTinyMasses();
  void bayesFloorsTinyProbabilities();
  void unseenCellsAreUnknown();
};

void TstRules::addition() {
  // Paper 001 §3.1 with paper 000's combine (eqs 7–8), normalisation on.
  auto r = rule("addition");
  // Reading 1: cell 0 pE = 0.5 → Emp0 = 0 + 0.5 − 0 = 0.5.
  r->apply(fp({empty(0, 0.5)}));
  // Reading 2: occupied arc over cells 1 and 2 with pO 0.6 and 0.2 → normalised 0.75 and 0.25.
  r->apply(fp({occupied(1, 0.6), occupied(2, 0.2)}));
  // Reading 3: cell 1 pE = 0.5 → Emp1 = 0.5; cell 0 pE = 0.5 again → Emp0 = 0.5 + 0.5 − 0.25 =
  // 0.75.
  r->apply(fp({empty(0, 0.5), empty(1, 0.5)}));
  NEAR(r->native(0), -0.75);  // Occ 0 < Emp 0.75 → −Emp
  NEAR(r->occupancy(0), 0.125);
  NEAR(r->native(1), 0.75);  // Occ 0.75 ≥ Emp 0.5 → Occ
  NEAR(r->occupancy(1), 0.875);
  NEAR(r->native(2), 0.25);
  QVERIFY(!r->filled(0) && r->filled(1) && r->filled(2));
  QCOMPARE(int(r->level(1)), 13);  // round(15 · 0.875) = round(13.125)

  // Without normalisation cell 1 takes 0.6 straight.
  auto raw = rule("addition", {{"normalise", 0}});
  raw->apply(fp({occupied(1, 0.6), occupied(2, 0.2)}));
  NEAR(raw->native(1), 0.6);
}

void TstRules::additionPaper001Combine() {
  // Paper 001 §3.1: Map = 1 − Emp if Emp > Occ, Occ if Occ > Emp; a tie (nothing known) is 0.5.
  auto r = rule("addition", {{"combine", 1}});
  r->apply(fp({empty(0, 0.5), occupied(1, 0.4)}));  // a lone pO normalises to 1
  r->apply(fp({empty(0, 0.5)}));
  NEAR(r->occupancy(0), 0.25);  // Emp = 0.75 → 1 − 0.75
  NEAR(r->occupancy(1), 1.0);
  NEAR(r->occupancy(2), 0.5);
}

void TstRules::additionInParts() {
  // The mapper may give a rule a footprint in parts (rows on different threads) with the totals of
  // the whole footprint: applying the parts must give what applying the whole gives, bit for bit.
  // Occupied 0.6, 0.2 and 0.2 sum to 1.0 (in units of 2^-40: each value rounds down to an integer
  // count of them, and the counts add exactly), so the scale is 1 and cell 1 gets 0.6.
  const Footprint whole = fp({occupied(0, 0.2), occupied(1, 0.6), empty(2, 0.3), occupied(3, 0.2)});
  const std::int64_t total = occupiedFixedPoint(whole);
  auto units = [](float v) { return static_cast<std::int64_t>(static_cast<double>(v) * 0x1p40); };
  QCOMPARE(total, units(0.2f) + units(0.6f) + units(0.2f));
  NEAR(FootprintTotals{total}.occupiedSum(), 1.0);
  auto a = rule("addition", {}, 4), b = rule("addition", {}, 4);
  QVERIFY(a->needsTotals());
  QVERIFY(!rule("addition", {{"normalise", 0}})->needsTotals());
  QVERIFY(!rule("bayes")->needsTotals());
  a->apply(whole);
  b->applyPart(fp({occupied(0, 0.2), occupied(1, 0.6)}), FootprintTotals{total});
  b->applyPart(fp({empty(2, 0.3), occupied(3, 0.2)}), FootprintTotals{total});
  for (std::size_t i = 0; i < 4; ++i) QCOMPARE(b->native(i), a->native(i));
  NEAR(a->native(1), 0.6);
  NEAR(a->native(2), -0.3);

  // Evidence no model gives still has a defined total (the cast of NaN or of 1e30 to an integer is
  // undefined, which UBSan reports): NaN counts 0, as the rule leaves its cell alone, and a value
  // beyond ±2^22 counts ±2^22, i.e. ±2^62 units.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  QCOMPARE(occupiedFixedPoint(nan), std::int64_t{0});
  QCOMPARE(occupiedFixedPoint(1e30f), std::int64_t{1} << 62);
  QCOMPARE(occupiedFixedPoint(-inf), -(std::int64_t{1} << 62));
  QCOMPARE(occupiedFixedPoint(0.5f), std::int64_t{1} << 39);
  const Footprint odd = fp({occupied(0, 0.5), occupied(1, nan), occupied(2, 0.25)});
  QCOMPARE(occupiedFixedPoint(odd), (std::int64_t{1} << 39) + (std::int64_t{1} << 38));
  // Four cells of 2^62 units wrap to 0 modulo 2^64, whatever their order or cut, instead of
  // overflowing.
  QCOMPARE(occupiedFixedPoint(
               fp({occupied(0, inf), occupied(1, inf), occupied(2, 1e30f), occupied(3, inf)})),
           std::int64_t{0});
  // And the rule leaves the NaN cell as it was while the others are scaled by 1 / 0.75.
  auto c = rule("addition", {}, 3);
  c->apply(odd);
  NEAR(c->native(0), 0.5 / 0.75);
  NEAR(c->native(1), 0.0);
  NEAR(c->native(2), 0.25 / 0.75);
}

void TstRules::bayesPaper001() {
  // Paper 001 §3.2: pE ↦ (1 − pE)/2, pO ↦ 0.5 + pO/2, Map ← P·Map / (P·Map + (1 − P)(1 − Map)).
  auto r = rule("bayes");
  r->apply(fp({empty(0, 0.6)}));  // P = 0.2: 0.1 / (0.1 + 0.4) = 0.2
  NEAR(r->occupancy(0), 0.2);
  r->apply(fp({occupied(0, 0.8)}));  // P = 0.9: 0.18 / (0.18 + 0.08) = 0.692308
  NEAR(r->occupancy(0), 0.18 / 0.26);
  QVERIFY(r->filled(0));
  NEAR(r->occupancy(1), 0.5);
}

void TstRules::bayesRecursive() {
  // Paper 002 eqs 5–6 (standard recursive form), fed P(s|Occ) directly.
  auto r = rule("bayes-recursive");
  r->apply(fp({likelihood(0, 0.7)}));  // 0.35 / (0.35 + 0.15) = 0.7
  NEAR(r->occupancy(0), 0.7);
  r->apply(fp({likelihood(0, 0.7)}));  // 0.49 / (0.49 + 0.09) = 0.844828
  NEAR(r->occupancy(0), 0.49 / 0.58);
  r->apply(fp({likelihood(0, 0.3)}));  // back to 0.7: 0.253448 / (0.253448 + 0.108621)
  NEAR(r->occupancy(0), 0.7);
  // Certain evidence against a certain cell: Bayes is undefined, the cell keeps its value.
  auto c = rule("bayes-recursive");
  c->apply(fp({likelihood(1, 1.0)}));
  c->apply(fp({likelihood(1, 0.0)}));
  NEAR(c->occupancy(1), 1.0);
}

void TstRules::logUpdate() {
  // Paper 001 §3.3 as notes fix it: Map = log10(Emp) + log10(Occ), cut to [−2, 2].
  auto r = rule("log");
  r->apply(fp({empty(0, 0.5)}));                          // log10 0.5 = −0.301030
  r->apply(fp({occupied(0, 0.8)}));                       // log10 1.8 = 0.255273
  NEAR(r->native(0), std::log10(0.5) + std::log10(1.8));  // −0.045757
  NEAR(r->occupancy(0), 0.5 - 0.5 * 0.0457575 / 2.0);     // 0.488561
  QVERIFY(!r->filled(0));
  // Ten certain echoes: 10 log10 2 = 3.0103, cut to 2 → p = 1.
  for (int i = 0; i < 10; ++i) r->apply(fp({occupied(1, 1.0)}));
  NEAR(r->native(1), 2.0);
  NEAR(r->occupancy(1), 1.0);
  // pE = 1 drives Emp to 0 (−∞ in logs): certainly free, and it stays so.
  r->apply(fp({empty(2, 1.0)}));
  r->apply(fp({occupied(2, 1.0)}));
  NEAR(r->native(2), -2.0);
  NEAR(r->occupancy(2), 0.0);
}

void TstRules::logOdds() {
  // L ← clamp(L + logit p − logit 0.5, logit 0.12, logit 0.97).
  auto r = rule("logodds");
  r->apply(fp({likelihood(0, 0.7)}));  // logit 0.7 = 0.847298
  NEAR(r->native(0), std::log(0.7 / 0.3));
  for (int i = 0; i < 4; ++i)
    r->apply(fp({likelihood(0, 0.7)}));  // 5 · 0.847298 = 4.236 > 3.476099
  NEAR(r->native(0), std::log(0.97 / 0.03));
  NEAR(r->occupancy(0), 0.97);
  r->apply(fp({likelihood(0, 0.4)}));  // 3.476099 − 0.405465 = 3.070634 → p = 0.955696
  NEAR(r->native(0), std::log(0.97 / 0.03) + std::log(0.4 / 0.6));
  NEAR(r->occupancy(0), 1.0 / (1.0 + std::exp(-3.0706342)));
  for (int i = 0; i < 20; ++i) r->apply(fp({likelihood(1, 0.4)}));  // clamps at 0.12
  NEAR(r->occupancy(1), 0.12);
}

void TstRules::himmClamping() {
  // Paper 000 §2.2: I⁺ = 3, I⁻ = 1, CV in [0, 15].
  auto r = rule("himm");
  for (int i = 0; i < 4; ++i) r->apply(fp({occupied(0, 1.0)}));
  QCOMPARE(r->native(0), 12.0);
  r->apply(fp({occupied(0, 1.0)}));
  QCOMPARE(r->native(0), 15.0);
  r->apply(fp({occupied(0, 1.0)}));  // 18 clamps to 15
  QCOMPARE(r->native(0), 15.0);
  r->apply(fp({empty(0, 1.0)}));
  QCOMPARE(r->native(0), 14.0);
  QCOMPARE(int(r->level(0)), 14);
  NEAR(r->occupancy(0), 14.0 / 15.0);
  r->apply(fp({empty(1, 1.0)}));  // −1 from 0 clamps at 0
  QCOMPARE(r->native(1), 0.0);
  QVERIFY(r->filled(0) && !r->filled(1));
}

void TstRules::dempsterShafer() {
  // Dempster's rule (dempster_shafer.cpp). Start: m = (occ 0, emp 0, unk 1).
  auto r = rule("dempster-shafer");
  r->apply(fp({occupied(0, 0.6)}));  // m = (0.6, 0, 0.4)
  NEAR(r->native(0), 0.6);
  // Evidence (0, 0.5, 0.5): K = 0.6·0.5 = 0.3; m(occ) = 0.3/0.7, m(emp) = 0.2/0.7, m(unk) =
  // 0.2/0.7.
  r->apply(fp({empty(0, 0.5)}));
  NEAR(r->native(0), 0.1 / 0.7);
  NEAR(r->occupancy(0), 0.3 / 0.7 + 0.1 / 0.7);  // pignistic 0.571429
  QVERIFY(r->filled(0));
  // Total conflict leaves the cell as it was.
  r->apply(fp({occupied(1, 1.0)}));
  r->apply(fp({empty(1, 1.0)}));
  NEAR(r->occupancy(1), 1.0);
}

void TstRules::dempsterShaferCells() {
  // A cell keeps its two smaller masses as floats and leaves out the largest, the sign bit saying
  // which (DempsterShaferCell, rule_classes.h). Every mass below is exact in binary, so the one
  // left out comes back exactly as one minus the other two.
  struct Case {
    float occ, emp, unk, a, b;
  };
  const Case cases[] = {
      {0.0f, 0.0f, 1.0f, 0.0f, 0.0f},           // a cell nobody has seen: m(unk) left out
      {0.25f, 0.125f, 0.625f, 0.25f, 0.125f},   // m(unk) the largest
      {0.625f, 0.125f, 0.25f, -0.25f, 0.125f},  // m(occ) the largest: a = −m(unk)
      {0.125f, 0.625f, 0.25f, 0.125f, -0.25f},  // m(emp) the largest: b = −m(unk)
      {0.375f, 0.25f, 0.375f, 0.375f, 0.25f},   // m(unk) ties m(occ): m(unk) left out
      {0.5f, 0.5f, 0.0f, -0.0f, 0.5f},          // m(occ) ties m(emp): m(occ) left out, a = −0
      {0.0f, 1.0f, 0.0f, 0.0f, -0.0f},          // certainly empty: b = −0
  };
  for (const Case& c : cases) {
    // Bit for bit (QCOMPARE of floats is fuzzy, and blind to the sign of a zero).
    const DempsterShaferCell cell = DempsterShaferCell::of({c.occ, c.emp, c.unk});
    QCOMPARE(std::bit_cast<std::uint32_t>(cell.a), std::bit_cast<std::uint32_t>(c.a));
    QCOMPARE(std::bit_cast<std::uint32_t>(cell.b), std::bit_cast<std::uint32_t>(c.b));
    const DempsterShaferMasses m = cell.masses();
    QVERIFY(m.occ == c.occ && m.emp == c.emp && m.unk == c.unk);
    const auto wide = cell.masses<double>();
    QVERIFY(wide.occ == c.occ && wide.emp == c.emp && wide.unk == c.unk);
  }
  // A kept mass of −0 does not set the sign bit that tags a left-out one.
  const DempsterShaferCell zero = DempsterShaferCell::of({-0.0f, 0.25f, 0.75f});
  QVERIFY(!std::signbit(zero.a) && !std::signbit(zero.b));
}

void TstRules::dempsterShaferKeepsSmallMasses() {
  // 30 occupied readings of 0.75, then empty readings of 0.9f, on one cell. Exact arithmetic
  // (fractions, with the float 0.9f the footprint carries): after the 30 m(unk) = 0.25^30, about
  // 8.7e-19, and m(emp) = 0; the empty readings then make m(emp)/m(occ) 0.087 after the 17th,
  // 0.867 after the 18th and 8.67 after the 19th, where m(occ) − m(emp) = −0.79325 and the
  // pignistic p = 0.10337. The cell keeps m(unk) as a float, so it follows: two doubles for m(occ)
  // and m(emp) rounded m(occ) to exactly 1 (8.7e-19 < 2^-53), and Dempster's rule never moves a
  // mass of 1.
  auto r = rule("dempster-shafer");
  for (int k = 0; k < 30; ++k) r->apply(fp({occupied(0, 0.75)}));
  QVERIFY(r->filled(0));
  NEAR(r->occupancy(0), 1.0);
  for (int k = 1; k <= 18; ++k) {
    r->apply(fp({empty(0, 0.9)}));
    QVERIFY2(r->filled(0), qPrintable(QString("empty reading %1").arg(k)));
  }
  NEAR(r->native(0), 0.0710319);
  r->apply(fp({empty(0, 0.9)}));
  QVERIFY(!r->filled(0));
  NEAR(r->native(0), -0.7932513);
  NEAR(r->occupancy(0), 0.1033744);
}

void TstRules::dempsterShaferFloorsTinyMasses() {
  // Empty readings of 0.5 on a cell nobody has seen, by hand: the first gives m(emp) = m(unk) =
  // 0.5 (a tie, m(unk) left out), the second m(emp) = 0.75 and m(unk) = 0.25, now stored as
  // b = −0.25, and each after it halves m(unk) exactly (s = (1 − 0.5) / (1 − 0 · 0.5)): after n
  // readings b = −2^-n. After the 100th b = −2^-100 = −DempsterShaferCell::kTiny, and there it
  // stays: the 101st would make it −2^-101, and the 300th −2^-300 (0 in a float, where no
  // evidence could turn the cell again). Occupied readings of 0.5 then turn it (m(occ) > m(emp)):
  // m(emp) is 1 in a float, so each doubles m(occ) and adds 2^-100 to it, (2^n − 1) 2^-100 after
  // the nth, until m(occ) nears 2^-24; each operation rounded to a float as the rule does (worked
  // in a script), m(occ) = 0.5 against m(emp) = 0.49999997 at the 100th. (In exact arithmetic
  // from m(unk) = 2^-100, where m(unk) then shrinks too, it is the 101st: 2/3 against 1/3.)
  // Through apply(), and through the run kernels in every lane width the CPU has
  // (11 cells: a group and a short tail), which must give the same bits.
  const auto bitsOf = [](float v) { return std::bit_cast<std::uint32_t>(v); };
  const auto check = [&](auto applyEmpty, auto applyOccupied, const DempsterShaferCell& cell,
                         auto filled) {
    for (int k = 1; k <= 300; ++k) {
      applyEmpty();
      if (k == 99) QCOMPARE(bitsOf(cell.b), bitsOf(-0x1p-99f));
      if (k >= 100) QCOMPARE(bitsOf(cell.b), bitsOf(-0x1p-100f));
    }
    QCOMPARE(bitsOf(cell.a), bitsOf(0.0f));
    for (int k = 1; k < 100; ++k) {
      applyOccupied();
      QVERIFY(!filled());
    }
    applyOccupied();
    QVERIFY(filled());
  };
  auto r = rule("dempster-shafer", {}, 11);
  check([&] { r->apply(fp({empty(0, 0.5)})); }, [&] { r->apply(fp({occupied(0, 0.5)})); },
        r->grid.cells<DempsterShaferCell>(0)[0], [&] { return r->filled(0); });

  EvidenceRuns emptyRuns, occupiedRuns;
  for (EvidenceRuns* runs : {&emptyRuns, &occupiedRuns}) {
    const bool isEmpty = runs == &emptyRuns;
    runs->runs.push_back({0, 11, 0});
    runs->empty.assign(11 + kRunPadding, isEmpty ? 0.5f : 0.0f);
    runs->occupied.assign(11 + kRunPadding, isEmpty ? 0.0f : 0.5f);
    runs->probability.assign(11 + kRunPadding, isEmpty ? 0.25f : 0.75f);
  }
  for (const ConeLanes lanes : {ConeLanes::Avx512, ConeLanes::Avx2, ConeLanes::Four}) {
    const ConeLanes previous = testing::limitConeLanes(lanes);
    auto v = rule("dempster-shafer", {}, 11);
    check([&] { v->rule->applyRuns(emptyRuns, v->grid, nullptr); },
          [&] { v->rule->applyRuns(occupiedRuns, v->grid, nullptr); },
          v->grid.cells<DempsterShaferCell>(0)[10], [&] { return v->filled(10); });
    testing::limitConeLanes(previous);
    for (int j = 0; j < 10; ++j) {
      const DempsterShaferCell& c = v->grid.cells<DempsterShaferCell>(0)[j];
      const DempsterShaferCell& last = v->grid.cells<DempsterShaferCell>(0)[10];
      QCOMPARE(bitsOf(c.a), bitsOf(last.a));
      QCOMPARE(bitsOf(c.b), bitsOf(last.b));
    }
  }
}

void TstRules::bayesFloorsTinyProbabilities() {
  // Bayes on the odds: each reading multiplies a cell's odds m/(1 − m) by p/(1 − p) (paper 002 eqs
  // 5–6), and once m is tiny, m itself by the same. With p = 0.2f (the footprint's float) that is
  // r = 0.2f/(1 − 0.2f) = 0.2500000047 a reading: from 0.5, after n readings m = rⁿ/(1 + rⁿ) to
  // some ulps a step, r⁴⁸⁰ = 2⁻⁹⁶⁰ (1 + 9·10⁻⁶) is still above the floor (kBayesFloor = 2⁻⁹⁶⁰)
  // and r⁴⁸¹ is below it: the 481st reading leaves exactly the floor, and so does every one after
  // it (without it m went on through the denormals to 0). Then p = 0.8f, R = 0.8f/(1 − 0.8f) =
  // 4.0000003 a reading: 480 of them bring the odds back to 2⁻⁹⁶⁰ R⁴⁸⁰ = 1.000036, m = 0.500009.
  // Certain evidence (p = 0) leaves the floor, not 0, which nothing could move. Through apply(),
  // and through the run kernels in every lane width the CPU has (11 cells: a group and a short
  // tail), which must give the same bits. (Exact comparisons: QCOMPARE takes any two doubles
  // within 10⁻¹² of 0 as equal.)
  const double floor = cellrule::kBayesFloor;
  QVERIFY(floor == std::ldexp(1.0, -960));
  const double r = double(0.2f) / (1.0 - double(0.2f));
  const double R = double(0.8f) / (1.0 - double(0.8f));
  const auto relativelyNear = [](double a, double b, double tol) {
    return std::abs(a - b) <= tol * std::abs(b);
  };
  const auto check = [&](auto applyEmpty, auto applyOccupied, auto applyCertain, const double& m,
                         const double& certainCell) {
    for (int n = 1; n <= 600; ++n) {
      applyEmpty();
      if (n == 100) QVERIFY(relativelyNear(m, std::pow(r, 100) / (1 + std::pow(r, 100)), 1e-12));
      if (n == 480) {
        QVERIFY(m > floor);
        QVERIFY(relativelyNear(m, std::pow(r, 480), 1e-12));
      }
      if (n >= 481) QVERIFY2(m == floor, qPrintable(QString("%1: %2").arg(n).arg(m, 0, 'g', 17)));
    }
    for (int n = 1; n <= 480; ++n) applyOccupied();
    const double odds = std::ldexp(std::pow(R, 480), -960);
    QVERIFY2(relativelyNear(m, odds / (1 + odds), 1e-9), qPrintable(QString::number(m, 'g', 17)));
    applyCertain();
    QVERIFY(certainCell == floor);
  };
  auto b = rule("bayes-recursive", {}, 11);
  const BayesCell* cells = b->grid.cells<BayesCell>(0);
  check([&] { b->apply(fp({likelihood(0, 0.2)})); }, [&] { b->apply(fp({likelihood(0, 0.8)})); },
        [&] { b->apply(fp({likelihood(1, 0.0)})); }, cells[0].p, cells[1].p);

  EvidenceRuns emptyRuns, occupiedRuns, certainRuns;
  const std::pair<EvidenceRuns*, float> kinds[] = {
      {&emptyRuns, 0.2f}, {&occupiedRuns, 0.8f}, {&certainRuns, 0.0f}};
  for (const auto& [runs, p] : kinds) {
    runs->runs.push_back({0, 11, 0});
    runs->empty.assign(11 + kRunPadding, p < 0.5f ? 1.0f - 2.0f * p : 0.0f);
    runs->occupied.assign(11 + kRunPadding, p > 0.5f ? 2.0f * p - 1.0f : 0.0f);
    runs->probability.assign(11 + kRunPadding, p);
  }
  for (const ConeLanes lanes : {ConeLanes::Avx512, ConeLanes::Avx2, ConeLanes::Four}) {
    const ConeLanes previous = testing::limitConeLanes(lanes);
    auto v = rule("bayes-recursive", {}, 11);
    auto c = rule("bayes-recursive", {}, 11);
    check([&] { v->rule->applyRuns(emptyRuns, v->grid, nullptr); },
          [&] { v->rule->applyRuns(occupiedRuns, v->grid, nullptr); },
          [&] { c->rule->applyRuns(certainRuns, c->grid, nullptr); },
          v->grid.cells<BayesCell>(0)[10].p, c->grid.cells<BayesCell>(0)[10].p);
    testing::limitConeLanes(previous);
    for (int j = 0; j < 10; ++j) {
      QCOMPARE(std::bit_cast<std::uint64_t>(v->grid.cells<BayesCell>(0)[j].p),
               std::bit_cast<std::uint64_t>(v->grid.cells<BayesCell>(0)[10].p));
      QVERIFY(c->grid.cells<BayesCell>(0)[j].p == floor);
    }
  }
}

void TstRules::unseenCellsAreUnknown() {
  for (const std::string& name : updateRuleNames()) {
    auto r = rule(name.c_str(), {}, 4);
    QVERIFY(!r->filled(3));
    // HIMM has no "unknown": CV 0 is both unseen and free (paper 000 §2.2).
    if (name != "himm") NEAR(r->occupancy(3), 0.5);
  }
}

QTEST_GUILESS_MAIN(TstRules)
#include "tst_rules.moc"
