// SPDX-License-Identifier: BSD-3-Clause
// Compiled with -ffp-contract=off (core/CMakeLists.txt): the AVX2 clones must not fuse a multiply
// and an add that the baseline build (x86-64 has no FMA) and the rules' apply() do apart.
// Each kernel takes four consecutive cells at a time in double lanes, the model's floats widened as
// apply() widens them, and repeats cell_updates.h's operations in its order; a lane's `if` is a
// select of the updated and the old value. The last count mod 4 cells (and Dempster–Shafer's cells
// with both kinds of evidence, which no cone model gives) go through cell_updates.h itself.
#include "sonargrid/rules/run_kernels.h"

#include <cstdint>
#include <cstring>

#include "sonargrid/rules/cell_updates.h"

// The clones' resolver (an ifunc) runs while the dynamic loader relocates the program, before a
// sanitizer's runtime is set up, and an instrumented one crashes the program at start; under
// ThreadSanitizer or AddressSanitizer (with UndefinedBehaviorSanitizer in the sanitizer and fuzz
// jobs) the kernels are built once, for the baseline. Clang (14) builds them once too: it ignores
// target_clones on a function declared before without it (run_kernels.h), where GCC clones it.
// The results are the same bits either way.
#if defined(__SANITIZE_THREAD__) || defined(__SANITIZE_ADDRESS__) || defined(__clang__)
#define SG_RUN_CLONES
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer) || __has_feature(address_sanitizer) || \
    __has_feature(undefined_behavior_sanitizer)
#define SG_RUN_CLONES
#endif
#endif
#ifndef SG_RUN_CLONES
#define SG_RUN_CLONES __attribute__((target_clones("default", "avx2")))
#endif

namespace sg::runs {
namespace {

constexpr int W = 4;
using Doubles = double __attribute__((vector_size(8 * W)));
using Floats = float __attribute__((vector_size(4 * W)));

[[gnu::always_inline]] inline Doubles widen(const float* p) {
  Floats f;
  std::memcpy(&f, p, sizeof f);
  return __builtin_convertvector(f, Doubles);
}
[[gnu::always_inline]] inline Doubles load(const void* p) {
  Doubles v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
[[gnu::always_inline]] inline void store(void* p, Doubles v) {
  std::memcpy(p, &v, sizeof v);
}
[[gnu::always_inline]] inline Doubles splat(double x) {
  return Doubles{x, x, x, x};
}
// std::clamp(v, lo, hi) per lane: v < lo ? lo : hi < v ? hi : v.
[[gnu::always_inline]] inline Doubles clamp(Doubles v, double lo, double hi) {
  return v < lo ? splat(lo) : (hi < v ? splat(hi) : v);
}

static_assert(sizeof(EmptyEvidence) == sizeof(double) &&
              sizeof(OccupiedEvidence) == sizeof(double));
static_assert(sizeof(BayesCell) == sizeof(double) && sizeof(LogCell) == sizeof(double));
static_assert(sizeof(LogOddsCell) == sizeof(double));
static_assert(sizeof(DempsterShaferCell) == 2 * sizeof(double));

}  // namespace

SG_RUN_CLONES void additionEmpty(const EvidenceRun& run, EmptyEvidence* emp) {
  const int n = run.count;
  int k = 0;
  for (; k + W <= n; k += W) {
    const Doubles e = widen(run.empty + k);
    const Doubles m = load(emp + k);
    const Doubles updated = m + e - m * e;
    store(emp + k, e > 0.0 ? updated : m);
  }
  for (; k < n; ++k) cellrule::additionEmpty(run.empty[k], emp[k]);
}

SG_RUN_CLONES void additionOccupied(const EvidenceRun& run, OccupiedEvidence* occ) {
  const int n = run.count;
  int k = 0;
  for (; k + W <= n; k += W) {
    const Doubles po = widen(run.occupied + k) * 1.0;  // the scale
    const Doubles m = load(occ + k);
    const Doubles updated = m + po - m * po;
    store(occ + k, po > 0.0 ? updated : m);
  }
  for (; k < n; ++k) cellrule::additionOccupied(run.occupied[k], 1.0, occ[k]);
}

SG_RUN_CLONES void bayes(const EvidenceRun& run, BayesCell* cells, bool likelihood) {
  const int n = run.count;
  auto update = [&](auto probability) {
    int k = 0;
    for (; k + W <= n; k += W) {
      const Doubles p = probability(k);
      const Doubles m = load(cells + k);
      const Doubles num = p * m;
      const Doubles den = num + (1.0 - p) * (1.0 - m);
      store(cells + k, den > 0.0 ? num / den : m);
    }
    return k;
  };
  int k = 0;
  if (likelihood) {
    k = update([&](int i) { return widen(run.probability + i); });
    for (; k < n; ++k) cellrule::bayes(static_cast<double>(run.probability[k]), cells[k]);
  } else {
    k = update([&](int i) { return 0.5 + 0.5 * (widen(run.occupied + i) - widen(run.empty + i)); });
    for (; k < n; ++k)
      cellrule::bayes(cellrule::bayesEvidence(run.empty[k], run.occupied[k]), cells[k]);
  }
}

SG_RUN_CLONES void logProduct(const EvidenceRun& run, LogCell* cells) {
  const int n = run.count;
  int k = 0;
  for (; k + W <= n; k += W) {
    const Doubles factor = (1.0 - widen(run.empty + k)) * (1.0 + widen(run.occupied + k));
    const Doubles m = load(cells + k) * factor;
    const auto tiny = (m < cellrule::kLogLow) & (m > 0.0);
    store(cells + k, m > cellrule::kLogHigh ? splat(cellrule::kLogHigh)
                                            : (tiny ? splat(cellrule::kLogLow) : m));
  }
  for (; k < n; ++k) cellrule::logProduct(run.empty[k], run.occupied[k], cells[k]);
}

SG_RUN_CLONES void logOdds(const EvidenceRun& run, LogOddsCell* cells, double invPrior,
                           double minOdds, double maxOdds) {
  const int n = run.count;
  int k = 0;
  for (; k + W <= n; k += W) {
    const Doubles p = clamp(widen(run.probability + k), cellrule::kProbabilityFloor,
                            1.0 - cellrule::kProbabilityFloor);
    const Doubles o = load(cells + k);
    store(cells + k, clamp(o * (p / (1.0 - p)) * invPrior, minOdds, maxOdds));
  }
  for (; k < n; ++k) cellrule::logOdds(run.probability[k], invPrior, minOdds, maxOdds, cells[k]);
}

SG_RUN_CLONES void dempsterShafer(const EvidenceRun& run, DempsterShaferCell* cells) {
  const int n = run.count;
  int k = 0;
  for (; k + W <= n; k += W) {
    const Doubles o = clamp(widen(run.occupied + k), 0.0, 1.0);
    const Doubles e = clamp(widen(run.empty + k), 0.0, 1.0);
    const Doubles lo = load(cells + k), hi = load(cells + k + 2);
    const Doubles mo = __builtin_shufflevector(lo, hi, 0, 2, 4, 6);
    const Doubles me = __builtin_shufflevector(lo, hi, 1, 3, 5, 7);
    // One kind of evidence x: occupied (e = 0, cellrule's first case) or empty (o = 0, its
    // second); `grow` is the mass x adds to, `shrink` the other.
    const auto onlyOccupied = e == 0.0;
    const auto onlyEmpty = o == 0.0;
    const Doubles x = onlyOccupied ? o : e;
    const Doubles grow = onlyOccupied ? mo : me;
    const Doubles shrink = onlyOccupied ? me : mo;
    const Doubles denominator = 1.0 - shrink * x;
    const Doubles inv = 1.0 / denominator;
    const Doubles mu = 1.0 - mo - me;
    const Doubles grown = (grow + mu * x) * inv;
    const Doubles shrunk = shrink * (1.0 - x) * inv;
    // Total conflict (denominator <= 0) keeps the masses, as does a lane of both kinds, done
    // below by cellrule.
    const auto general = ~(onlyOccupied | onlyEmpty);
    const auto keep = (denominator <= 0.0) | general;
    const Doubles newOcc = keep ? mo : (onlyOccupied ? grown : shrunk);
    const Doubles newEmp = keep ? me : (onlyOccupied ? shrunk : grown);
    store(cells + k, __builtin_shufflevector(newOcc, newEmp, 0, 4, 1, 5));
    store(cells + k + 2, __builtin_shufflevector(newOcc, newEmp, 2, 6, 3, 7));
    for (int j = 0; j < W; ++j) {
      if (general[j]) cellrule::dempsterShafer(run.occupied[k + j], run.empty[k + j], cells[k + j]);
    }
  }
  for (; k < n; ++k) cellrule::dempsterShafer(run.occupied[k], run.empty[k], cells[k]);
}

}  // namespace sg::runs
