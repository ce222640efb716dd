// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/sweep/rank_correlation.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include "sonargrid/base/concurrency.h"
#include "sonargrid/metrics/seeded_random.h"

namespace sg {
namespace {

void requireFinite(std::span<const double> values) {
  for (double v : values) {
    if (!std::isfinite(v))
      throw RankCorrelationError("rank correlation of a NaN or infinite value");
  }
}

// ρ of two rank vectors of equal length n ≥ 2: Pearson's correlation.
std::optional<double> pearsonOfRanks(const std::vector<double>& rx, const std::vector<double>& ry) {
  const std::size_t n = rx.size();
  if (n < 2) return std::nullopt;
  double mx = 0.0, my = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    mx += rx[i];
    my += ry[i];
  }
  mx /= static_cast<double>(n);
  my /= static_cast<double>(n);
  double sxy = 0.0, sxx = 0.0, syy = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double dx = rx[i] - mx;
    const double dy = ry[i] - my;
    sxy += dx * dy;
    sxx += dx * dx;
    syy += dy * dy;
  }
  if (sxx == 0.0 || syy == 0.0) return std::nullopt;
  return std::clamp(sxy / std::sqrt(sxx * syy), -1.0, 1.0);
}

}  // namespace

std::vector<double> averageRanks(std::span<const double> values) {
  requireFinite(values);
  const std::size_t n = values.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
  std::vector<double> ranks(n);
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i + 1;
    while (j < n && values[order[j]] == values[order[i]]) ++j;
    // Positions i .. j − 1 (0-based) hold ranks i + 1 .. j: their mean is (i + 1 + j) / 2.
    const double rank = static_cast<double>(i + 1 + j) / 2.0;
    for (std::size_t k = i; k < j; ++k) ranks[order[k]] = rank;
    i = j;
  }
  return ranks;
}

std::optional<double> spearman(std::span<const double> x, std::span<const double> y) {
  if (x.size() != y.size())
    throw RankCorrelationError("rank correlation of " + std::to_string(x.size()) + " and " +
                               std::to_string(y.size()) + " values");
  return pearsonOfRanks(averageRanks(x), averageRanks(y));
}

double percentile(std::vector<double> values, double p) {
  if (values.empty()) throw RankCorrelationError("a percentile of no values");
  if (!(p >= 0.0 && p <= 1.0)) throw RankCorrelationError("a percentile outside [0, 1]");
  requireFinite(values);
  std::sort(values.begin(), values.end());
  const double h = static_cast<double>(values.size() - 1) * p;
  const auto below = static_cast<std::size_t>(std::floor(h));
  const std::size_t above = std::min(below + 1, values.size() - 1);
  return values[below] + (h - static_cast<double>(below)) * (values[above] - values[below]);
}

std::uint64_t bootstrapSampleSeed(std::uint64_t seed, std::size_t replicate) {
  // SplitMix64: the state advances by the golden gamma before each output.
  std::uint64_t z = seed + (static_cast<std::uint64_t>(replicate) + 1) * 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

std::vector<std::size_t> bootstrapSample(std::uint64_t seed, std::size_t replicate, std::size_t n) {
  std::vector<std::size_t> out(n);
  if (n == 0) return out;
  SeededRandom random(bootstrapSampleSeed(seed, replicate));
  for (std::size_t& i : out) i = static_cast<std::size_t>(random.below(n));
  return out;
}

SpearmanBootstrap bootstrapSpearman(std::span<const double> x, std::span<const double> y,
                                    std::size_t replicates, std::uint64_t seed, double level) {
  if (!(level > 0.0 && level < 1.0))
    throw RankCorrelationError("a confidence level outside (0, 1)");
  SpearmanBootstrap out;
  out.rho = spearman(x, y);  // checks lengths and values
  out.replicates = replicates;
  const std::size_t n = x.size();
  if (replicates == 0 || n == 0) return out;

  // Slot r holds replicate r's ρ (NaN: undefined), whichever thread computed it.
  std::vector<double> rhos(replicates, std::numeric_limits<double>::quiet_NaN());
  std::atomic<bool> stop{false};
  const auto threads =
      static_cast<unsigned>(std::clamp<std::size_t>(replicates, 1, parallelThreads()));
  auto work = [&](unsigned t) {
    std::vector<double> xs(n), ys(n);
    for (std::size_t r = t; r < replicates && !stop.load(std::memory_order_relaxed); r += threads) {
      const std::vector<std::size_t> sample = bootstrapSample(seed, r, n);
      for (std::size_t k = 0; k < n; ++k) {
        xs[k] = x[sample[k]];
        ys[k] = y[sample[k]];
      }
      if (const std::optional<double> rho = spearman(xs, ys)) rhos[r] = *rho;
    }
  };
  runParallel(threads, work, [&] { stop.store(true); });

  std::vector<double> defined;
  defined.reserve(replicates);
  for (double r : rhos) {
    if (!std::isnan(r)) defined.push_back(r);
  }
  out.defined = defined.size();
  if (defined.empty()) return out;
  out.lo = percentile(defined, (1.0 - level) / 2.0);
  out.hi = percentile(std::move(defined), (1.0 + level) / 2.0);
  return out;
}

}  // namespace sg
