// SPDX-License-Identifier: BSD-3-Clause
// Compiled with -ffp-contract=off (core/CMakeLists.txt): the AVX2 clones must not fuse a multiply
// and an add that the baseline build (x86-64 has no FMA) and the rules' apply() do apart.
// Each kernel takes four cells at a time in double lanes (four consecutive cells of a run, or four
// listed cells gathered from the plane and scattered back), the model's floats widened as apply()
// widens them, and repeats cell_updates.h's operations in its order; a lane's `if` is a select of
// the updated and the old value. Addition's single-precision cells are widened on load and rounded
// to float on store, as cell_updates.h does one cell at a time. Dempster–Shafer's cells with both
// kinds of evidence (which no model gives) go through cell_updates.h itself, one at a time.
#include "sonargrid/rules/run_kernels.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <span>
#include <type_traits>

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
// A kernel's lambdas are inlined into each clone: one left out of line is built for the baseline,
// its 32-byte vectors passed through memory (GCC did so with Dempster–Shafer's, 4 × slower).
#if defined(__GNUC__) && !defined(__clang__)
#define SG_INLINE_LAMBDA __attribute__((always_inline))
#else
#define SG_INLINE_LAMBDA
#endif

namespace sg::runs {
namespace {

constexpr int W = 4;  // written out as four in the gathers and scatters below
using Doubles = double __attribute__((vector_size(8 * W)));
using Floats = float __attribute__((vector_size(4 * W)));

[[gnu::always_inline]] inline Doubles widen(const void* p) {
  Floats f;
  std::memcpy(&f, p, sizeof f);
  return __builtin_convertvector(f, Doubles);
}
// W doubles rounded to float (as static_cast<float> rounds each) and stored at p.
[[gnu::always_inline]] inline void narrow(void* p, Doubles v) {
  const Floats f = __builtin_convertvector(v, Floats);
  std::memcpy(p, &f, sizeof f);
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
// Whether any lane of a comparison's result is set: one test where looking at each lane was four.
using Mask = decltype(Doubles{} == Doubles{});
[[gnu::always_inline]] inline bool anyLane(Mask m) {
  std::uint64_t lane[W];
  std::memcpy(lane, &m, sizeof lane);
  static_assert(sizeof lane == sizeof m && W == 4);
  return (lane[0] | lane[1] | lane[2] | lane[3]) != 0;
}
// std::clamp(v, lo, hi) per lane: v < lo ? lo : hi < v ? hi : v, which is what std::clamp gives
// for any v (NaN and ±0 included) when lo <= hi.
[[gnu::always_inline]] inline Doubles clamp(Doubles v, double lo, double hi) {
  return v < lo ? splat(lo) : (hi < v ? splat(hi) : v);
}

// `Bytes` bytes from src to dst in moves of W doubles where they fit: a run's last cells are copied
// to `last` and the lanes then load them with one such move, which the CPU forwards from a store
// of the same size (memcpy stored them as two halves, and the wide load after them stalled).
template <std::size_t Bytes>
[[gnu::always_inline]] inline void copyLanes(void* dst, const void* src) {
  if constexpr (Bytes % sizeof(Doubles) == 0) {
    for (std::size_t i = 0; i < Bytes; i += sizeof(Doubles))
      store(static_cast<char*>(dst) + i, load(static_cast<const char*>(src) + i));
  } else {
    std::memcpy(dst, src, Bytes);
  }
}

// group(empty, occupied, probability, cells) for every W consecutive cells of every run: W values
// from each array, W cells to update in place. No lane touches a cell past its run (another
// row's, perhaps another thread's): a run's last count mod W cells are updated as part of its last
// W cells, computed on a copy of their values from before the run's other groups (so that the
// cells both cover get the same value from either) and copied back at the end; a run shorter
// than W is updated on a copy padded with its first cell. The values past a run that the padding
// lanes read are ignored.
template <class Cell, class Group>
[[gnu::always_inline]] inline void eachGroup(const EvidenceRuns& runs, Cell* plane, Group&& group) {
  const float* const empty = runs.empty.data();
  const float* const occupied = runs.occupied.data();
  const float* const probability = runs.probability.data();
  for (const EvidenceRuns::Run& run : runs.runs) {
    Cell* const cells = plane + run.cell;
    const std::size_t v = run.first;
    const int n = run.count;
    Cell last[W];
    if (n < W) {
      for (int j = 0; j < W; ++j) last[j] = cells[j < n ? j : 0];
      group(empty + v, occupied + v, probability + v, last);
      for (int j = 0; j < n; ++j) cells[j] = last[j];
      continue;
    }
    const int tail = n % W == 0 ? -1 : n - W;  // the first of the last W cells, when apart
    if (tail >= 0) {
      copyLanes<sizeof last>(last, cells + tail);
      group(empty + v + tail, occupied + v + tail, probability + v + tail, last);
    }
    for (int k = 0; k + W <= n; k += W)
      group(empty + v + k, occupied + v + k, probability + v + k, cells + k);
    if (tail >= 0) copyLanes<sizeof last>(cells + tail, last);
  }
}

// update(m) for every cell of `cells` (distinct grid indices into `plane`, one double a cell): W
// cells at a time, gathered into lanes and scattered back; the last cells.size() mod W by
// one(cell).
template <class Cell, class Lanes, class One>
[[gnu::always_inline]] inline void eachListed(std::span<const std::uint32_t> cells, Cell* plane,
                                              Lanes&& update, One&& one) {
  static_assert(sizeof(Cell) == sizeof(double) && W == 4);
  const std::uint32_t* c = cells.data();
  const std::uint32_t* const end = c + cells.size();
  for (; end - c >= W; c += W) {
    double v[W];
    for (int j = 0; j < W; ++j) std::memcpy(&v[j], plane + c[j], sizeof(double));
    const Doubles m = update(Doubles{v[0], v[1], v[2], v[3]});
    // Written out: a loop over j went through the stack (a 32-byte store, four 8-byte loads).
    const double m0 = m[0], m1 = m[1], m2 = m[2], m3 = m[3];
    std::memcpy(plane + c[0], &m0, sizeof(double));
    std::memcpy(plane + c[1], &m1, sizeof(double));
    std::memcpy(plane + c[2], &m2, sizeof(double));
    std::memcpy(plane + c[3], &m3, sizeof(double));
  }
  for (; c != end; ++c) one(plane[*c]);
}

// Dempster's rule for one kind of evidence x per lane (cellrule::dempsterShafer's first two
// cases): `grow` is the mass x adds to, `shrink` the other, `mu` the unknown mass. The masses
// before the rule's total-conflict test, which the caller applies (denominator <= 0 keeps them).
struct OneKind {
  Doubles grown, shrunk, denominator;
};
[[gnu::always_inline]] inline OneKind oneKind(Doubles grow, Doubles shrink, Doubles mu, Doubles x) {
  const Doubles denominator = 1.0 - shrink * x;
  const Doubles inv = 1.0 / denominator;
  return {(grow + mu * x) * inv, shrink * (1.0 - x) * inv, denominator};
}

// Dempster–Shafer's general case, for a cell with both kinds of evidence (no cone model gives one):
// a call, so that the kernel's lanes stay small enough to inline.
[[gnu::noinline]] void generalDempsterShafer(float occupied, float empty,
                                             DempsterShaferCell& cell) {
  cellrule::dempsterShafer(occupied, empty, cell);
}

static_assert(sizeof(EmptyEvidence) == sizeof(float) && sizeof(OccupiedEvidence) == sizeof(float));
static_assert(sizeof(BayesCell) == sizeof(double) && sizeof(LogCell) == sizeof(double));
static_assert(sizeof(LogOddsCell) == sizeof(double));
static_assert(sizeof(DempsterShaferCell) == 2 * sizeof(double));

}  // namespace

SG_RUN_CLONES void additionEmpty(const EvidenceRuns& runs, EmptyEvidence* emp) {
  eachGroup(runs, emp,
            [](const float* empty, const float*, const float*, EmptyEvidence* cells)
                SG_INLINE_LAMBDA {
                  const Doubles e = widen(empty);
                  const Doubles m = widen(cells);
                  narrow(cells, e > 0.0 ? m + e - m * e : m);
                });
}

SG_RUN_CLONES void additionOccupied(const EvidenceRuns& runs, OccupiedEvidence* occ) {
  eachGroup(runs, occ,
            [](const float*, const float* occupied, const float*, OccupiedEvidence* cells)
                SG_INLINE_LAMBDA {
                  const Doubles po = widen(occupied) * 1.0;  // the scale
                  const Doubles m = widen(cells);
                  narrow(cells, po > 0.0 ? m + po - m * po : m);
                });
}

SG_RUN_CLONES void bayes(const EvidenceRuns& runs, BayesCell* plane, bool likelihood) {
  auto update = [](Doubles p, BayesCell* cells) SG_INLINE_LAMBDA {
    const Doubles m = load(cells);
    const Doubles num = p * m;
    const Doubles den = num + (1.0 - p) * (1.0 - m);
    store(cells, den > 0.0 ? num / den : m);
  };
  if (likelihood) {
    eachGroup(runs, plane,
              [&](const float*, const float*, const float* probability, BayesCell* cells)
                  SG_INLINE_LAMBDA { update(widen(probability), cells); });
  } else {
    eachGroup(
        runs, plane,
        [&](const float* empty, const float* occupied, const float*, BayesCell* cells)
            SG_INLINE_LAMBDA { update(0.5 + 0.5 * (widen(occupied) - widen(empty)), cells); });
  }
}

SG_RUN_CLONES void bayesUniform(double p, std::span<const std::uint32_t> cells, BayesCell* plane) {
  eachListed(
      cells, plane,
      [p](Doubles m) SG_INLINE_LAMBDA {
        const Doubles num = p * m;
        const Doubles den = num + (1.0 - p) * (1.0 - m);
        return den > 0.0 ? num / den : m;
      },
      [p](BayesCell& cell) SG_INLINE_LAMBDA { cellrule::bayes(p, cell); });
}

SG_RUN_CLONES void logProduct(const EvidenceRuns& runs, LogCell* plane) {
  eachGroup(runs, plane,
            [](const float* empty, const float* occupied, const float*, LogCell* cells)
                SG_INLINE_LAMBDA {
                  const Doubles m = load(cells) * ((1.0 - widen(empty)) * (1.0 + widen(occupied)));
                  const auto tiny = (m < cellrule::kLogLow) & (m > 0.0);
                  store(cells, m > cellrule::kLogHigh ? splat(cellrule::kLogHigh)
                                                      : (tiny ? splat(cellrule::kLogLow) : m));
                });
}

SG_RUN_CLONES void logOdds(const EvidenceRuns& runs, LogOddsCell* plane, double invPrior,
                           double minOdds, double maxOdds) {
  eachGroup(runs, plane,
            [=](const float*, const float*, const float* probability, LogOddsCell* cells)
                SG_INLINE_LAMBDA {
                  const Doubles p = clamp(widen(probability), cellrule::kProbabilityFloor,
                                          1.0 - cellrule::kProbabilityFloor);
                  const Doubles o = load(cells);
                  store(cells, clamp(o * (p / (1.0 - p)) * invPrior, minOdds, maxOdds));
                });
}

SG_RUN_CLONES void dempsterShafer(const EvidenceRuns& runs, DempsterShaferCell* plane) {
  eachGroup(runs, plane,
            [](const float* empty, const float* occupied, const float*, DempsterShaferCell* cells)
                SG_INLINE_LAMBDA {
                  const Doubles o = clamp(widen(occupied), 0.0, 1.0);
                  const Doubles e = clamp(widen(empty), 0.0, 1.0);
                  const Doubles lo = load(cells), hi = load(cells + 2);
                  const Doubles mo = __builtin_shufflevector(lo, hi, 0, 2, 4, 6);
                  const Doubles me = __builtin_shufflevector(lo, hi, 1, 3, 5, 7);
                  // One kind of evidence x: occupied (e = 0, cellrule's first case) or empty (o =
                  // 0, its second); `grow` is the mass x adds to, `shrink` the other.
                  const auto onlyOccupied = e == 0.0;
                  const auto onlyEmpty = o == 0.0;
                  const Doubles x = onlyOccupied ? o : e;
                  const Doubles grow = onlyOccupied ? mo : me;
                  const Doubles shrink = onlyOccupied ? me : mo;
                  const OneKind r = oneKind(grow, shrink, 1.0 - mo - me, x);
                  // Total conflict (denominator <= 0) keeps the masses, as does a lane of both
                  // kinds, done below by cellrule.
                  const auto general = ~(onlyOccupied | onlyEmpty);
                  const auto keep = (r.denominator <= 0.0) | general;
                  const Doubles newOcc = keep ? mo : (onlyOccupied ? r.grown : r.shrunk);
                  const Doubles newEmp = keep ? me : (onlyOccupied ? r.shrunk : r.grown);
                  store(cells, __builtin_shufflevector(newOcc, newEmp, 0, 4, 1, 5));
                  store(cells + 2, __builtin_shufflevector(newOcc, newEmp, 2, 6, 3, 7));
                  if (anyLane(general)) {
                    for (int j = 0; j < W; ++j) {
                      if (general[j]) generalDempsterShafer(occupied[j], empty[j], cells[j]);
                    }
                  }
                });
}

SG_RUN_CLONES void logOddsUniform(float probability, std::span<const std::uint32_t> cells,
                                  LogOddsCell* plane, double invPrior, double minOdds,
                                  double maxOdds) {
  const double p = std::clamp(static_cast<double>(probability), cellrule::kProbabilityFloor,
                              1.0 - cellrule::kProbabilityFloor);
  const double ratio = p / (1.0 - p);
  eachListed(
      cells, plane,
      [=](Doubles o) SG_INLINE_LAMBDA { return clamp(o * ratio * invPrior, minOdds, maxOdds); },
      [=](LogOddsCell& cell)
          SG_INLINE_LAMBDA { cellrule::logOdds(probability, invPrior, minOdds, maxOdds, cell); });
}

SG_RUN_CLONES void dempsterShaferUniform(float occupied, float empty,
                                         std::span<const std::uint32_t> cells,
                                         DempsterShaferCell* plane) {
  const double o = std::clamp(static_cast<double>(occupied), 0.0, 1.0);
  const double e = std::clamp(static_cast<double>(empty), 0.0, 1.0);
  if (e != 0.0 && o != 0.0) {  // both kinds: cellrule's general case, one cell at a time
    for (const std::uint32_t c : cells) generalDempsterShafer(occupied, empty, plane[c]);
    return;
  }
  // One kind of evidence x, as cellrule's first case (occupied, e = 0) or second (empty, o = 0):
  // `grow` is the mass x adds to, `shrink` the other; W cells at a time, gathered from the plane.
  static_assert(W == 4);
  const std::uint32_t* c = cells.data();
  const std::uint32_t* const end = c + cells.size();
  auto lanes = [&](auto occupiedKind) SG_INLINE_LAMBDA {
    constexpr bool kOccupied = decltype(occupiedKind)::value;
    const Doubles x = splat(kOccupied ? o : e);
    auto grow = [](DempsterShaferCell& m) -> double& { return kOccupied ? m.occ : m.emp; };
    auto shrink = [](DempsterShaferCell& m) -> double& { return kOccupied ? m.emp : m.occ; };
    for (; end - c >= W; c += W) {
      DempsterShaferCell* const m[W] = {plane + c[0], plane + c[1], plane + c[2], plane + c[3]};
      const Doubles mo = {m[0]->occ, m[1]->occ, m[2]->occ, m[3]->occ};
      const Doubles me = {m[0]->emp, m[1]->emp, m[2]->emp, m[3]->emp};
      const Doubles g = kOccupied ? mo : me;
      const Doubles s = kOccupied ? me : mo;
      const OneKind r = oneKind(g, s, 1.0 - mo - me, x);
      const auto keep = r.denominator <= 0.0;  // total conflict keeps the masses
      const Doubles grown = keep ? g : r.grown;
      const Doubles shrunk = keep ? s : r.shrunk;
      // Written out: a loop over j went through the stack.
      grow(*m[0]) = grown[0], shrink(*m[0]) = shrunk[0];
      grow(*m[1]) = grown[1], shrink(*m[1]) = shrunk[1];
      grow(*m[2]) = grown[2], shrink(*m[2]) = shrunk[2];
      grow(*m[3]) = grown[3], shrink(*m[3]) = shrunk[3];
    }
  };
  if (e == 0.0)
    lanes(std::true_type{});
  else
    lanes(std::false_type{});
  for (; c != end; ++c) cellrule::dempsterShafer(occupied, empty, plane[*c]);
}

}  // namespace sg::runs
