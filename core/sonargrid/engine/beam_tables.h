// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Precomputed distance and bearing from a sensor to the centres of the cells around it, so that
// rasterising a sonar cone needs no per-cell sqrt or atan2 (the lookup-table inserter of
// Cartographer's 2-D grids). The sensor's position inside its cell is quantised to a
// `subdivisions` x `subdivisions` lattice of sub-cell centres, so distances are exact to within
// half a sub-cell diagonal: cellSize / (subdivisions * sqrt 2), 0.9 cm at 5 cm cells.

#include <cstddef>
#include <memory>
#include <vector>

namespace sg {

class BeamTables {
 public:
  struct Entry {
    float distance;  // metres, sensor to cell centre
    float bearing;   // radians in [-pi, pi], world frame
  };

  static constexpr int kDefaultSubdivisions = 4;
  // Entries past the end of any row that may be read (and ignored): lanes load whole groups (of
  // up to eight, cone_model.h).
  static constexpr int kPadding = 7;

  // subdivisions must be a power of two (std::invalid_argument otherwise).
  BeamTables(double cellSize, int radiusCells, int subdivisions = kDefaultSubdivisions);

  double cellSize() const { return cellSize_; }
  int radius() const { return radius_; }
  int side() const { return 2 * radius_ + 1; }
  int subdivisions() const { return subdivisions_; }

  // The table for a sensor in sub-cell (qx, qy), a row of cells at a time. Only the sub-cells of
  // the lower half (qy < (subdivisions + 1) / 2) have a table of their own; an upper one reads the
  // table of its mirror image about the cell's horizontal centre line, upside down. The offsets
  // from a sub-cell centre to the cell centres are exact in binary (subdivisions is a power of
  // two), so the mirrored offsets are the same offsets with y negated, and the distances read are
  // the very floats the sub-cell's own table would hold and the bearings exactly their negations
  // (hypot is even in y, atan2 odd; tst_geometry checks every entry). A reader of a mirrored view
  // negates the heading it compares bearings with (bit for bit the same test: IEEE rounding is
  // symmetric), or the bearing. Half the tables halve the memory and the cache misses of a
  // re-map, and the time to build them.
  struct View {
    const Entry* centre;     // entry (0, 0): the sensor's own cell
    std::ptrdiff_t rowStep;  // from row dy to row dy + 1: side(), or −side() when mirrored
    bool mirrored;           // the bearings read are the true ones negated
    // Entry (dx, dy), the cell dx columns and dy rows away from the sensor's cell, is row(dy)[dx]
    // for |dx|, |dy| <= radius(); consecutive dx are consecutive entries.
    const Entry* row(int dy) const { return centre + dy * rowStep; }
  };
  View view(int qx, int qy) const {
    const bool mirrored = qy >= storedRows();
    const int own = mirrored ? subdivisions_ - 1 - qy : qy;  // the sub-cell row with the table
    const Entry* t =
        entries_.data() + static_cast<std::size_t>(own * subdivisions_ + qx) * tableSize_;
    return View{t + static_cast<std::ptrdiff_t>(radius_) * side() + radius_,
                mirrored ? -static_cast<std::ptrdiff_t>(side()) : side(), mirrored};
  }
  // Entry (dx, dy) for sub-cell (qx, qy), with its true bearing.
  Entry entry(int qx, int qy, int dx, int dy) const {
    const View v = view(qx, qy);
    Entry e = v.row(dy)[dx];
    if (v.mirrored) e.bearing = -e.bearing;
    return e;
  }
  // Bytes the tables take.
  std::size_t bytes() const { return entries_.size() * sizeof(Entry); }

  // Tables for `cellSize` that reach at least `reach` metres, shared between mappers (thread-safe).
  // Their radius is radiusFor(cellSize, reach) or more: a cached table that reaches further serves,
  // and one that must replace a smaller one of the same cell size is at least 5/4 of its radius.
  static std::shared_ptr<const BeamTables> shared(double cellSize, double reach);

  // The radius shared() builds for a reach: ceil(reach / cellSize) + 2 cells, rounded up to a
  // multiple of kRadiusStep. Sliders that move the reach (ε, P3, a tolerance, a maximum range)
  // would otherwise rebuild the tables, 60 ms at 5 cm cells and a 10 m sonar, on every other step;
  // with the step, a slider's whole range needs one to three builds (1.6 m per step at 5 cm).
  static constexpr int kRadiusStep = 32;
  static int radiusFor(double cellSize, double reach);

 private:
  // The rows of sub-cells with a table of their own (View).
  int storedRows() const { return (subdivisions_ + 1) / 2; }

  double cellSize_;
  int radius_;
  int subdivisions_;
  std::size_t tableSize_;
  std::vector<Entry> entries_;
};

}  // namespace sg
