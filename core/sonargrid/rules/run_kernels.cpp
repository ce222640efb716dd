// SPDX-License-Identifier: BSD-3-Clause
// Compiled with -ffp-contract=off (core/CMakeLists.txt): the AVX2 clones must not fuse a multiply
// and an add that the baseline build (x86-64 has no FMA) and the rules' apply() do apart.
// Each kernel but Dempster–Shafer's takes four cells at a time in double lanes (four consecutive
// cells of a run, or four listed cells gathered from the plane and scattered back), the model's
// floats widened as apply() widens them, and repeats cell_updates.h's operations in its order; a
// lane's `if` is a select of the updated and the old value. Addition's single-precision cells are
// widened on load and rounded to float on store, as cell_updates.h does one cell at a time.
// Dempster–Shafer computes in float, as cell_updates.h does, in eight float lanes (a run's cells,
// or listed ones; the lanes' formulas are in dempster_shafer_lanes.h); its cells with both kinds of
// evidence (which no model gives) go through cell_updates.h itself, one at a time. Addition's
// deferral (deferOccupiedSpan) looks at eight values at a time too. Where the CPU has AVX-512, the
// run kernels take eight double lanes with masks instead (SG_MASKED_RUNS, below).

#include "sonargrid/rules/run_kernels.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <span>

#include "sonargrid/rules/cell_updates.h"
#include "sonargrid/rules/dempster_shafer_lanes.h"  // and SG_INLINE_LAMBDA
#include "sonargrid/simd/lanes.h"

// On x86-64 with GCC, each kernel that updates runs also has a version in eight double lanes with
// masks, built for AVX-512 and chosen at run time where the CPU has it (coneLanes(), lanes.h): a
// lane the mask leaves out neither loads nor stores, so a run's last cells need no copy and no
// branch on the run's length. The lanes do the same operations as the four-lane version's.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define SG_MASKED_RUNS 1
#include <immintrin.h>
#define SG_MASKED_TARGET target("avx2,avx512f,avx512vl,avx512bw,avx512dq")
// A helper or lambda inlined into the masked kernels (a lambda does not inherit its function's
// target).
#define SG_MASKED_INLINE __attribute__((SG_MASKED_TARGET, always_inline))
#endif

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
// std::clamp(v, lo, hi) per lane: v < lo ? lo : hi < v ? hi : v, which is what std::clamp gives
// for any v (NaN and ±0 included) when lo <= hi.
[[gnu::always_inline]] inline Doubles clamp(Doubles v, double lo, double hi) {
  return v < lo ? splat(lo) : (hi < v ? splat(hi) : v);
}

// x in every lane of V, and std::clamp per lane as clamp() above, for V of any width.
template <class V>
[[gnu::always_inline]] inline V splatAs(double x) {
  V v;
  for (std::size_t j = 0; j < sizeof(V) / sizeof(double); ++j) v[j] = x;
  return v;
}
template <class V>
[[gnu::always_inline]] inline V clampAs(V v, double lo, double hi) {
  return v < lo ? splatAs<V>(lo) : (hi < v ? splatAs<V>(hi) : v);
}

// Each rule's update of a cell's double m in lanes, as cell_updates.h does it one cell at a time,
// for the four-lane kernels and the masked eight.
// Probability addition of evidence x (cellrule::additionEmpty, additionOccupied).
template <class V>
[[gnu::always_inline]] inline V additionLanes(V m, V x) {
  return x > 0.0 ? m + x - m * x : m;
}
// Bayes with the probability p: cellrule::bayesLanes (cell_updates.h).
using cellrule::bayesLanes;
// FastBayesRule's cells (the upper halves of doubles v: FastBayesRule::probabilityOf, cellOf) as
// their p, and four p rounded to their cells.
using Bits4 = std::uint64_t __attribute__((vector_size(32)));
using Halves4 = std::uint32_t __attribute__((vector_size(16)));
[[gnu::always_inline]] inline Doubles unpackHalves(const void* p) {
  Halves4 h;
  std::memcpy(&h, p, sizeof h);
  const Doubles v = (Doubles)(__builtin_convertvector(h, Bits4) << 32);
  return v <= 0.0 ? 1.0 + v : v;
}
[[gnu::always_inline]] inline void packHalves(void* p, Doubles m) {
  const Doubles v = m > 0.5 ? -(1.0 - m) : m;
  const Halves4 h = __builtin_convertvector(((Bits4)v + 0x80000000u) >> 32, Halves4);
  std::memcpy(p, &h, sizeof h);
}
// Paper 001's evidence as a probability (cellrule::bayesEvidence).
template <class V>
[[gnu::always_inline]] inline V bayesEvidenceLanes(V empty, V occupied) {
  return 0.5 + 0.5 * (occupied - empty);
}
// The log update's product (cellrule::logProduct): above kLogHigh it becomes kLogHigh, and
// between 0 and kLogLow kLogLow, written as a clamp kept where the product is positive. (The
// select of the and of two masks, or a select nested in another's first branch, made GCC 12 split
// the eight lanes of this template into scalar compares: 1.8 × the one-thread time of hpf × log.)
template <class V>
[[gnu::always_inline]] inline V logLanes(V m, V empty, V occupied) {
  const V product = m * ((1.0 - empty) * (1.0 + occupied));
  const V clamped = clampAs(product, cellrule::kLogLow, cellrule::kLogHigh);
  return product > 0.0 ? clamped : product;
}
// Clamped log-odds on the odds (cellrule::logOdds).
template <class V>
[[gnu::always_inline]] inline V logOddsLanes(V odds, V probability, double invPrior, double minOdds,
                                             double maxOdds) {
  const V p = clampAs(probability, cellrule::kProbabilityFloor, 1.0 - cellrule::kProbabilityFloor);
  return clampAs(odds * (p / (1.0 - p)) * invPrior, minOdds, maxOdds);
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

// The value arrays a kernel reads: those of `runs`, or, with `occupiedOnly`, its occupied array for
// all three (a deferred run's, UpdateRule::applyRuns).
struct RunValues {
  const float* empty;
  const float* occupied;
  const float* probability;
};
[[gnu::always_inline]] inline RunValues runValues(const EvidenceRuns& runs, bool occupiedOnly) {
  const float* const occupied = runs.occupied.data();
  return {occupiedOnly ? occupied : runs.empty.data(), occupied,
          occupiedOnly ? occupied : runs.probability.data()};
}

// Runs [first, end) of some runs (past their last, up to it): one reading's deferred runs among
// those of a batch (Mapper::integrateBands); all of them by default.
struct RunRange {
  std::size_t first = 0;
  std::size_t end = SIZE_MAX;
  std::span<const EvidenceRuns::Run> of(const EvidenceRuns& runs) const {
    const std::size_t size = runs.runs.size();
    const std::size_t last = std::min(end, size);
    return {runs.runs.data() + std::min(first, last), runs.runs.data() + last};
  }
};

// group(empty, occupied, probability, cells) for every G consecutive cells of every run: G values
// from each array, G cells to update in place (G is W unless a kernel asks for more:
// Dempster–Shafer's eight float lanes). No lane touches a cell past its run (another row's,
// perhaps another thread's): a run's last G cells, which take its last count mod G, are computed on
// a copy of their values from before the run's other groups (so that the cells both cover get the
// same value from either) and copied back at the end; a run shorter than G is
// updated on a copy padded with its first cell. The values past a run that the padding lanes read
// (up to kRunPadding, footprint.h) are ignored. The values are runValues(runs, occupiedOnly).
// After each run's groups, runDone(run) (nothing by default).
// Only the runs of `range`, where one is given.
struct NoRunDone {
  void operator()(const EvidenceRuns::Run&) const {}
};
template <int G = W, class Cell, class Group, class RunDone = NoRunDone>
[[gnu::always_inline]] inline void eachGroup(const EvidenceRuns& runs, Cell* plane, Group&& group,
                                             bool occupiedOnly = false, RunDone runDone = {},
                                             RunRange range = {}) {
  static_assert(G - 1 <= static_cast<int>(kRunPadding), "a short run's lanes read past it");
  const auto [empty, occupied, probability] = runValues(runs, occupiedOnly);
  for (const EvidenceRuns::Run& run : range.of(runs)) {
    Cell* const cells = plane + run.cell;
    const std::size_t v = run.first;
    const int n = run.count;
    Cell last[G];
    if (n < G) {
      for (int j = 0; j < G; ++j) last[j] = cells[j < n ? j : 0];
      group(empty + v, occupied + v, probability + v, last);
      for (int j = 0; j < n; ++j) cells[j] = last[j];
      runDone(run);
      continue;
    }
    // The last G cells, on the copy, whatever n mod G (without a branch on it: a run's length is
    // as good as random); then the groups before them, the last of which may overlap them.
    const int tail = n - G;
    copyLanes<sizeof last>(last, cells + tail);
    group(empty + v + tail, occupied + v + tail, probability + v + tail, last);
    for (int k = 0; k < tail; k += G)
      group(empty + v + k, occupied + v + k, probability + v + k, cells + k);
    copyLanes<sizeof last>(cells + tail, last);
    runDone(run);
  }
}

// group(c) for every G consecutive entries c[0 .. G) of `cells` (distinct grid indices, the same
// evidence for all), in order. The last cells.size() mod G go in a group padded with copies of its
// last cell: the same cell in two lanes gets the same value in both (a lane's update is a function
// of the cell's bytes alone), so their stores agree, and each cell is still updated once. A call
// per cell, the way the last ones went before, cost HIMM's reading with its one echo cell more than
// its lanes.
template <int G, class Group>
[[gnu::always_inline]] inline void eachListedGroup(std::span<const std::uint32_t> cells,
                                                   Group&& group) {
  const std::uint32_t* const c = cells.data();
  const std::size_t n = cells.size();
  const std::size_t whole = n - n % G;
  for (std::size_t k = 0; k < whole; k += G) group(c + k);
  if (whole < n) {
    std::uint32_t padded[G];
    for (std::size_t j = 0; j < G; ++j) padded[j] = c[std::min(whole + j, n - 1)];
    group(padded);
  }
}

// The W cells c[0 .. W) of `plane`, eight bytes each, as one double's bits a lane, and back.
template <class Cell>
[[gnu::always_inline]] inline Doubles gather(const Cell* plane, const std::uint32_t* c) {
  static_assert(sizeof(Cell) == sizeof(double) && W == 4);
  double v[W];
  for (int j = 0; j < W; ++j) std::memcpy(&v[j], plane + c[j], sizeof(double));
  return Doubles{v[0], v[1], v[2], v[3]};
}
template <class Cell>
[[gnu::always_inline]] inline void scatter(Cell* plane, const std::uint32_t* c, Doubles m) {
  static_assert(sizeof(Cell) == sizeof(double) && W == 4);
  // Written out: a loop over j went through the stack (a 32-byte store, four 8-byte loads).
  const double m0 = m[0], m1 = m[1], m2 = m[2], m3 = m[3];
  std::memcpy(plane + c[0], &m0, sizeof(double));
  std::memcpy(plane + c[1], &m1, sizeof(double));
  std::memcpy(plane + c[2], &m2, sizeof(double));
  std::memcpy(plane + c[3], &m3, sizeof(double));
}

// update(m) for every cell of `cells` (eachListedGroup; one double a cell), W at a time, gathered
// into lanes and scattered back.
template <class Cell, class Lanes>
[[gnu::always_inline]] inline void eachListed(std::span<const std::uint32_t> cells, Cell* plane,
                                              Lanes&& update) {
  eachListedGroup<W>(cells, [&](const std::uint32_t* c)
                                SG_INLINE_LAMBDA { scatter(plane, c, update(gather(plane, c))); });
}

// Dempster–Shafer's general case, for a cell with both kinds of evidence (no cone model gives one):
// a call, so that the kernel's lanes stay small enough to inline.
[[gnu::noinline]] void generalDempsterShafer(float occupied, float empty,
                                             DempsterShaferCell& cell) {
  cellrule::dempsterShafer(occupied, empty, cell);
}

static_assert(sizeof(EmptyEvidence) == sizeof(float) && sizeof(OccupiedEvidence) == sizeof(float));
static_assert(sizeof(BayesFloatCell) == sizeof(std::uint32_t));
static_assert(sizeof(BayesCell) == sizeof(double) && sizeof(LogCell) == sizeof(double));
static_assert(sizeof(LogOddsCell) == sizeof(double));
static_assert(sizeof(DempsterShaferCell) == 2 * sizeof(float) &&
              sizeof(DempsterShaferCell) == sizeof(double));

// deferOccupiedSpan()'s part of a run with evidence: values lo .. hi − 1 of `run` (whose occupied
// values start at `occupied`) appended to `deferred` from value `used` (which it advances), with
// kRunPadding zeros past them, which the lanes read from a short run's start and throw away
// (eachGroup).
inline void deferSpan(const EvidenceRuns::Run& run, const float* occupied, int lo, int hi,
                      EvidenceRuns& deferred, std::size_t& used) {
  const auto count = static_cast<std::size_t>(hi - lo);
  const std::size_t room = used + count + kRunPadding;
  if (deferred.occupied.size() < room) deferred.occupied.resize(room);
  std::copy_n(occupied + lo, count, deferred.occupied.data() + used);
  std::fill_n(deferred.occupied.data() + used + count, kRunPadding, 0.0f);
  deferred.runs.push_back(
      {run.cell + static_cast<std::uint32_t>(lo), hi - lo, static_cast<std::uint32_t>(used)});
  used += count;
}

#ifdef SG_MASKED_RUNS
// The masked kernels' lanes: eight doubles, and the eight floats they widen from and narrow to.
using Doubles8 = double __attribute__((vector_size(64)));

// The lanes of `mask` loaded from p (the others 0, and nothing read for them), and stored to p
// (nothing written for the others): doubles, or floats widened and rounded back as widen() and
// narrow() do.
SG_MASKED_INLINE inline Doubles8 load8(__mmask8 mask, const void* p) {
  return reinterpret_cast<Doubles8>(_mm512_maskz_loadu_pd(mask, p));
}
SG_MASKED_INLINE inline void store8(__mmask8 mask, void* p, Doubles8 v) {
  _mm512_mask_storeu_pd(p, mask, reinterpret_cast<__m512d>(v));
}
SG_MASKED_INLINE inline Doubles8 widen8(__mmask8 mask, const void* p) {
  // One conversion of all eight (__builtin_convertvector made two of four and a merge); the
  // masked form, as the plain one trips GCC 12's -Wmaybe-uninitialized in its own header.
  return reinterpret_cast<Doubles8>(_mm512_maskz_cvtps_pd(mask, _mm256_maskz_loadu_ps(mask, p)));
}
SG_MASKED_INLINE inline void narrow8(__mmask8 mask, void* p, Doubles8 v) {
  _mm256_mask_storeu_ps(p, mask, reinterpret_cast<__m256>(__builtin_convertvector(v, Floats8)));
}
// unpackHalves() and packHalves() of eight cells (masked forms throughout, as in widen8()).
SG_MASKED_INLINE inline Doubles8 unpackHalves8(__mmask8 mask, const void* p) {
  const Doubles8 v = reinterpret_cast<Doubles8>(_mm512_maskz_slli_epi64(
      mask, _mm512_maskz_cvtepu32_epi64(mask, _mm256_maskz_loadu_epi32(mask, p)), 32));
  return v <= 0.0 ? 1.0 + v : v;
}
SG_MASKED_INLINE inline void packHalves8(__mmask8 mask, void* p, Doubles8 m) {
  const Doubles8 v = m > 0.5 ? -(1.0 - m) : m;
  const __m512i rounded =
      _mm512_maskz_add_epi64(mask, reinterpret_cast<__m512i>(v), _mm512_set1_epi64(0x80000000));
  const __m512i high = _mm512_maskz_srli_epi64(mask, rounded, 32);
  _mm256_mask_storeu_epi32(p, mask, _mm512_maskz_cvtepi64_epi32(mask, high));
}

// The mask of the first min(left, 8) lanes: a group of eight with `left` values from its start to
// the end of its run.
inline __mmask8 laneMask(int left) {
  return static_cast<__mmask8>((1u << std::min(left, 8)) - 1u);
}

// group(mask, empty, occupied, probability, cells) for every eight consecutive cells of every run,
// the last group of a run masked to its cells: eachGroup() without the copies. `occupiedOnly` and
// `range` as in eachGroup().
template <class Cell, class Group>
SG_MASKED_INLINE inline void eachMasked(const EvidenceRuns& runs, Cell* plane, Group&& group,
                                        bool occupiedOnly = false, RunRange range = {}) {
  const auto [empty, occupied, probability] = runValues(runs, occupiedOnly);
  for (const EvidenceRuns::Run& run : range.of(runs)) {
    Cell* const cells = plane + run.cell;
    const std::size_t v = run.first;
    const int n = run.count;  // a local: the cells' stores could otherwise alias it
    for (int k = 0; k < n; k += 8) {
      const __mmask8 mask = laneMask(n - k);
      group(mask, empty + v + k, occupied + v + k, probability + v + k, cells + k);
    }
  }
}

// Whether the run kernels take eight masked lanes (the CPU has AVX-512, and no test limited the
// lanes below it).
bool masked() {
  return coneLanes() == ConeLanes::Avx512;
}

// The empty update of every run; with kDefer, in the same pass over the runs, the deferral of each
// run's occupied span (as plain::deferOccupiedSpan), rather than in a second pass.
template <bool kDefer>
__attribute__((SG_MASKED_TARGET)) void additionEmptyMasked(const EvidenceRuns& runs,
                                                           EmptyEvidence* emp,
                                                           EvidenceRuns* deferred) {
  std::size_t used = kDefer ? deferred->valuesEnd() : 0;
  const float* const emptyValues = runs.empty.data();
  const float* const occupiedValues = runs.occupied.data();
  for (const EvidenceRuns::Run& run : runs.runs) {
    EmptyEvidence* const cells = emp + run.cell;
    const float* const empty = emptyValues + run.first;
    const float* const occupied = occupiedValues + run.first;
    const int n = run.count;
    int lo = -1, hi = 0;
    for (int k = 0; k < n; k += 8) {
      const __mmask8 mask = laneMask(n - k);
      narrow8(mask, cells + k, additionLanes(widen8(mask, cells + k), widen8(mask, empty + k)));
      if constexpr (kDefer) {
        // A bit for each value not ±0 (unordered or not equal: NaN counts, as in the plain
        // kernel, plain::deferOccupiedSpan).
        const unsigned bits = _mm256_mask_cmp_ps_mask(
            mask, _mm256_maskz_loadu_ps(mask, occupied + k), _mm256_setzero_ps(), _CMP_NEQ_UQ);
        if (bits == 0) continue;
        if (lo < 0) lo = k + __builtin_ctz(bits);
        hi = k + 32 - __builtin_clz(bits);
      }
    }
    if (kDefer && lo >= 0) deferSpan(run, occupied, lo, hi, *deferred, used);
  }
}

__attribute__((SG_MASKED_TARGET)) void additionOccupiedMasked(const EvidenceRuns& runs,
                                                              RunRange range, OccupiedEvidence* occ,
                                                              double scale) {
  eachMasked(
      runs, occ,
      [scale](__mmask8 m, const float*, const float* occupied, const float*,
              OccupiedEvidence* cells) SG_MASKED_INLINE {
        narrow8(m, cells, additionLanes(widen8(m, cells), widen8(m, occupied) * scale));
      },
      true, range);
}

__attribute__((SG_MASKED_TARGET)) void bayesMasked(const EvidenceRuns& runs, BayesCell* plane,
                                                   bool likelihood) {
  if (likelihood) {
    eachMasked(runs, plane,
               [](__mmask8 m, const float*, const float*, const float* probability,
                  BayesCell* cells) SG_MASKED_INLINE {
                 store8(m, cells, bayesLanes(load8(m, cells), widen8(m, probability)));
               });
  } else {
    eachMasked(runs, plane,
               [](__mmask8 m, const float* empty, const float* occupied, const float*,
                  BayesCell* cells) SG_MASKED_INLINE {
                 const Doubles8 p = bayesEvidenceLanes(widen8(m, empty), widen8(m, occupied));
                 store8(m, cells, bayesLanes(load8(m, cells), p));
               });
  }
}

__attribute__((SG_MASKED_TARGET)) void floatBayesMasked(const EvidenceRuns& runs,
                                                        BayesFloatCell* plane, bool likelihood) {
  if (likelihood) {
    eachMasked(runs, plane,
               [](__mmask8 m, const float*, const float*, const float* probability,
                  BayesFloatCell* cells) SG_MASKED_INLINE {
                 const Doubles8 p = unpackHalves8(m, cells);
                 packHalves8(m, cells, bayesLanes(p, widen8(m, probability)));
               });
  } else {
    eachMasked(runs, plane,
               [](__mmask8 m, const float* empty, const float* occupied, const float*,
                  BayesFloatCell* cells) SG_MASKED_INLINE {
                 const Doubles8 e = bayesEvidenceLanes(widen8(m, empty), widen8(m, occupied));
                 const Doubles8 p = unpackHalves8(m, cells);
                 packHalves8(m, cells, bayesLanes(p, e));
               });
  }
}

__attribute__((SG_MASKED_TARGET)) void logProductMasked(const EvidenceRuns& runs, LogCell* plane) {
  eachMasked(runs, plane,
             [](__mmask8 m, const float* empty, const float* occupied, const float*,
                LogCell* cells) SG_MASKED_INLINE {
               store8(m, cells, logLanes(load8(m, cells), widen8(m, empty), widen8(m, occupied)));
             });
}

__attribute__((SG_MASKED_TARGET)) void logOddsMasked(const EvidenceRuns& runs, LogOddsCell* plane,
                                                     double invPrior, double minOdds,
                                                     double maxOdds) {
  eachMasked(
      runs, plane,
      [=](__mmask8 m, const float*, const float*, const float* probability,
          LogOddsCell* cells) SG_MASKED_INLINE {
        store8(m, cells,
               logOddsLanes(load8(m, cells), widen8(m, probability), invPrior, minOdds, maxOdds));
      });
}

__attribute__((SG_MASKED_TARGET)) std::int64_t occupiedTotalMasked(const EvidenceRuns& runs,
                                                                   RunRange range) {
  // Each value's share as occupiedFixedPoint(float) computes it (NaN 0, clamped to ±2^22, times
  // 2^40, truncated), summed in 64-bit lanes modulo 2^64: the same sum in any order.
  const Doubles8 zero{};
  __m512i sum = _mm512_setzero_si512();
  for (const EvidenceRuns::Run& run : range.of(runs)) {
    const float* const occupied = runs.occupied.data() + run.first;
    const int n = run.count;
    for (int k = 0; k < n; k += 8) {
      const __mmask8 mask = laneMask(n - k);
      Doubles8 x = widen8(mask, occupied + k);
      x = clampAs(x == x ? x : zero, -0x1p22, 0x1p22);
      sum = _mm512_add_epi64(sum, _mm512_cvttpd_epi64(reinterpret_cast<__m512d>(x * 0x1p40)));
    }
  }
  std::uint64_t lanes[8];  // summed here: _mm512_reduce_add_epi64 trips GCC 12's -Wuninitialized
  std::memcpy(lanes, &sum, sizeof lanes);
  std::uint64_t total = 0;
  for (const std::uint64_t share : lanes) total += share;
  return static_cast<std::int64_t>(total);
}

__attribute__((SG_MASKED_TARGET)) void dempsterShaferMasked(const EvidenceRuns& runs,
                                                            DempsterShaferCell* plane) {
  using Floats16 = float __attribute__((vector_size(64)));
  eachMasked(runs, plane,
             [](__mmask8 m, const float* empty, const float* occupied, const float*,
                DempsterShaferCell* cells) SG_MASKED_INLINE {
               const auto o = reinterpret_cast<Floats8>(_mm256_maskz_loadu_ps(m, occupied));
               const auto e = reinterpret_cast<Floats8>(_mm256_maskz_loadu_ps(m, empty));
               // The cells as eight 8-byte pairs a b; a lane left out reads as −0, −0 (both
               // signs set), which keeps the group on dempsterShaferLanes' usual case.
               const auto ab = reinterpret_cast<Floats16>(_mm512_mask_loadu_epi64(
                   _mm512_set1_epi64(static_cast<long long>(0x8000000080000000ull)), m, cells));
               Floats8 a = __builtin_shufflevector(ab, ab, 0, 2, 4, 6, 8, 10, 12, 14);
               Floats8 b = __builtin_shufflevector(ab, ab, 1, 3, 5, 7, 9, 11, 13, 15);
               // A group whose cells all have one kind of evidence, as runs mostly are (a lane
               // left out counts as either): that kind's lanes (dempsterShaferOneKind), which
               // give the bits of dempsterShaferLanes' for it with fewer selects.
               const Floats8 co = clampUnit(o), ce = clampUnit(e);
               const auto outside = static_cast<__mmask8>(~m);
               const __mmask8 occupiedKind = _mm256_cmp_ps_mask(ce, Floats8{}, _CMP_EQ_OQ);
               const __mmask8 emptyKind =
                   _mm256_cmp_ps_mask(co, Floats8{}, _CMP_EQ_OQ) & ~occupiedKind;
               int general = 0;
               if ((emptyKind | outside) == 0xff) {
                 dempsterShaferOneKind<false>(ce, a, b);
               } else if ((occupiedKind | outside) == 0xff) {
                 dempsterShaferOneKind<true>(co, a, b);
               } else {
                 general = dempsterShaferLanes(o, e, a, b);
               }
               const Floats16 out = __builtin_shufflevector(a, b, 0, 8, 1, 9, 2, 10, 3, 11, 4, 12,
                                                            5, 13, 6, 14, 7, 15);
               _mm512_mask_storeu_epi64(cells, m, reinterpret_cast<__m512i>(out));
               // A lane left out has no evidence (o = e = 0), so it is never general.
               if (general != 0) {
                 for (int j = 0; j < 8; ++j) {
                   if (general & (1 << j)) generalDempsterShafer(occupied[j], empty[j], cells[j]);
                 }
               }
             });
}
#endif

}  // namespace

// The four-lane kernels, cloned for AVX2.
namespace plain {

// Addition's deferral of one run (AdditionRule::applyRuns), whose occupied values start at
// `occupied`: its span from the first value that is not ±0 (NaN counts) to the last, if any.
[[gnu::always_inline]] inline void deferOccupiedSpan(const EvidenceRuns::Run& run,
                                                     const float* occupied, EvidenceRuns& deferred,
                                                     std::size_t& used) {
  const int n = run.count;
  // Eight values at a time, a bit each for "not ±0" (the vector == holds for ±0 and not for NaN
  // or denormals, as the scalar == does; nothing in the program sets the CPU to treat denormals
  // as zero); the last group's bits past the run, read from the room kRunPadding keeps past the
  // last run, are cleared.
  int lo = -1, hi = 0;  // the first value of evidence, and one past the last
  for (int k = 0; k < n; k += 8) {
    Floats8 v;
    std::memcpy(&v, occupied + k, sizeof v);
    unsigned bits = ~static_cast<unsigned>(signBits(reinterpret_cast<Floats8>(v == 0.0f))) & 0xffu;
    if (n - k < 8) bits &= (1u << (n - k)) - 1u;
    if (bits == 0) continue;
    if (lo < 0) lo = k + __builtin_ctz(bits);
    hi = k + 32 - __builtin_clz(bits);
  }
  if (lo >= 0) deferSpan(run, occupied, lo, hi, deferred, used);
}

// The empty update; with `deferred`, each run's occupied span deferred right after its groups
// (AdditionRule::applyRuns), in the same pass over the runs.
SG_RUN_CLONES void additionEmpty(const EvidenceRuns& runs, EmptyEvidence* emp,
                                 EvidenceRuns* deferred) {
  auto update = [](const float* empty, const float*, const float*, EmptyEvidence* cells)
                    SG_INLINE_LAMBDA { narrow(cells, additionLanes(widen(cells), widen(empty))); };
  if (!deferred) return eachGroup(runs, emp, update);
  std::size_t used = deferred->valuesEnd();
  const float* const occupied = runs.occupied.data();
  eachGroup(runs, emp, update, false, [&](const EvidenceRuns::Run& run) SG_INLINE_LAMBDA {
    deferOccupiedSpan(run, occupied + run.first, *deferred, used);
  });
}

SG_RUN_CLONES void additionOccupied(const EvidenceRuns& runs, RunRange range, OccupiedEvidence* occ,
                                    double scale) {
  // po > 0 exactly where c.occupied > 0, the scale being positive and finite: the product of a
  // float and a scale of at least 2^-63 cannot round to 0 in double.
  eachGroup(
      runs, occ,
      [scale](const float*, const float* occupied, const float*, OccupiedEvidence* cells)
          SG_INLINE_LAMBDA { narrow(cells, additionLanes(widen(cells), widen(occupied) * scale)); },
      true, NoRunDone{}, range);
}

SG_RUN_CLONES void bayes(const EvidenceRuns& runs, BayesCell* plane, bool likelihood) {
  if (likelihood) {
    eachGroup(runs, plane,
              [&](const float*, const float*, const float* probability, BayesCell* cells)
                  SG_INLINE_LAMBDA { store(cells, bayesLanes(load(cells), widen(probability))); });
  } else {
    eachGroup(runs, plane,
              [&](const float* empty, const float* occupied, const float*, BayesCell* cells)
                  SG_INLINE_LAMBDA {
                    const Doubles p = bayesEvidenceLanes(widen(empty), widen(occupied));
                    store(cells, bayesLanes(load(cells), p));
                  });
  }
}

SG_RUN_CLONES void logProduct(const EvidenceRuns& runs, LogCell* plane) {
  eachGroup(
      runs, plane,
      [](const float* empty, const float* occupied, const float*, LogCell* cells)
          SG_INLINE_LAMBDA { store(cells, logLanes(load(cells), widen(empty), widen(occupied))); });
}

SG_RUN_CLONES void logOdds(const EvidenceRuns& runs, LogOddsCell* plane, double invPrior,
                           double minOdds, double maxOdds) {
  eachGroup(runs, plane,
            [=](const float*, const float*, const float* probability, LogOddsCell* cells)
                SG_INLINE_LAMBDA {
                  store(cells,
                        logOddsLanes(load(cells), widen(probability), invPrior, minOdds, maxOdds));
                });
}

// Eight cells at a time: Dempster–Shafer computes in float, so a group of eight is one AVX2
// register a lane (two SSE registers in the baseline clone), as wide as the other kernels' four
// doubles; a lane does what it did in four (tst_fused_runs, tst_rules).
SG_RUN_CLONES void dempsterShafer(const EvidenceRuns& runs, DempsterShaferCell* plane) {
  constexpr int G = 8;
  eachGroup<G>(runs, plane,
               [](const float* empty, const float* occupied, const float*,
                  DempsterShaferCell* cells) SG_INLINE_LAMBDA {
                 Floats8 o, e, lo, hi;  // lo, hi: a0 b0 … a3 b3, a4 b4 … a7 b7
                 std::memcpy(&o, occupied, sizeof o);
                 std::memcpy(&e, empty, sizeof e);
                 std::memcpy(&lo, cells, sizeof lo);
                 std::memcpy(&hi, cells + 4, sizeof hi);
                 Floats8 a = __builtin_shufflevector(lo, hi, 0, 2, 4, 6, 8, 10, 12, 14);
                 Floats8 b = __builtin_shufflevector(lo, hi, 1, 3, 5, 7, 9, 11, 13, 15);
                 const int general = dempsterShaferLanes(o, e, a, b);
                 lo = __builtin_shufflevector(a, b, 0, 8, 1, 9, 2, 10, 3, 11);
                 hi = __builtin_shufflevector(a, b, 4, 12, 5, 13, 6, 14, 7, 15);
                 std::memcpy(cells, &lo, sizeof lo);
                 std::memcpy(cells + 4, &hi, sizeof hi);
                 if (general != 0) {
                   for (int j = 0; j < G; ++j) {
                     if (general & (1 << j)) generalDempsterShafer(occupied[j], empty[j], cells[j]);
                   }
                 }
               });
}

SG_RUN_CLONES void floatBayes(const EvidenceRuns& runs, BayesFloatCell* plane, bool likelihood) {
  if (likelihood) {
    eachGroup(runs, plane,
              [&](const float*, const float*, const float* probability, BayesFloatCell* cells)
                  SG_INLINE_LAMBDA {
                    const Doubles p = unpackHalves(cells);
                    packHalves(cells, bayesLanes(p, widen(probability)));
                  });
  } else {
    eachGroup(runs, plane,
              [&](const float* empty, const float* occupied, const float*, BayesFloatCell* cells)
                  SG_INLINE_LAMBDA {
                    const Doubles e = bayesEvidenceLanes(widen(empty), widen(occupied));
                    const Doubles p = unpackHalves(cells);
                    packHalves(cells, bayesLanes(p, e));
                  });
  }
}

}  // namespace plain

// The kernels: masked where the CPU has AVX-512, else the four lanes.
#ifdef SG_MASKED_RUNS
#define SG_RUN_MASKED(call) \
  if (masked()) return call
#else
#define SG_RUN_MASKED(call)
#endif

void additionEmpty(const EvidenceRuns& runs, EmptyEvidence* emp, EvidenceRuns* deferred) {
  if (deferred) {
    SG_RUN_MASKED(additionEmptyMasked<true>(runs, emp, deferred));
  } else {
    SG_RUN_MASKED(additionEmptyMasked<false>(runs, emp, nullptr));
  }
  plain::additionEmpty(runs, emp, deferred);
}

void additionOccupied(const EvidenceRuns& runs, std::size_t firstRun, std::size_t endRun,
                      OccupiedEvidence* occ, double scale) {
  const RunRange range{firstRun, endRun};
  SG_RUN_MASKED(additionOccupiedMasked(runs, range, occ, scale));
  plain::additionOccupied(runs, range, occ, scale);
}

void bayes(const EvidenceRuns& runs, BayesCell* plane, bool likelihood) {
  SG_RUN_MASKED(bayesMasked(runs, plane, likelihood));
  plain::bayes(runs, plane, likelihood);
}

void floatBayes(const EvidenceRuns& runs, BayesFloatCell* plane, bool likelihood) {
  SG_RUN_MASKED(floatBayesMasked(runs, plane, likelihood));
  plain::floatBayes(runs, plane, likelihood);
}

void logProduct(const EvidenceRuns& runs, LogCell* plane) {
  SG_RUN_MASKED(logProductMasked(runs, plane));
  plain::logProduct(runs, plane);
}

void logOdds(const EvidenceRuns& runs, LogOddsCell* plane, double invPrior, double minOdds,
             double maxOdds) {
  SG_RUN_MASKED(logOddsMasked(runs, plane, invPrior, minOdds, maxOdds));
  plain::logOdds(runs, plane, invPrior, minOdds, maxOdds);
}

void dempsterShafer(const EvidenceRuns& runs, DempsterShaferCell* plane) {
  SG_RUN_MASKED(dempsterShaferMasked(runs, plane));
  plain::dempsterShafer(runs, plane);
}

SG_RUN_CLONES void bayesUniform(double p, std::span<const std::uint32_t> cells, BayesCell* plane) {
  eachListed(cells, plane, [p](Doubles m) SG_INLINE_LAMBDA { return bayesLanes(m, splat(p)); });
}

SG_RUN_CLONES void logOddsUniform(float probability, std::span<const std::uint32_t> cells,
                                  LogOddsCell* plane, double invPrior, double minOdds,
                                  double maxOdds) {
  const double p = std::clamp(static_cast<double>(probability), cellrule::kProbabilityFloor,
                              1.0 - cellrule::kProbabilityFloor);
  const double ratio = p / (1.0 - p);
  eachListed(cells, plane, [=](Doubles o) SG_INLINE_LAMBDA {
    return clamp(o * ratio * invPrior, minOdds, maxOdds);
  });
}

// One kind of evidence, eight cells at a time (eachListedGroup<2 * W>), gathered as eight 8-byte
// pairs into lo = a0 b0 … a3 b3 and hi = a4 b4 … a7 b7, and scattered back.
template <bool kOccupied>
[[gnu::always_inline]] inline void dempsterShaferListed(float x,
                                                        std::span<const std::uint32_t> cells,
                                                        DempsterShaferCell* plane) {
  eachListedGroup<2 * W>(cells, [=](const std::uint32_t* c) SG_INLINE_LAMBDA {
    const Doubles lo = gather(plane, c), hi = gather(plane, c + W);
    const Floats8 lo8 = reinterpret_cast<Floats8>(lo), hi8 = reinterpret_cast<Floats8>(hi);
    Floats8 a = __builtin_shufflevector(lo8, hi8, 0, 2, 4, 6, 8, 10, 12, 14);
    Floats8 b = __builtin_shufflevector(lo8, hi8, 1, 3, 5, 7, 9, 11, 13, 15);
    dempsterShaferOneKind<kOccupied>(Floats8{} + x, a, b);
    const Doubles newLo =
        reinterpret_cast<Doubles>(__builtin_shufflevector(a, b, 0, 8, 1, 9, 2, 10, 3, 11));
    const Doubles newHi =
        reinterpret_cast<Doubles>(__builtin_shufflevector(a, b, 4, 12, 5, 13, 6, 14, 7, 15));
    scatter(plane, c, newLo);
    scatter(plane, c + W, newHi);
  });
}

SG_RUN_CLONES void dempsterShaferUniform(float occupied, float empty,
                                         std::span<const std::uint32_t> cells,
                                         DempsterShaferCell* plane) {
  const float o = std::clamp(occupied, 0.0f, 1.0f);
  const float e = std::clamp(empty, 0.0f, 1.0f);
  // Both kinds (cellrule's general case), or one cell (HIMM's echo: eight lanes cost it more than
  // cellrule's branches): one cell at a time.
  if ((e != 0.0f && o != 0.0f) || cells.size() == 1) {
    for (const std::uint32_t c : cells) generalDempsterShafer(occupied, empty, plane[c]);
    return;
  }
  // The kind as cellrule::dempsterShafer takes it: occupied where e is 0, o then possibly 0 too.
  if (e == 0.0f) {
    dempsterShaferListed<true>(o, cells, plane);
  } else {
    dempsterShaferListed<false>(e, cells, plane);
  }
}

}  // namespace sg::runs

namespace sg {

std::int64_t occupiedFixedPoint(const EvidenceRuns& runs, std::size_t firstRun) {
  const runs::RunRange range{firstRun};
#ifdef SG_MASKED_RUNS
  if (runs::masked()) return runs::occupiedTotalMasked(runs, range);
#endif
  FootprintTotals sum;
  for (const EvidenceRuns::Run& run : range.of(runs)) {
    const float* const occupied = runs.occupied.data() + run.first;
    for (int k = 0; k < run.count; ++k) sum.add(occupiedFixedPoint(occupied[k]));
  }
  return sum.occupied;
}

}  // namespace sg
