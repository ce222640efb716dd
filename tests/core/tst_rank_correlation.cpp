// SPDX-License-Identifier: BSD-3-Clause
// Spearman's ρ with average ranks, the type-7 percentile and the percentile bootstrap of
// rank_correlation.h (the statistics of `sonargrid-cli goodness-study`, docs/goodness-study.md).
// Every expected value is worked by hand in the row's comment.

#include <QtTest>
#include <cmath>
#include <limits>
#include <vector>

#include "sonargrid/base/concurrency.h"
#include "sonargrid/sweep/rank_correlation.h"

using sg::RankCorrelationError;

using Doubles = std::vector<double>;
Q_DECLARE_METATYPE(Doubles)

class TstRankCorrelation : public QObject {
  Q_OBJECT

 private slots:
  void averageRanks_data();
  void averageRanks();
  void spearman_data();
  void spearman();
  void spearmanUndefined_data();
  void spearmanUndefined();
  void percentile_data();
  void percentile();
  void splitMixSeeds();
  void bootstrapSampleInRange();
  void bootstrapMonotone_data();
  void bootstrapMonotone();
  void bootstrapTwoPairs();
  void bootstrapEqualsItsResamples();
  void badInput();
};

void TstRankCorrelation::averageRanks_data() {
  QTest::addColumn<Doubles>("values");
  QTest::addColumn<Doubles>("ranks");
  // Sorted: 5 (rank 1), 10 (2), 20 and 20 (ranks 3 and 4, each (3 + 4) / 2 = 3.5).
  QTest::newRow("a tie in the middle") << Doubles{10, 20, 20, 5} << Doubles{2, 3.5, 3.5, 1};
  // All three tied: ranks 1, 2, 3 averaged, 2 each.
  QTest::newRow("all tied") << Doubles{3, 3, 3} << Doubles{2, 2, 2};
  // Two ties: -1 (rank 1), 0.5 and 0.5 (ranks 2, 3 → 2.5), 7, 7, 7 (ranks 4, 5, 6 → 5).
  QTest::newRow("two ties") << Doubles{7, 0.5, -1, 7, 0.5, 7} << Doubles{5, 2.5, 1, 5, 2.5, 5};
  QTest::newRow("one value") << Doubles{42} << Doubles{1};
  QTest::newRow("none") << Doubles{} << Doubles{};
}

void TstRankCorrelation::averageRanks() {
  QFETCH(Doubles, values);
  QFETCH(Doubles, ranks);
  QCOMPARE(sg::averageRanks(values), ranks);
}

void TstRankCorrelation::spearman_data() {
  QTest::addColumn<Doubles>("x");
  QTest::addColumn<Doubles>("y");
  QTest::addColumn<double>("rho");
  // x = 1..5, y = 5, 6, 7, 8, 7. Ranks: rx = 1, 2, 3, 4, 5; ry = 1, 2, 3.5, 5, 3.5 (the two 7s
  // share ranks 3 and 4). Both means are 3. dx = −2, −1, 0, 1, 2; dy = −2, −1, 0.5, 2, 0.5.
  // Σ dx·dy = 4 + 1 + 0 + 2 + 1 = 8; Σ dx² = 10; Σ dy² = 4 + 1 + 0.25 + 4 + 0.25 = 9.5.
  // ρ = 8 / √(10 · 9.5) = 8 / √95 = 0.820782681668... The shortcut 1 − 6Σd²/(n(n² − 1)), with
  // d = rx − ry = 0, 0, −0.5, −1, 1.5 and Σd² = 3.5, gives 1 − 21/120 = 0.825: it is exact only
  // without ties, so the tie-averaged ρ is 0.8208, not 0.825 (scipy.stats.spearmanr agrees).
  QTest::newRow("ties averaged") << Doubles{1, 2, 3, 4, 5} << Doubles{5, 6, 7, 8, 7}
                                 << 8.0 / std::sqrt(95.0);
  // Monotone increasing though not linear: the ranks are equal, ρ = 1.
  QTest::newRow("perfect monotone") << Doubles{1, 2, 3, 4, 5} << Doubles{2, 4, 8, 16, 32} << 1.0;
  // Reversed: ry = 6 − rx, ρ = −1.
  QTest::newRow("reversed") << Doubles{0.1, 0.2, 0.3, 0.4, 0.5} << Doubles{50, 40, 30, 20, 10}
                            << -1.0;
  // No ties: d = −1, 1, −1, 1, 0, Σd² = 4, ρ = 1 − 6·4 / (5·24) = 0.8 (the shortcut is exact here).
  QTest::newRow("no ties") << Doubles{1, 2, 3, 4, 5} << Doubles{2, 1, 4, 3, 5} << 0.8;
  // Ties on both sides: rx = 1.5, 1.5, 3.5, 3.5 and ry = 1.5, 3.5, 1.5, 3.5; dx = −1, −1, 1, 1 and
  // dy = −1, 1, −1, 1, Σ dx·dy = 1 − 1 − 1 + 1 = 0: ρ = 0.
  QTest::newRow("uncorrelated ties") << Doubles{1, 1, 2, 2} << Doubles{1, 2, 1, 2} << 0.0;
  // Order of the pairs does not matter: the "ties averaged" row shuffled.
  QTest::newRow("shuffled") << Doubles{4, 1, 5, 3, 2} << Doubles{8, 5, 7, 7, 6}
                            << 8.0 / std::sqrt(95.0);
}

void TstRankCorrelation::spearman() {
  QFETCH(Doubles, x);
  QFETCH(Doubles, y);
  QFETCH(double, rho);
  const std::optional<double> got = sg::spearman(x, y);
  QVERIFY(got.has_value());
  QVERIFY2(std::abs(*got - rho) < 1e-12, qPrintable(QString::number(*got, 'g', 17)));
  // Symmetric in x and y.
  QVERIFY(std::abs(*sg::spearman(y, x) - rho) < 1e-12);
}

void TstRankCorrelation::spearmanUndefined_data() {
  QTest::addColumn<Doubles>("x");
  QTest::addColumn<Doubles>("y");
  // A constant side has no varying rank: Σ dy² = 0, ρ undefined.
  QTest::newRow("constant y") << Doubles{1, 2, 3} << Doubles{4, 4, 4};
  QTest::newRow("constant x") << Doubles{7, 7} << Doubles{1, 2};
  QTest::newRow("one pair") << Doubles{1} << Doubles{2};
  QTest::newRow("none") << Doubles{} << Doubles{};
}

void TstRankCorrelation::spearmanUndefined() {
  QFETCH(Doubles, x);
  QFETCH(Doubles, y);
  QVERIFY(!sg::spearman(x, y).has_value());
}

void TstRankCorrelation::percentile_data() {
  QTest::addColumn<Doubles>("values");
  QTest::addColumn<double>("p");
  QTest::addColumn<double>("expected");
  // Sorted 1, 2, 3, 4 (given unsorted); h = (4 − 1)·p between the ⌊h⌋-th and ⌈h⌉-th (0-based).
  const Doubles four{4, 1, 3, 2};
  QTest::newRow("p 0") << four << 0.0 << 1.0;       // h = 0: the smallest
  QTest::newRow("p 0.25") << four << 0.25 << 1.75;  // h = 0.75: 1 + 0.75·(2 − 1)
  QTest::newRow("p 0.5") << four << 0.5 << 2.5;     // h = 1.5: 2 + 0.5·(3 − 2)
  QTest::newRow("p 1") << four << 1.0 << 4.0;       // h = 3: the largest
  QTest::newRow("p 0.025 of 0..40") << Doubles{0, 10, 20, 30, 40} << 0.025 << 1.0;   // h = 0.1
  QTest::newRow("p 0.975 of 0..40") << Doubles{0, 10, 20, 30, 40} << 0.975 << 39.0;  // h = 3.9
  QTest::newRow("one value") << Doubles{-3} << 0.3 << -3.0;
}

void TstRankCorrelation::percentile() {
  QFETCH(Doubles, values);
  QFETCH(double, p);
  QFETCH(double, expected);
  QVERIFY(std::abs(sg::percentile(values, p) - expected) < 1e-12);
}

void TstRankCorrelation::splitMixSeeds() {
  // SplitMix64 started from 0: its first three outputs are the published reference values of
  // Vigna's splitmix64.c (0xe220a8397b1dcdaf, 0x6e789e6aa1b965f4, 0x06c45d188009454f).
  QCOMPARE(sg::bootstrapSampleSeed(0, 0), std::uint64_t{0xe220a8397b1dcdafULL});
  QCOMPARE(sg::bootstrapSampleSeed(0, 1), std::uint64_t{0x6e789e6aa1b965f4ULL});
  QCOMPARE(sg::bootstrapSampleSeed(0, 2), std::uint64_t{0x06c45d188009454fULL});
}

void TstRankCorrelation::bootstrapSampleInRange() {
  // n indices, each in [0, n); the same for the same (seed, replicate); another replicate or seed
  // draws another resample (for n = 50 two equal resamples have chance 50^-50).
  const std::vector<std::size_t> a = sg::bootstrapSample(7, 3, 50);
  QCOMPARE(a.size(), std::size_t{50});
  for (std::size_t i : a) QVERIFY(i < 50);
  QVERIFY(a == sg::bootstrapSample(7, 3, 50));
  QVERIFY(a != sg::bootstrapSample(7, 4, 50));
  QVERIFY(a != sg::bootstrapSample(8, 3, 50));
  QVERIFY(sg::bootstrapSample(1, 0, 0).empty());
}

void TstRankCorrelation::bootstrapMonotone_data() {
  QTest::addColumn<Doubles>("y");
  QTest::addColumn<double>("rho");
  // Every resample of a monotone relation keeps it (pairs stay together): each defined replicate
  // has ρ = ±1, so both ends of the interval are ±1.
  QTest::newRow("increasing") << Doubles{1, 3, 4, 8, 9, 11, 20, 21} << 1.0;
  QTest::newRow("decreasing") << Doubles{21, 20, 11, 9, 8, 4, 3, 1} << -1.0;
}

void TstRankCorrelation::bootstrapMonotone() {
  QFETCH(Doubles, y);
  QFETCH(double, rho);
  const Doubles x{1, 2, 3, 4, 5, 6, 7, 8};
  const sg::SpearmanBootstrap b = sg::bootstrapSpearman(x, y, 500, 1);
  QCOMPARE(*b.rho, rho);
  QCOMPARE(b.replicates, std::size_t{500});
  // A resample drawing one pair 8 times is constant: chance 8 · 8^-8 each, so all 500 count.
  QCOMPARE(b.defined, std::size_t{500});
  QCOMPARE(*b.lo, rho);
  QCOMPARE(*b.hi, rho);
}

void TstRankCorrelation::bootstrapTwoPairs() {
  // Two pairs (1, 1), (2, 2): a resample drawing both has ρ = 1, one drawing the same pair twice
  // is constant and undefined. `defined` counts the first kind, found from the resamples
  // themselves.
  const Doubles x{1, 2};
  const std::size_t replicates = 200;
  const sg::SpearmanBootstrap b = sg::bootstrapSpearman(x, x, replicates, 99);
  std::size_t both = 0;
  for (std::size_t r = 0; r < replicates; ++r) {
    const std::vector<std::size_t> s = sg::bootstrapSample(99, r, 2);
    if (s[0] != s[1]) ++both;
  }
  QCOMPARE(b.defined, both);
  QVERIFY(both > 50 && both < 150);  // binomial(200, 1/2): 100 ± 7
  QCOMPARE(*b.lo, 1.0);
  QCOMPARE(*b.hi, 1.0);
  QVERIFY(!sg::bootstrapSpearman(x, x, 0, 99).lo.has_value());  // no replicates, no interval
}

void TstRankCorrelation::bootstrapEqualsItsResamples() {
  // A noisy relation with ties: the interval is the 2.5th and 97.5th type-7 percentiles of ρ over
  // the resamples bootstrapSample gives, recomputed here one by one; the same bits at 1, 2 and 3
  // threads.
  Doubles x, y;
  for (int i = 0; i < 30; ++i) {
    x.push_back(i % 7);                    // ties in x
    y.push_back((i * 13) % 11 + i / 3.0);  // a trend with noise
  }
  const std::size_t replicates = 300;
  const std::uint64_t seed = 2026;
  Doubles rhos;
  for (std::size_t r = 0; r < replicates; ++r) {
    Doubles xs, ys;
    for (std::size_t i : sg::bootstrapSample(seed, r, x.size())) {
      xs.push_back(x[i]);
      ys.push_back(y[i]);
    }
    if (const auto rho = sg::spearman(xs, ys)) rhos.push_back(*rho);
  }
  const double lo = sg::percentile(rhos, 0.025);
  const double hi = sg::percentile(rhos, 0.975);
  QVERIFY(lo < hi);
  for (unsigned threads : {1u, 2u, 3u}) {
    const sg::ScopedThreadCount scoped(threads);
    const sg::SpearmanBootstrap b = sg::bootstrapSpearman(x, y, replicates, seed);
    QCOMPARE(b.defined, rhos.size());
    QCOMPARE(*b.lo, lo);
    QCOMPARE(*b.hi, hi);
    QCOMPARE(*b.rho, *sg::spearman(x, y));
    QVERIFY(*b.lo <= *b.rho && *b.rho <= *b.hi);
  }
  // A 50 % interval lies inside the 95 % one.
  const sg::SpearmanBootstrap half = sg::bootstrapSpearman(x, y, replicates, seed, 0.5);
  QVERIFY(*half.lo >= lo && *half.hi <= hi);
}

void TstRankCorrelation::badInput() {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  QVERIFY_THROWS_EXCEPTION(RankCorrelationError, sg::spearman(Doubles{1, 2}, Doubles{1}));
  QVERIFY_THROWS_EXCEPTION(RankCorrelationError, sg::spearman(Doubles{1, nan}, Doubles{1, 2}));
  QVERIFY_THROWS_EXCEPTION(RankCorrelationError, sg::averageRanks(Doubles{1, INFINITY}));
  QVERIFY_THROWS_EXCEPTION(RankCorrelationError, sg::percentile(Doubles{}, 0.5));
  QVERIFY_THROWS_EXCEPTION(RankCorrelationError, sg::percentile(Doubles{1}, 1.5));
  QVERIFY_THROWS_EXCEPTION(RankCorrelationError,
                           sg::bootstrapSpearman(Doubles{1, 2}, Doubles{1, 2}, 10, 1, 1.0));
}

QTEST_GUILESS_MAIN(TstRankCorrelation)
#include "tst_rank_correlation.moc"
