// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The shape every cone model shares. A model's per-reading constants are a `Shape<S>` (S = double
// or float) with one formula,
//   template <class T> [[gnu::always_inline]] ConeValue<T> value(T delta, T absTheta) const,
// for a point already known to be within the reach and the half-angle (always inlined: the row
// loops of coneRow() and coneRowRuns() both call it, and a call per group of lanes, its values
// returned through memory, cost Konolige's batch re-map a third). T = double serves
// evaluate() (the beam view); T = four float lanes serve footprint(), which evaluates the cone a
// grid row at a time. Both are the same formula, so what the beam view shows is what the mapper
// writes, to single precision (footprints are stored in floats anyway; footprint.h).

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>
#include <vector>

#include "sonargrid/engine/sensor_model.h"
#include "sonargrid/models/cone_raster.h"
#include "sonargrid/simd/lanes.h"

namespace sg {

// A model's value at points inside the cone: which region (bools, or lane masks) and the three
// values a Footprint cell carries. A point in neither region is left alone by the reading.
template <class T>
struct ConeValue {
  using Mask = decltype(T{} < T{});
  Mask occupied;  // Region I
  Mask empty;     // Region II (only where not occupied)
  T pE, pO, p;
};

// One reading of a cone model: whether it writes anything, how far and how wide, and its shape.
template <class Shape>
struct ConeBeam {
  bool active = false;
  double reach = 0.0;
  double halfAngle = 0.0;
  Shape shape;
};

// A threshold for comparisons with a float distance or angle d: the float that leaves `d >= x`
// (roundUp) or `d <= x` (roundDown) the same test as in double, so footprints and evaluate() agree
// on every region boundary. Identity for double.
template <class S>
S roundUp(double x) {
  if constexpr (std::is_same_v<S, float>) {
    float f = static_cast<float>(x);
    if (static_cast<double>(f) < x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
    return f;
  } else {
    return x;
  }
}
template <class S>
S roundDown(double x) {
  if constexpr (std::is_same_v<S, float>) {
    float f = static_cast<float>(x);
    if (static_cast<double>(f) > x) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
    return f;
  } else {
    return x;
  }
}

// Appends the cells of one row, `row.count` of them, to dst; returns the new end. dst has room
// for lanes::kWidth − 1 entries past the row (written, then overwritten or cut off).
template <class Shape>
CellEvidence* coneRow(const Shape& shape, const ConeRow& row, CellEvidence* dst) {
  using lanes::Floats;
  using Cells = std::uint32_t __attribute__((vector_size(16)));
  constexpr int W = lanes::kWidth;
  // bearing − heading in two steps, hi then lo: the first is exact (Sterbenz) near the axis, so
  // the angle off the axis keeps near double accuracy.
  const float hHi = static_cast<float>(row.heading);
  const float hLo = static_cast<float>(row.heading - static_cast<double>(hHi));
  static_assert(BeamTables::kPadding >= W - 1);
  const lanes::Ints lane = {0, 1, 2, 3};
  Cells cells = row.cell + Cells{0, 1, 2, 3};
  for (int k = 0; k < row.count; k += W, cells += W) {
    // The last group may read up to W − 1 entries past the row (the tables are padded for it).
    const BeamTables::Entry* e = row.entries + k;
    const Floats lo = lanes::load(&e[0].distance), hi = lanes::load(&e[2].distance);
    const Floats delta = __builtin_shufflevector(lo, hi, 0, 2, 4, 6);
    const Floats bearing = __builtin_shufflevector(lo, hi, 1, 3, 5, 7);
    const ConeValue<Floats> v = shape.value(delta, lanes::abs((bearing - hHi) - hLo));
    // Four CellEvidence {cell, empty, occupied, probability}: a 4 × 4 transpose.
    Floats c0 = reinterpret_cast<Floats>(cells);
    Floats c1 = v.pE, c2 = v.pO, c3 = v.p;
    lanes::transpose(c0, c1, c2, c3);
    static_assert(sizeof(CellEvidence) == sizeof(Floats));
    std::memcpy(static_cast<void*>(dst + 0), &c0, sizeof c0);
    std::memcpy(static_cast<void*>(dst + 1), &c1, sizeof c1);
    std::memcpy(static_cast<void*>(dst + 2), &c2, sizeof c2);
    std::memcpy(static_cast<void*>(dst + 3), &c3, sizeof c3);
    // Lanes past the row's end count as kept: they are cut off below.
    const int n = std::min(W, row.count - k);
    const lanes::Ints keep = v.occupied | v.empty | (lane >= n);
    if (lanes::all(keep)) {
      dst += n;
    } else {  // a cell the reading says nothing about: rare, at the edge of a region
      CellEvidence* kept = dst;
      for (int j = 0; j < n; ++j) {
        if (keep[j]) *kept++ = dst[j];
      }
      dst = kept;
    }
  }
  return dst;
}

// Vectors of W float and int lanes.
template <int W>
struct LaneTypes;
template <>
struct LaneTypes<lanes::kWidth> {
  using Floats = lanes::Floats;
  using Ints = lanes::Ints;
};
#ifdef SG_WIDE_LANES
template <>
struct LaneTypes<lanes::kWideWidth> {
  using Floats = lanes::WideFloats<>;
  using Ints = lanes::WideInts<>;
};
#endif

// coneRow() side by side instead of as CellEvidence, appended to `out` from value index `next`
// (which it advances): the same formula per lane, the same values, no 4 × 4 transpose; in W = 4
// lanes, or 8 (coneRunsWide). The row is one run unless a lane at the edge of a region writes
// nothing. `out`'s arrays have room for W − 1 values past the row, and `kept` for a mask per cell
// and W − 1 more. The row's runs are stored at runEnd, which it advances, in room sized once a
// reading (coneRunsIn): no call in the rows' loop (push_back's growth was one), so the shape's
// broadcast values can stay in registers from row to row instead of being spilled around it.
template <class Shape, int W>
[[gnu::always_inline]] inline void coneRowRuns(const Shape& model, const ConeRow& row,
                                               EvidenceRuns& out, std::size_t& next,
                                               std::int32_t* kept, EvidenceRuns::Run*& runEnd) {
  // The shape's and the row's values as locals: the loop's float and int stores could otherwise
  // alias them, and the compiler loaded and broadcast every one of them again per group of lanes.
  static_assert(std::is_trivially_copyable_v<Shape>);
  const Shape shape = model;
  const int count = row.count;
  const BeamTables::Entry* const entries = row.entries;
  // As in coneRow(), operation for operation.
  const float hHi = static_cast<float>(row.heading);
  const float hLo = static_cast<float>(row.heading - static_cast<double>(hHi));
  static_assert(BeamTables::kPadding >= W - 1);
  float* const empty = out.empty.data() + next;
  float* const occupied = out.occupied.data() + next;
  float* const probability = out.probability.data() + next;
  using F = typename LaneTypes<W>::Floats;
  using I = typename LaneTypes<W>::Ints;
  I lane;  // each lane's cell in the row: k + j
  for (int j = 0; j < W; ++j) lane[j] = j;
  const I last = I{} + (count - 1);
  I every = I{} - 1;  // every lane set
  for (int k = 0; k < count; k += W, lane += W) {
    const BeamTables::Entry* e = entries + k;
    F lo, hi;
    std::memcpy(&lo, &e[0].distance, sizeof lo);
    std::memcpy(&hi, &e[W / 2].distance, sizeof hi);
    F delta, bearing;
    if constexpr (W == 4) {
      delta = __builtin_shufflevector(lo, hi, 0, 2, 4, 6);
      bearing = __builtin_shufflevector(lo, hi, 1, 3, 5, 7);
    } else {
      delta = __builtin_shufflevector(lo, hi, 0, 2, 4, 6, 8, 10, 12, 14);
      bearing = __builtin_shufflevector(lo, hi, 1, 3, 5, 7, 9, 11, 13, 15);
    }
    const ConeValue<F> v = shape.value(delta, lanes::abs((bearing - hHi) - hLo));
    std::memcpy(empty + k, &v.pE, sizeof v.pE);
    std::memcpy(occupied + k, &v.pO, sizeof v.pO);
    std::memcpy(probability + k, &v.p, sizeof v.p);
    // Which lanes the reading writes (lanes past the row's end count as written: cut off).
    const I keep = v.occupied | v.empty | (lane > last);
    std::memcpy(kept + k, &keep, sizeof keep);
    every &= keep;
  }
  const bool all = lanes::all(every);
  const auto first = static_cast<std::uint32_t>(next);
  next += static_cast<std::size_t>(count);
  if (all) {
    *runEnd++ = EvidenceRuns::Run{row.cell, count, first};
    return;
  }
  // A cell the reading says nothing about (rare, at the edge of a region) splits the row.
  int begin = -1;  // of the run being extended
  for (int k = 0; k < count; ++k) {
    const bool keep = kept[k] != 0;
    if (keep && begin < 0) begin = k;
    if (!keep && begin >= 0) {
      *runEnd++ = EvidenceRuns::Run{row.cell + static_cast<std::uint32_t>(begin), k - begin,
                                    first + static_cast<std::uint32_t>(begin)};
      begin = -1;
    }
  }
  if (begin >= 0) {
    *runEnd++ = EvidenceRuns::Run{row.cell + static_cast<std::uint32_t>(begin), count - begin,
                                  first + static_cast<std::uint32_t>(begin)};
  }
}

// coneRuns() in W lanes: the rasteriser and the rows' evaluation in one function, so that the
// shape's values are set up in lanes once a reading rather than once a row. kSpanLanes: the
// rasteriser's spans in lanes too (forEachConeRow), where the function is built for AVX2 or later.
template <class Shape, int W, bool kSpanLanes = false>
[[gnu::always_inline]] inline void coneRunsIn(const ConeBeam<Shape>& pb, const Beam& beam,
                                              const GridSpec& grid, const BeamTables& tables,
                                              RowWindow window, EvidenceRuns& out) {
  static_assert(std::is_trivially_copyable_v<Shape>);
  static_assert(W - 1 <= static_cast<int>(kRunPadding), "a row's last lanes write past it");
  const Shape shape = pb.shape;  // a local: the rows' stores cannot alias it
  std::size_t next = out.valuesEnd();
  thread_local std::vector<std::int32_t> kept;  // a mask per cell of a row
  std::int32_t* keptData = nullptr;
  const std::size_t runsBefore = out.runs.size();
  EvidenceRuns::Run* runEnd = nullptr;
  // Eight lanes are built for AVX2, which rounds in one instruction.
  forEachConeRow<W == 8, kSpanLanes>(
      beam.sensor, pb.reach, pb.halfAngle, grid, tables,
      [&](std::size_t bound) {
        // A row of n cells gives at most (n + 1) / 2 <= n runs: room for `bound` of them.
        out.runs.resize(runsBefore + bound);
        runEnd = out.runs.data() + runsBefore;
        // Leaves new values unwritten (UninitialisedAllocator); the room past the last run
        // (kRunPadding, footprint.h) also takes the W − 1 values a row's last lanes write.
        const std::size_t need = next + bound + kRunPadding;
        if (out.empty.size() < need) {
          out.empty.resize(need);
          out.occupied.resize(need);
          out.probability.resize(need);
        }
        if (kept.size() < bound + W) kept.resize(bound + W);
        keptData = kept.data();
      },
      [&](const ConeRow& row)
          SG_ROW_INLINE { coneRowRuns<Shape, W>(shape, row, out, next, keptData, runEnd); },
      window);
  out.runs.resize(runEnd ? static_cast<std::size_t>(runEnd - out.runs.data()) : runsBefore);
}

#ifdef SG_WIDE_LANES
// coneRuns() in eight lanes, built for AVX2 (without FMA, so every lane does what the four-lane
// build does, and the rasteriser's scalar arithmetic gives the same bits); called only where the
// CPU has AVX2.
template <class Shape>
__attribute__((target("avx2"))) void coneRunsWide(const ConeBeam<Shape>& pb, const Beam& beam,
                                                  const GridSpec& grid, const BeamTables& tables,
                                                  RowWindow window, EvidenceRuns& out) {
  coneRunsIn<Shape, lanes::kWideWidth, true>(pb, beam, grid, tables, window, out);
}
// The same eight lanes built for AVX-512 (F, VL, BW, DQ): the same operations on the same 32-byte
// vectors (still no FMA: the files are built with -ffp-contract=off), with 32 vector registers
// instead of 16, so that the shape's values and the lanes' intermediates stay in registers rather
// than on the stack. Called only where the CPU has all four.
template <class Shape>
__attribute__((target("avx2,avx512f,avx512vl,avx512bw,avx512dq"))) void coneRunsWide512(
    const ConeBeam<Shape>& pb, const Beam& beam, const GridSpec& grid, const BeamTables& tables,
    RowWindow window, EvidenceRuns& out) {
  coneRunsIn<Shape, lanes::kWideWidth, true>(pb, beam, grid, tables, window, out);
}
#endif

// The cells of coneFootprint(), as runs.
template <class Shape>
void coneRuns(const ConeBeam<Shape>& pb, const Beam& beam, const GridSpec& grid,
              const BeamTables& tables, RowWindow window, EvidenceRuns& out) {
  if (!pb.active) return;
#ifdef SG_WIDE_LANES
  switch (coneLanes()) {
    case ConeLanes::Avx512:
      return coneRunsWide512(pb, beam, grid, tables, window, out);
    case ConeLanes::Avx2:
      return coneRunsWide(pb, beam, grid, tables, window, out);
    case ConeLanes::Four:
      break;
  }
#endif
  coneRunsIn<Shape, lanes::kWidth>(pb, beam, grid, tables, window, out);
}

// The footprint of one reading: the cone's rows, evaluated in lanes.
template <class Shape>
void coneFootprint(const ConeBeam<Shape>& pb, const Beam& beam, const GridSpec& grid,
                   const BeamTables& tables, Footprint& out, RowWindow window = {}) {
  if (!pb.active) return;
  const std::size_t start = out.cells.size();
  CellEvidence* dst = nullptr;
  forEachConeRow(
      beam.sensor, pb.reach, pb.halfAngle, grid, tables,
      [&](std::size_t bound) {
        // Leaves the new entries unwritten (UninitialisedAllocator); the last lanes of a row may
        // write up to kWidth − 1 entries past its end.
        out.cells.resize(start + bound + lanes::kWidth - 1);
        dst = out.cells.data() + start;
      },
      [&](const ConeRow& row) { dst = coneRow(pb.shape, row, dst); }, window);
  out.cells.resize(dst ? static_cast<std::size_t>(dst - out.cells.data()) : start);
}

// The scalar value, as evaluate() gives it.
template <class Shape>
ModelValue coneValueAt(const ConeBeam<Shape>& pb, double delta, double theta) {
  if (!pb.active || std::abs(theta) > pb.halfAngle || delta > pb.reach) return {};
  const ConeValue<double> v = pb.shape.value(delta, std::abs(theta));
  if (v.occupied) return ModelValue{BeamRegion::Occupied, v.pE, v.pO, v.p};
  if (v.empty) return ModelValue{BeamRegion::Empty, v.pE, v.pO, v.p};
  return {};
}

// What every cone model shares: its declaration is staticInfo(), and evaluate() and footprint() are
// its per-reading prepare<S>(range, maxRange) followed by the formula at one point or over the
// rasterised cone. A model supplies staticInfo(), configure(), reach() and prepare().
template <class Derived>
class ConeModel : public SensorModel {
 public:
  const ModelInfo& info() const final { return Derived::staticInfo(); }
  ModelValue evaluate(double delta, double theta, double range, double maxRange) const final {
    return coneValueAt(self().template prepare<double>(range, maxRange), delta, theta);
  }
  void footprint(const Beam& beam, const GridSpec& grid, const BeamTables& tables,
                 Footprint& out) const final {
    coneFootprint(self().template prepare<float>(beam.range, beam.maxRange), beam, grid, tables,
                  out);
  }
  bool rasterisesRows() const final { return true; }
  void footprintRows(const Beam& beam, const GridSpec& grid, const BeamTables& tables,
                     RowWindow window, Footprint& out) const final {
    coneFootprint(self().template prepare<float>(beam.range, beam.maxRange), beam, grid, tables,
                  out, window);
  }
  bool evidenceRuns(const Beam& beam, const GridSpec& grid, const BeamTables& tables,
                    RowWindow window, EvidenceRuns& out) const final {
    coneRuns(self().template prepare<float>(beam.range, beam.maxRange), beam, grid, tables, window,
             out);
    return true;
  }

 private:
  const Derived& self() const { return static_cast<const Derived&>(*this); }
};

// p = 0.5 + (pO - pE) / 2 and back: the translation paper 001 §3.2 uses between evidence and a
// probability, shared by the models whose native output is one of the two.
inline ModelValue fromEvidence(BeamRegion region, double empty, double occupied) {
  return ModelValue{region, empty, occupied, 0.5 + 0.5 * (occupied - empty)};
}
inline ModelValue fromProbability(double p) {
  if (p > 0.5) return ModelValue{BeamRegion::Occupied, 0.0, 2.0 * p - 1.0, p};
  return ModelValue{BeamRegion::Empty, 1.0 - 2.0 * p, 0.0, p};
}

// The "no echo" switch every model declares (notes: a no-echo reading is free-space evidence only,
// or nothing — a documented choice per model).
ParameterSpec noEchoParameter(const std::string& freeMeaning);

}  // namespace sg
