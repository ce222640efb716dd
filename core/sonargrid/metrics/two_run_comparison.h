// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The third goodness measure of paper 002 §5: two runs over the same place should give the same
// map. Both maps are thresholded to binary (occupied when p > 0.5) and compared cell by cell, after
// Moravec & Elfes: a positive count for each cell equal in both, a negative count for each cell
// that differs. Only cells observed in both runs are compared: a cell one run never saw says
// nothing about agreement, and counting it would reward the larger blank margin.

#include <cstddef>

#include "sonargrid/engine/occupancy_map.h"

namespace sg {

struct TwoRunComparison {
  std::size_t positive = 0;  // cells equal in both binary maps
  std::size_t negative = 0;  // cells that differ
};

// Throws std::invalid_argument unless both maps are on the same grid (build them on one GridSpec
// covering both runs).
TwoRunComparison compareTwoRuns(const OccupancyMap& a, const OccupancyMap& b);

}  // namespace sg
