// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The built map as a classifier of occupied cells, against the ideal map (beyond the papers):
//   ROC AUC of p(occ) as a score (ties count one half: the Mann–Whitney U with mid-ranks);
//   precision, recall, F1 and IoU of the occupied class, a cell predicted occupied when p > 0.5
//   (the threshold of paper 001's "map score of occupied cells" and of the two-run comparison).
// Over the evaluated cells (ideal known and built observed; see ideal_map.h).

#include <cstddef>
#include <optional>

#include "sonargrid/engine/occupancy_map.h"
#include "sonargrid/metrics/ideal_map.h"

namespace sg {

struct OccupancyClassification {
  std::size_t truePositive = 0, falsePositive = 0, falseNegative = 0, trueNegative = 0;
  std::optional<double> auc;        // empty unless both classes are present
  std::optional<double> precision;  // empty when nothing is predicted occupied
  std::optional<double> recall;     // empty when nothing is occupied in the ideal map
  std::optional<double> f1;         // empty when both of the above are
  std::optional<double> iou;
};

// Throws std::invalid_argument when the maps are on different grids.
OccupancyClassification classifyOccupancy(const OccupancyMap& map, const IdealMap& ideal);

}  // namespace sg
