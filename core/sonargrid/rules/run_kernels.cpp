// SPDX-License-Identifier: BSD-3-Clause
// Compiled with -ffp-contract=off (core/CMakeLists.txt): the AVX2 clones must not fuse a multiply
// and an add that the baseline build (x86-64 has no FMA) and the rules' apply() do apart.
// Each kernel but Dempster–Shafer's takes four cells at a time in double lanes (four consecutive
// cells of a run, or four listed cells gathered from the plane and scattered back), the model's
// floats widened as apply()
// widens them, and repeats cell_updates.h's operations in its order; a lane's `if` is a select of
// the updated and the old value. Addition's single-precision cells are widened on load and rounded
// to float on store, as cell_updates.h does one cell at a time. Dempster–Shafer computes in float,
// as cell_updates.h does, in eight float lanes (a run's cells, or listed ones); its cells with both
// kinds of evidence (which no model gives) go through cell_updates.h itself, one at a time.
// Addition's deferral (occupiedSpans) looks at eight values at a time too.
#include "sonargrid/rules/run_kernels.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <span>

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

// group(empty, occupied, probability, cells) for every G consecutive cells of every run: G values
// from each array, G cells to update in place (G is W unless a kernel asks for more:
// Dempster–Shafer's eight float lanes). No lane touches a cell past its run (another row's,
// perhaps another thread's): a run's last G cells, which take its last count mod G, are computed on
// a copy of their values from before the run's other groups (so that the cells both cover get the
// same value from either) and copied back at the end; a run shorter than G is
// updated on a copy padded with its first cell. The values past a run that the padding lanes read
// (up to kRunPadding, footprint.h) are ignored. The values are those of `runs`' arrays, or, with
// `occupiedOnly`, of its occupied array alone (all three pointers point into it; a deferred
// run's, UpdateRule::applyRuns).
template <int G = W, class Cell, class Group>
[[gnu::always_inline]] inline void eachGroup(const EvidenceRuns& runs, Cell* plane, Group&& group,
                                             bool occupiedOnly = false) {
  static_assert(G - 1 <= static_cast<int>(kRunPadding), "a short run's lanes read past it");
  const float* const occupied = runs.occupied.data();
  const float* const empty = occupiedOnly ? occupied : runs.empty.data();
  const float* const probability = occupiedOnly ? occupied : runs.probability.data();
  for (const EvidenceRuns::Run& run : runs.runs) {
    Cell* const cells = plane + run.cell;
    const std::size_t v = run.first;
    const int n = run.count;
    Cell last[G];
    if (n < G) {
      for (int j = 0; j < G; ++j) last[j] = cells[j < n ? j : 0];
      group(empty + v, occupied + v, probability + v, last);
      for (int j = 0; j < n; ++j) cells[j] = last[j];
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

// DempsterShaferCell::masses() and ::of() per lane, on four or eight cells' a and b (V: Floats or
// Floats8), with I the int lanes of the same count.
using Floats8 = float __attribute__((vector_size(32)));
template <class V>
using IntsOf = decltype(V{} < V{});
template <class V>
struct Masses {
  V occ, emp, unk;
};
template <class V>
[[gnu::always_inline]] inline Masses<V> masses(V a, V b) {
  const IntsOf<V> occLeftOut = reinterpret_cast<IntsOf<V>>(a) < 0;  // the sign bit
  const IntsOf<V> empLeftOut = reinterpret_cast<IntsOf<V>>(b) < 0;
  const V unk = occLeftOut ? -a : (empLeftOut ? -b : 1.0f - a - b);
  return {occLeftOut ? 1.0f - unk - b : a, empLeftOut ? 1.0f - unk - a : b, unk};
}
template <class V>
[[gnu::always_inline]] inline V magnitude(V v) {
  return reinterpret_cast<V>(reinterpret_cast<IntsOf<V>>(v) & 0x7fffffff);
}
template <class V>
[[gnu::always_inline]] inline void cellsOf(const Masses<V>& m, V& a, V& b) {
  const IntsOf<V> unkLeftOut = (m.unk >= m.occ) & (m.unk >= m.emp);
  const IntsOf<V> occLeftOut = ~unkLeftOut & (m.occ >= m.emp);
  const IntsOf<V> empLeftOut = ~(unkLeftOut | occLeftOut);
  const V unk = -magnitude(m.unk);
  a = occLeftOut ? unk : magnitude(m.occ);
  b = empLeftOut ? unk : magnitude(m.emp);
}
// Bit j set where lane j's sign bit is (movmskps, SSE: in every clone; eight lanes as two fours).
[[gnu::always_inline]] inline int signBits(Floats v) {
  return __builtin_ia32_movmskps(v);
}
[[gnu::always_inline]] inline int signBits(Floats8 v) {
  return signBits(Floats{v[0], v[1], v[2], v[3]}) | signBits(Floats{v[4], v[5], v[6], v[7]}) << 4;
}
template <class V>
[[gnu::always_inline]] inline V clampUnit(V v) {
  return v < 0.0f ? V{} : (1.0f < v ? V{} + 1.0f : v);  // std::clamp(v, 0, 1)
}

// Dempster's rule on four or eight cells (a, b per lane) for the model's evidence per lane, as
// cellrule::dempsterShafer's first two cases: one kind of evidence x, `grow` the mass x adds to,
// `shrink` the other. Lanes of total conflict keep their cells; lanes with both kinds (which no
// model gives) are left as they were and set in the bits returned, for cellrule to do one at a
// time.
template <class V>
[[gnu::always_inline]] inline int dempsterShaferLanes(V occupied, V empty, V& a, V& b) {
  using I = IntsOf<V>;
  constexpr int kAll = (1 << sizeof(V) / sizeof(float)) - 1;
  const V o = clampUnit(occupied), e = clampUnit(empty);
  const I onlyOccupied = e == 0.0f;
  const I onlyEmpty = o == 0.0f;
  const I general = ~(onlyOccupied | onlyEmpty);
  const V x = onlyOccupied ? o : e;
  // Lanes where the mass x adds to is the one the cell leaves out (its sign bit): the other two are
  // a and b, and both scale by s. All lanes so, the usual case: nothing else to do.
  const V grownCell = onlyOccupied ? a : b;
  if (signBits(grownCell) == kAll && signBits(reinterpret_cast<V>(general)) == 0) {
    const V denominator = 1.0f - (onlyOccupied ? b : a) * x;
    const V s = (1.0f - x) * (1.0f / denominator);
    const I keep = denominator <= 0.0f;  // total conflict
    a = keep ? a : a * s;
    b = keep ? b : b * s;
    return 0;
  }
  const Masses<V> m = masses(a, b);
  const V grow = onlyOccupied ? m.occ : m.emp;
  const V shrink = onlyOccupied ? m.emp : m.occ;
  const V denominator = 1.0f - shrink * x;
  const V inv = 1.0f / denominator;
  const V s = (1.0f - x) * inv;
  const V grown = (grow + m.unk * x) * inv;
  const V shrunk = shrink * s;
  V newA, newB;
  cellsOf<V>({onlyOccupied ? grown : shrunk, onlyOccupied ? shrunk : grown, m.unk * s}, newA, newB);
  const I scaled = reinterpret_cast<I>(grownCell) < 0;
  const I keep = (denominator <= 0.0f) | general;
  a = keep ? a : (scaled ? a * s : newA);
  b = keep ? b : (scaled ? b * s : newB);
  return signBits(reinterpret_cast<V>(general));
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
static_assert(sizeof(DempsterShaferCell) == 2 * sizeof(float) &&
              sizeof(DempsterShaferCell) == sizeof(double));

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

SG_RUN_CLONES void additionOccupied(const EvidenceRuns& runs, OccupiedEvidence* occ, double scale) {
  // po > 0 exactly where c.occupied > 0, the scale being positive and finite: the product of a
  // float and a scale of at least 2^-63 cannot round to 0 in double.
  eachGroup(
      runs, occ,
      [scale](const float*, const float* occupied, const float*, OccupiedEvidence* cells)
          SG_INLINE_LAMBDA {
            const Doubles po = widen(occupied) * scale;
            const Doubles m = widen(cells);
            narrow(cells, po > 0.0 ? m + po - m * po : m);
          },
      true);
}

SG_RUN_CLONES void occupiedSpans(const EvidenceRuns& runs, EvidenceRuns& deferred) {
  std::size_t used = deferred.valuesEnd();
  for (const EvidenceRuns::Run& run : runs.runs) {
    const float* const occupied = runs.occupied.data() + run.first;
    const int n = run.count;
    // Eight values at a time, a bit each for "not ±0" (the vector == holds for ±0 and not for NaN
    // or denormals, as the scalar == does; nothing in the program sets the CPU to treat denormals
    // as zero); the last group's bits past the run, read from the room kRunPadding keeps past the
    // last run, are cleared.
    int lo = -1, hi = 0;  // the first value of evidence, and one past the last
    for (int k = 0; k < n; k += 8) {
      Floats8 v;
      std::memcpy(&v, occupied + k, sizeof v);
      unsigned bits =
          ~static_cast<unsigned>(signBits(reinterpret_cast<Floats8>(v == 0.0f))) & 0xffu;
      if (n - k < 8) bits &= (1u << (n - k)) - 1u;
      if (bits == 0) continue;
      if (lo < 0) lo = k + __builtin_ctz(bits);
      hi = k + 32 - __builtin_clz(bits);
    }
    if (lo < 0) continue;
    const auto count = static_cast<std::size_t>(hi - lo);
    // kRunPadding values of room past the span, zeros, which the lanes read from a short run's
    // start and throw away (eachGroup).
    const std::size_t room = used + count + kRunPadding;
    if (deferred.occupied.size() < room) deferred.occupied.resize(room);
    std::copy_n(occupied + lo, count, deferred.occupied.data() + used);
    std::fill_n(deferred.occupied.data() + used + count, kRunPadding, 0.0f);
    deferred.runs.push_back(
        {run.cell + static_cast<std::uint32_t>(lo), hi - lo, static_cast<std::uint32_t>(used)});
    used += count;
  }
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
  eachListed(cells, plane, [p](Doubles m) SG_INLINE_LAMBDA {
    const Doubles num = p * m;
    const Doubles den = num + (1.0 - p) * (1.0 - m);
    return den > 0.0 ? num / den : m;
  });
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

SG_RUN_CLONES void dempsterShaferUniform(float occupied, float empty,
                                         std::span<const std::uint32_t> cells,
                                         DempsterShaferCell* plane) {
  const float o = std::clamp(occupied, 0.0f, 1.0f);
  const float e = std::clamp(empty, 0.0f, 1.0f);
  if (e != 0.0f && o != 0.0f) {  // both kinds: cellrule's general case, one cell at a time
    for (const std::uint32_t c : cells) generalDempsterShafer(occupied, empty, plane[c]);
    return;
  }
  // One kind of evidence: eight cells at a time (eachListedGroup<2 * W>), gathered as eight 8-byte
  // pairs into lo = a0 b0 … a3 b3 and hi = a4 b4 … a7 b7, and scattered back.
  eachListedGroup<2 * W>(cells, [=](const std::uint32_t* c) SG_INLINE_LAMBDA {
    const Doubles lo = gather(plane, c), hi = gather(plane, c + W);
    const Floats8 lo8 = reinterpret_cast<Floats8>(lo), hi8 = reinterpret_cast<Floats8>(hi);
    Floats8 a = __builtin_shufflevector(lo8, hi8, 0, 2, 4, 6, 8, 10, 12, 14);
    Floats8 b = __builtin_shufflevector(lo8, hi8, 1, 3, 5, 7, 9, 11, 13, 15);
    dempsterShaferLanes(Floats8{} + occupied, Floats8{} + empty, a, b);
    const Doubles newLo =
        reinterpret_cast<Doubles>(__builtin_shufflevector(a, b, 0, 8, 1, 9, 2, 10, 3, 11));
    const Doubles newHi =
        reinterpret_cast<Doubles>(__builtin_shufflevector(a, b, 4, 12, 5, 13, 6, 14, 7, 15));
    scatter(plane, c, newLo);
    scatter(plane, c + W, newHi);
  });
}

}  // namespace sg::runs
