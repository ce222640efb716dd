// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Dempster–Shafer's update in four or eight float lanes, for the run kernels (run_kernels.cpp, its
// only includer): each lane does what cellrule::dempsterShafer (cell_updates.h) does to one cell,
// operation for operation, on the cell's two floats a and b (DempsterShaferCell). Templates
// without a target, always inlined into the kernels' clones and AVX-512 functions.

// A kernel's lambdas are inlined into each clone: one left out of line is built for the baseline,
// its 32-byte vectors passed through memory (GCC did so with Dempster–Shafer's, 4 × slower).
#if defined(__GNUC__) && !defined(__clang__)
#define SG_INLINE_LAMBDA __attribute__((always_inline))
#else
#define SG_INLINE_LAMBDA
#endif

#include "sonargrid/rules/rule_classes.h"
#include "sonargrid/simd/lanes.h"

namespace sg::runs {

// DempsterShaferCell::masses() and ::of() per lane, on four or eight cells' a and b (V: Floats4 or
// Floats8), with I the int lanes of the same count.
using Floats4 = float __attribute__((vector_size(16)));
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
// DempsterShaferCell::floored() per lane: a magnitude other than 0 below kTiny becomes kTiny of
// its sign. As max(|v|, kTiny) where |v| is not 0, with v's sign: the same bits for every v (±0,
// NaN and infinities too: max keeps a NaN magnitude, which != 0 keeps), in and, max, compare
// and or, where a select on two compares took a blend of three operations on some CPUs.
template <class V>
[[gnu::always_inline]] inline V floored(V v) {
  using I = IntsOf<V>;
  const I sign = reinterpret_cast<I>(v) & int(0x80000000u);
  const V m = magnitude(v);
  const I kept = reinterpret_cast<I>(lanes::max(m, V{} + DempsterShaferCell::kTiny)) & (m != 0.0f);
  return reinterpret_cast<V>(kept | sign);
}
template <class V>
[[gnu::always_inline]] inline void cellsOf(const Masses<V>& m, V& a, V& b) {
  const IntsOf<V> unkLeftOut = (m.unk >= m.occ) & (m.unk >= m.emp);
  const IntsOf<V> occLeftOut = ~unkLeftOut & (m.occ >= m.emp);
  const IntsOf<V> empLeftOut = ~(unkLeftOut | occLeftOut);
  const V unk = floored(-magnitude(m.unk));
  a = occLeftOut ? unk : floored(magnitude(m.occ));
  b = empLeftOut ? unk : floored(magnitude(m.emp));
}
// Bit j set where lane j's sign bit is (movmskps, SSE: in every clone; eight lanes as two fours).
[[gnu::always_inline]] inline int signBits(Floats4 v) {
  return __builtin_ia32_movmskps(v);
}
[[gnu::always_inline]] inline int signBits(Floats8 v) {
  // The halves as shuffles: built from elements, GCC moved the lanes one at a time (three valignd,
  // three unpacks and a shuffle for the upper half, in the masked Dempster–Shafer kernel).
  return signBits(Floats4(__builtin_shufflevector(v, v, 0, 1, 2, 3))) |
         signBits(Floats4(__builtin_shufflevector(v, v, 4, 5, 6, 7))) << 4;
}
template <class V>
[[gnu::always_inline]] inline V clampUnit(V v) {
  return v < 0.0f ? V{} : (1.0f < v ? V{} + 1.0f : v);  // std::clamp(v, 0, 1)
}

// Dempster's rule on four or eight cells (a, b per lane), as cellrule::dempsterShafer's first two
// cases, for evidence of one kind per lane: x, the mass it adds to m(occ) or m(emp) as
// pick(forOccupied, forEmpty) chooses per lane (a select on the lanes' kinds, or one of the two
// where every lane has the same kind). `grow` is the mass x adds to, `shrink` the other. Lanes of
// total conflict, and lanes set in `leave`, keep their cells; `leaving` says whether any is set.
template <class V, class Pick>
[[gnu::always_inline]] inline void oneKindLanes(V x, Pick pick, IntsOf<V> leave, bool leaving, V& a,
                                                V& b) {
  using I = IntsOf<V>;
  constexpr int kAll = (1 << sizeof(V) / sizeof(float)) - 1;
  // Lanes where the mass x adds to is the one the cell leaves out (its sign bit): the other two are
  // a and b, and both scale by s. All lanes so, the usual case: nothing else to do.
  const V grownCell = pick(a, b);
  if (signBits(grownCell) == kAll && !leaving) {
    const V denominator = 1.0f - pick(b, a) * x;
    const V s = (1.0f - x) * (1.0f / denominator);
    const I keep = denominator <= 0.0f;  // total conflict
    a = keep ? a : floored(a * s);
    b = keep ? b : floored(b * s);
    return;
  }
  const Masses<V> m = masses(a, b);
  const V grow = pick(m.occ, m.emp);
  const V shrink = pick(m.emp, m.occ);
  const V denominator = 1.0f - shrink * x;
  const V inv = 1.0f / denominator;
  const V s = (1.0f - x) * inv;
  const V grown = (grow + m.unk * x) * inv;
  const V shrunk = shrink * s;
  V newA, newB;
  cellsOf<V>({pick(grown, shrunk), pick(shrunk, grown), m.unk * s}, newA, newB);
  const I scaled = reinterpret_cast<I>(grownCell) < 0;
  const I keep = (denominator <= 0.0f) | leave;
  a = keep ? a : (scaled ? floored(a * s) : newA);
  b = keep ? b : (scaled ? floored(b * s) : newB);
}

// oneKindLanes() for the model's evidence per lane: lanes with both kinds (which no model gives)
// are left as they were and set in the bits returned, for cellrule to do one at a time.
template <class V>
[[gnu::always_inline]] inline int dempsterShaferLanes(V occupied, V empty, V& a, V& b) {
  using I = IntsOf<V>;
  const V o = clampUnit(occupied), e = clampUnit(empty);
  const I onlyOccupied = e == 0.0f;
  const I onlyEmpty = o == 0.0f;
  const I general = ~(onlyOccupied | onlyEmpty);
  const int generalBits = signBits(reinterpret_cast<V>(general));
  auto pick = [onlyOccupied](V forOccupied, V forEmpty)
                  SG_INLINE_LAMBDA { return onlyOccupied ? forOccupied : forEmpty; };
  oneKindLanes(pick(o, e), pick, general, generalBits != 0, a, b);
  return generalBits;
}

// oneKindLanes() where every lane's evidence x is of the kind kOccupied says (the listed cells of
// HIMM's axis, a masked group of a run: fewer selects).
template <bool kOccupied, class V>
[[gnu::always_inline]] inline void dempsterShaferOneKind(V x, V& a, V& b) {
  auto pick = [](V forOccupied, V forEmpty)
                  SG_INLINE_LAMBDA { return kOccupied ? forOccupied : forEmpty; };
  oneKindLanes(x, pick, IntsOf<V>{}, false, a, b);
}

}  // namespace sg::runs
