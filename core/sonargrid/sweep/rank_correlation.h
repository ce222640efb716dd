// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Spearman's rank correlation with average ranks for ties, and a percentile bootstrap confidence
// interval for it: what `sonargrid-cli goodness-study` (docs/goodness-study.md) reports between a
// reference-free goodness measure and a reference metric over the sets of a sweep.
//
// Determinism: replicate r of a bootstrap draws its resample from its own generator, seeded from
// (seed, r) alone (bootstrapSampleSeed), and the replicates are computed on the thread policy's
// threads (concurrency.h) into fixed slots. The interval is therefore the same bits at any thread
// count and on every platform (SeededRandom maps bits to indices itself).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <vector>

namespace sg {

// Non-finite input, x and y of different lengths, a percentile outside [0, 1]...
class RankCorrelationError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// The 1-based ranks of `values`; tied values each get the mean of the ranks they span (ranks 3 and
// 4 tied: 3.5 each). Throws RankCorrelationError for a NaN or infinity.
std::vector<double> averageRanks(std::span<const double> values);

// Spearman's ρ: Pearson's correlation of the average ranks of x and of y (the definition that
// stays exact with ties; 1 − 6Σd²/(n(n²−1)) is exact only without them). Empty when n < 2 or when
// either side is constant (no rank varies). Throws RankCorrelationError for unequal lengths or
// non-finite values.
std::optional<double> spearman(std::span<const double> x, std::span<const double> y);

// The p-quantile of `values` (0 ≤ p ≤ 1) by linear interpolation between order statistics
// (Hyndman & Fan 1996, type 7: h = (n − 1)·p, between the ⌊h⌋-th and ⌈h⌉-th smallest, 0-based; R's
// default and NumPy's). Throws RankCorrelationError for no values or p outside [0, 1].
double percentile(std::vector<double> values, double p);

// The generator seed of bootstrap replicate `replicate` under `seed`: output number replicate + 1
// of SplitMix64 (Steele, Lea & Flood 2014) started from `seed`, so that neighbouring replicates and
// seeds draw unrelated streams and any replicate is found without drawing the ones before it.
std::uint64_t bootstrapSampleSeed(std::uint64_t seed, std::size_t replicate);

// Replicate `replicate`'s resample of n items: n indices drawn uniformly with replacement from
// [0, n) by SeededRandom(bootstrapSampleSeed(seed, replicate)).
std::vector<std::size_t> bootstrapSample(std::uint64_t seed, std::size_t replicate, std::size_t n);

struct SpearmanBootstrap {
  std::optional<double> rho;  // spearman(x, y) of the data as given
  // The percentile interval: the (1 − level)/2 and (1 + level)/2 percentiles of ρ over the
  // replicates where it is defined. Empty without replicates or when none was defined.
  std::optional<double> lo;
  std::optional<double> hi;
  std::size_t replicates = 0;  // asked for
  std::size_t defined = 0;     // replicates whose resample had ρ defined (not constant)
};

// ρ of (x, y) and its percentile bootstrap interval over `replicates` resamples of the n pairs
// (bootstrapSample(seed, r, n) for r = 0 .. replicates − 1; pairs stay together), at confidence
// `level` (0 < level < 1; 0.95 for a 95 % interval). A resample whose x or y is constant has no ρ
// and is left out of the percentiles (`defined` says how many counted). Computed on the thread
// policy's threads; the same result at any count. Throws RankCorrelationError as spearman() does
// and for a level outside (0, 1).
SpearmanBootstrap bootstrapSpearman(std::span<const double> x, std::span<const double> y,
                                    std::size_t replicates, std::uint64_t seed,
                                    double level = 0.95);

}  // namespace sg
