// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/metrics/map_agreement.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sg {

MapAgreement mapAgreement(const OccupancyMap& map, const IdealMap& ideal) {
  if (!(map.spec == ideal.spec))
    throw std::invalid_argument("map agreement: the ideal map is on another grid");
  const std::size_t n = map.spec.cellCount();
  if (map.probability.size() != n || map.observed.size() != n) {
    throw std::invalid_argument("map agreement: the map's layers do not match its grid");
  }
  MapAgreement out;
  double sumP = 0.0, sumY = 0.0;
  double squared = 0.0, squaredOccupied = 0.0, logLoss = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!evaluatedCell(map, ideal, i)) continue;
    const double p = std::clamp(map.probability[i], 0.0, 1.0);
    const double y = ideal.cells[i] == IdealCell::Occupied ? 1.0 : 0.0;
    ++out.cellsEvaluated;
    sumP += p;
    sumY += y;
    const double d2 = (p - y) * (p - y);
    squared += d2;
    if (p > 0.5 || y == 1.0) {
      ++out.cellsOccupiedEvaluated;
      squaredOccupied += d2;
    }
    // p·q + (1 − p)(1 − q) with q ∈ {0, 1} is the probability the map gives the true state.
    const double pc = std::clamp(p, kProbabilityFloor, 1.0 - kProbabilityFloor);
    logLoss += -std::log2(y == 1.0 ? pc : 1.0 - pc);
  }
  if (out.cellsEvaluated == 0) return out;
  const double count = static_cast<double>(out.cellsEvaluated);
  out.mapScorePct = 100.0 * squared / count;
  out.brier = squared / count;
  if (out.cellsOccupiedEvaluated > 0) {
    out.mapScoreOccupiedPct =
        100.0 * squaredOccupied / static_cast<double>(out.cellsOccupiedEvaluated);
  }
  out.crossEntropyBits = logLoss / count;
  out.matchBits = count - logLoss;

  // Pearson's r in a second pass about the means (numerically safe for a million cells).
  const double meanP = sumP / count, meanY = sumY / count;
  double sxy = 0.0, sxx = 0.0, syy = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!evaluatedCell(map, ideal, i)) continue;
    const double dp = std::clamp(map.probability[i], 0.0, 1.0) - meanP;
    const double dy = (ideal.cells[i] == IdealCell::Occupied ? 1.0 : 0.0) - meanY;
    sxy += dp * dy;
    sxx += dp * dp;
    syy += dy * dy;
  }
  if (sxx > 0.0 && syy > 0.0) out.correlationPct = 100.0 * sxy / std::sqrt(sxx * syy);
  return out;
}

}  // namespace sg
