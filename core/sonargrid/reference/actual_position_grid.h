// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The actual position grid (APG) of paper 000 §3: "the lines connecting these coordinates are
// computed and projected onto a blank grid", a cell being 1 when an edge of an object passes
// through it. It is drawn on the grid of the map being scored (same origin, same cell size).
//
// Rasterisation is the supercover of each edge: every cell whose closed square the edge touches.
// So there are no gaps (consecutive cells share a side, never only a corner, which matters to the
// 8-connected path planner of the path comparison), an edge lying on a cell boundary marks the
// cells on both sides (no half-cell bias towards either), and an edge through a grid corner marks
// the four cells around it. Coordinates within 1e-6 cell of a boundary count as on it, so that a
// wall at 3.2 m sits on the boundary of 5 cm cells whatever the rounding of 3.2 / 0.05.
//
// An obstacle raster (a ROS reference) adds every map cell that an obstacle pixel overlaps with
// positive area.

#include <cstdint>
#include <vector>

#include "sonargrid/engine/grid_spec.h"
#include "sonargrid/reference/reference_map.h"

namespace sg {

struct ActualPositionGrid {
  GridSpec spec;
  std::vector<std::uint8_t> cells;  // 1 where an edge passes, row-major as GridSpec

  std::size_t count() const;
  bool empty() const { return count() == 0; }

  static ActualPositionGrid rasterise(const ReferenceMap& reference, const GridSpec& spec);
};

// Marks (sets to 1) the supercover of the segment a-b (world metres) within the grid.
void markSupercover(const GridSpec& spec, const Position& a, const Position& b,
                    std::vector<std::uint8_t>& cells);

// Marks every cell of `spec` that the raster's obstacle cells overlap with positive area.
void markRasterObstacles(const GridSpec& spec, const ObstacleRaster& raster,
                         std::vector<std::uint8_t>& cells);

}  // namespace sg
