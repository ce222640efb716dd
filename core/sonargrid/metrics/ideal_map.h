// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The ideal map: what a perfect map of the reference would hold in each cell of the scored grid
// (paper 001 §4 compares built maps with "hand drawn ideal maps"). Edges of the reference (its
// APG) are occupied; other cells are free where the reference says the robot's space is, and
// unknown where nobody can know (docs/metrics.md, "The ideal map"):
//   - inside a closed object: unknown, the robot cannot see into a box or a pillar;
//   - except inside an *enclosure*, a closed object that holds a corner of another object (the
//     walls of a room around its furniture): its inside is free space;
//   - when the reference has enclosures, everything outside all of them is unknown (behind walls);
//   - with an obstacle raster (ROS reference): a cell takes the raster's class at its centre
//     (free or unknown), and outside the raster it is unknown.
// A lone closed room with nothing in it therefore reads as a solid block: draw its walls as an
// open polyline that repeats the first corner to make its inside free.

#include <cstdint>
#include <vector>

#include "sonargrid/engine/occupancy_map.h"
#include "sonargrid/reference/actual_position_grid.h"
#include "sonargrid/reference/reference_map.h"

namespace sg {

enum class IdealCell : std::uint8_t { Free = 0, Occupied = 1, Unknown = 2 };

struct IdealMap {
  GridSpec spec;
  std::vector<IdealCell> cells;

  std::size_t count(IdealCell kind) const;

  // `apg` must be the reference's APG on `apg.spec`.
  static IdealMap fromReference(const ReferenceMap& reference, const ActualPositionGrid& apg);
};

// The cells every agreement metric (correlation, map score, cross-entropy, AUC...) is computed
// over: the ideal map knows the cell (free or occupied) and the built map observed it (at least one
// reading wrote it). A never-observed cell holds the prior, not the mapper's opinion, so counting
// it would score the size of the grid's margin rather than the map (docs/metrics.md).
inline bool evaluatedCell(const OccupancyMap& map, const IdealMap& ideal, std::size_t i) {
  return ideal.cells[i] != IdealCell::Unknown && map.observed[i] != 0;
}

// The strict inside (cell centre inside, by the even-odd rule) of a closed object, marked 1.
void markInterior(const GridSpec& spec, const std::vector<Position>& polygon,
                  std::vector<std::uint8_t>& inside);

}  // namespace sg
