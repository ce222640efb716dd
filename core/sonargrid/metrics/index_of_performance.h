// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The Index of Performance of paper 000 §3, eq 9:
//   I = Σ D_min(i, j) · CV(i, j) / Σ CV(i, j)   over the filled cells of the built map,
// D_min the distance from the cell's centre to the nearest APG cell centre, CV the cell's
// certainty value on 0..15 (IopWeight: the rule's own certainty of occupancy, or the display
// level). Reported in millimetres: one 10 cm cell away is 100 mm.
// Every filled cell counts, wherever it is (inside an object, outside the walls): IOP measures the
// dispersion of the map's obstacle evidence around the true edges and has no notion of "unknown".

#include <optional>
#include <string>
#include <vector>

#include "sonargrid/engine/occupancy_map.h"
#include "sonargrid/reference/actual_position_grid.h"

namespace sg {

// What CV(i, j) of eq 9 is (docs/metrics.md, "IOP weights").
enum class IopWeight {
  // The rule's own certainty of occupancy scaled to 0..15 (OccupancyMap::evidence × 15): HIMM its
  // CV, addition 15·Occ (paper 000 eq 7), probabilistic rules 15·(2p − 1), Dempster–Shafer
  // 15·m(occ). A map without an evidence layer (read from a ROS map) weighs by its level.
  Evidence,
  // The display level 0..15 (round(15 p) for most rules): every filled cell of a probabilistic
  // rule weighs at least 8.
  Level,
};
const char* iopWeightName(IopWeight w);  // "evidence", "level"
// "evidence" or "level"; false for anything else.
bool parseIopWeight(const std::string& text, IopWeight& out);

struct IopOptions {
  IopWeight weight = IopWeight::Evidence;  // paper 000 §3 and §5: see docs/metrics.md
  // A filled cell counts only when its weight is at least this (0..15); 0: every cell the rule
  // calls filled (occupied evidence beats free evidence).
  double filledThreshold = 0.0;
};

// The weight CV(i, j) of cell i, 0..15.
double iopCellWeight(const OccupancyMap& map, std::size_t i, IopWeight weight);

struct IndexOfPerformance {
  std::optional<double> mm;     // empty when no filled cell has CV > 0
  std::size_t filledCells = 0;  // filled cells that counted (weight ≥ the threshold)
  double cvSum = 0.0;
};

// Throws std::invalid_argument when the APG is on another grid or has no cell, or the threshold
// is outside 0..15.
IndexOfPerformance indexOfPerformance(const OccupancyMap& map, const ActualPositionGrid& apg,
                                      const IopOptions& options = {});

// Exact Euclidean distance, in cells, from every cell centre to the nearest APG cell centre
// (OpenCV's distanceTransform with DIST_L2 and DIST_MASK_PRECISE, the exact algorithm of
// Felzenszwalb & Huttenlocher). Row-major like GridSpec. The APG must not be empty.
std::vector<float> distanceToApg(const ActualPositionGrid& apg);

}  // namespace sg
