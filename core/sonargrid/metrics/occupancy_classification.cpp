// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/metrics/occupancy_classification.h"

#include <algorithm>
#include <stdexcept>
#include <utility>
#include <vector>

namespace sg {

OccupancyClassification classifyOccupancy(const OccupancyMap& map, const IdealMap& ideal) {
  if (!(map.spec == ideal.spec))
    throw std::invalid_argument("classification: the ideal map is on another grid");
  const std::size_t n = map.spec.cellCount();
  if (map.probability.size() != n || map.observed.size() != n) {
    throw std::invalid_argument("classification: the map's layers do not match its grid");
  }
  OccupancyClassification out;
  std::vector<std::pair<double, bool>> scored;  // (p, ideal occupied)
  for (std::size_t i = 0; i < n; ++i) {
    if (!evaluatedCell(map, ideal, i)) continue;
    const double p = map.probability[i];
    const bool truth = ideal.cells[i] == IdealCell::Occupied;
    const bool predicted = p > 0.5;
    if (predicted && truth)
      ++out.truePositive;
    else if (predicted)
      ++out.falsePositive;
    else if (truth)
      ++out.falseNegative;
    else
      ++out.trueNegative;
    scored.emplace_back(p, truth);
  }
  const auto tp = static_cast<double>(out.truePositive);
  const auto fp = static_cast<double>(out.falsePositive);
  const auto fn = static_cast<double>(out.falseNegative);
  if (tp + fp > 0) out.precision = tp / (tp + fp);
  if (tp + fn > 0) out.recall = tp / (tp + fn);
  if (tp + fp + fn > 0) {
    out.f1 = 2.0 * tp / (2.0 * tp + fp + fn);
    out.iou = tp / (tp + fp + fn);
  }

  // AUC = (sum of the positives' ranks − n₁(n₁ + 1)/2) / (n₁ n₀), tied scores sharing their mean
  // rank.
  const double positives = tp + fn;
  const double negatives = static_cast<double>(scored.size()) - positives;
  if (positives > 0 && negatives > 0) {
    std::sort(scored.begin(), scored.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    double rankSum = 0.0;
    std::size_t i = 0;
    while (i < scored.size()) {
      std::size_t j = i;
      std::size_t tiedPositives = 0;
      while (j < scored.size() && scored[j].first == scored[i].first)
        tiedPositives += scored[j++].second ? 1 : 0;
      const double meanRank =
          (static_cast<double>(i + 1) + static_cast<double>(j)) / 2.0;  // ranks i+1..j
      rankSum += meanRank * static_cast<double>(tiedPositives);
      i = j;
    }
    out.auc = (rankSum - positives * (positives + 1.0) / 2.0) / (positives * negatives);
  }
  return out;
}

}  // namespace sg
