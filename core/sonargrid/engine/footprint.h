// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What one reading writes into the grid: the sensor model's output, which the update rule consumes
// (the model / storage split of DESIGN.md). Every model fills all three values consistently:
//   empty     pE in [0, 1], evidence that the cell is free      (paper 000 eq 1, paper 001 §2.1.1)
//   occupied  pO in [0, 1], evidence that the cell is occupied  (paper 000 eq 4, paper 001 §2.1.2)
//   probability  P(occupied | this reading) as the model's likelihood, 0.5 = no information
//                (paper 002 §3.1, P(s|Occupied)); rules that need one number read this.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "sonargrid/data/pose.h"

namespace sg {

// Single precision keeps a cell's entry at 16 bytes: a re-map streams ~10⁸ of them, and the
// models are heuristics whose 7 significant digits are more than they mean. Rules accumulate in
// double.
// Trivially constructible, so a Footprint can be grown without writing it twice (see below).
struct CellEvidence {
  std::uint32_t cell;  // linear index into the grid
  float empty;
  float occupied;
  float probability;

  CellEvidence() = default;
  CellEvidence(std::uint32_t c, double e, double o, double p)
      : cell(c),
        empty(static_cast<float>(e)),
        occupied(static_cast<float>(o)),
        probability(static_cast<float>(p)) {}
};

// An allocator whose value-less construct() leaves trivially constructible elements unwritten, so
// the rasteriser can size a footprint for a whole reading at once and fill it through a pointer.
template <class T>
struct UninitialisedAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = UninitialisedAllocator<U>;
  };
  UninitialisedAllocator() = default;
  template <class U>
  UninitialisedAllocator(const UninitialisedAllocator<U>&) noexcept {}
  template <class U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

struct Footprint {
  std::vector<CellEvidence, UninitialisedAllocator<CellEvidence>> cells;
  void clear() { cells.clear(); }
};

// Some readings' cells for a model whose every reading gives its cells one of two values (HIMM's
// axis: free evidence before the echo, the hit at it; SensorModel::listDirect): entry k, one per
// reading the model writes with (those it skips, such as no-echo readings left alone, have none;
// an entry may hold no cell when they all lie outside the grid), has cells[k == 0 ? 0 :
// ends[k − 1] .. ends[k]), the cells its footprint would hold in the same order, and the first
// frees[k] of them take the first value.
struct DirectCells {
  std::vector<std::uint32_t> cells;
  std::vector<std::uint32_t> ends, frees;
  void clear() {
    cells.clear();
    ends.clear();
    frees.clear();
  }
};

// A reading's cells as runs of consecutive cells of one grid row, with the model's three values
// side by side: what the cone models hand the rules directly on the mapper's batch path
// (Mapper::integrateBeams without an observer), where a Footprint would be written and read back
// once per cell. Run r is cells r.cell .. r.cell + r.count − 1, their values at [r.first,
// r.first + r.count) of the three arrays; the cells and values are those the Footprint would hold,
// in the same order. The arrays are sized by the writer, with room for kRunPadding values past the
// last run, which a rule's lanes may read (and ignore) from a short run's start.
inline constexpr std::size_t kRunPadding = 7;
struct EvidenceRuns {
  struct Run {
    std::uint32_t cell;
    int count;
    std::uint32_t first;
  };
  std::vector<Run, UninitialisedAllocator<Run>> runs;
  std::vector<float, UninitialisedAllocator<float>> empty, occupied, probability;
  void clear() { runs.clear(); }
  // One past the last run's values: where a writer appends the next run's (runs are appended in
  // order of their values; 0 with no runs).
  std::size_t valuesEnd() const {
    return runs.empty() ? 0 : runs.back().first + static_cast<std::size_t>(runs.back().count);
  }
};

// The grid rows a footprint is restricted to: those of [begin, end) (all rows by default). The
// mapper gives each of its threads one band of consecutive rows (mapper.cpp, row_bands.h).
struct RowWindow {
  int begin = 0;
  int end = std::numeric_limits<int>::max() / 2;  // room for arithmetic on it
  bool contains(int row) const { return row >= begin && row < end; }
  // f(row) for every row of [lo, hi] (rows >= 0) that contains() accepts, in increasing order. f is
  // called from one place, so that the compiler inlines it, and forEachRow is always inlined, so
  // that it is built for the caller's target (the cone rasteriser's AVX2 function, cone_model.h).
  template <class F>
  [[gnu::always_inline]] void forEachRow(int lo, int hi, F&& f) const {
    const int last = lastRow(hi);
    for (int row = firstRow(lo); row <= last; ++row) f(row);
  }
  // The first and the last row forEachRow(lo, hi, …) visits (none where first > last).
  int firstRow(int lo) const { return std::max({lo, begin, 0}); }
  int lastRow(int hi) const { return std::min(hi, end - 1); }
};

// One reading placed in the world.
struct Beam {
  Pose2D sensor;          // world pose of the transducer
  double range = 0.0;     // metres, or Reading::kNoEcho
  double maxRange = 5.0;  // of the transducer: a no-echo reading clears at most this far
  bool echo() const { return std::isfinite(range); }
};

}  // namespace sg
