// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Precomputed distance and bearing from a sensor to the centres of the cells around it, so that
// rasterising a sonar cone needs no per-cell sqrt or atan2 (the lookup-table inserter of
// Cartographer's 2-D grids). The sensor's position inside its cell is quantised to a
// `subdivisions` x `subdivisions` lattice of sub-cell centres, so distances are exact to within
// half a sub-cell diagonal: cellSize / (subdivisions * sqrt 2), 0.9 cm at 5 cm cells.

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

  BeamTables(double cellSize, int radiusCells, int subdivisions = kDefaultSubdivisions);

  double cellSize() const { return cellSize_; }
  int radius() const { return radius_; }
  int side() const { return 2 * radius_ + 1; }
  int subdivisions() const { return subdivisions_; }

  // The table for a sensor in sub-cell (qx, qy); entry (dx, dy) is at [(dy + R) * side + dx + R]
  // for the cell dx columns and dy rows away from the sensor's cell.
  const Entry* table(int qx, int qy) const {
    return entries_.data() + static_cast<std::size_t>(qy * subdivisions_ + qx) * tableSize_;
  }

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
  double cellSize_;
  int radius_;
  int subdivisions_;
  std::size_t tableSize_;
  std::vector<Entry> entries_;
};

}  // namespace sg
