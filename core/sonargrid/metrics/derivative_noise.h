// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Derivative noise, the second goodness measure of paper 002 §5, on p(occ) with a 3 × 3 window:
//   S(x, y) = Σ over the window |W(i, j) − W(x, y)|,  D(x, y) = S(x, y) / (3·3 − 1),
//   D_map = Σ D(x, y) over the interior cells (x = 2..M−1, y = 2..N−1 in the paper's 1-based
//   terms);
// and, because "if the maps are different in sizes then normalization is essential", the mean
// D_map / (number of cells scored).
// A cell is scored when it and its eight neighbours were all observed: a never-observed neighbour
// holds the prior 0.5, and its difference would be noise the map never had. Maps of the same run on
// grids of different margins thus get the same D_map.

#include <cstddef>
#include <optional>

#include "sonargrid/engine/occupancy_map.h"

namespace sg {

struct DerivativeNoise {
  double sum = 0.0;            // D_map
  std::optional<double> mean;  // D_map / cellsScored; empty when no cell was scored
  std::size_t cellsScored = 0;
};

// Throws std::invalid_argument when the layers do not match the grid.
DerivativeNoise derivativeNoise(const OccupancyMap& map);

}  // namespace sg
