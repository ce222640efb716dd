// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The Index of Performance of paper 000 §3, eq 9:
//   I = Σ D_min(i, j) · CV(i, j) / Σ CV(i, j)   over the filled cells of the built map,
// D_min the distance from the cell's centre to the nearest APG cell centre, CV the cell's
// certainty value (its level, 0..15). Reported in millimetres: one 10 cm cell away is 100 mm.
// Every filled cell counts, wherever it is (inside an object, outside the walls): IOP measures the
// dispersion of the map's obstacle evidence around the true edges and has no notion of "unknown".

#include <optional>
#include <vector>

#include "sonargrid/occupancy_map.h"
#include "sonargrid/reference/actual_position_grid.h"

namespace sg {

struct IndexOfPerformance {
  std::optional<double> mm;  // empty when no filled cell has CV > 0
  std::size_t filledCells = 0;
  double cvSum = 0.0;
};

// Throws std::invalid_argument when the APG is on another grid or has no cell.
IndexOfPerformance indexOfPerformance(const OccupancyMap& map, const ActualPositionGrid& apg);

// Exact Euclidean distance, in cells, from every cell centre to the nearest APG cell centre
// (OpenCV's distanceTransform with DIST_L2 and DIST_MASK_PRECISE, the exact algorithm of
// Felzenszwalb & Huttenlocher). Row-major like GridSpec. The APG must not be empty.
std::vector<float> distanceToApg(const ActualPositionGrid& apg);

}  // namespace sg
