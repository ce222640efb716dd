// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/metrics/two_run_comparison.h"

#include <stdexcept>

namespace sg {

TwoRunComparison compareTwoRuns(const OccupancyMap& a, const OccupancyMap& b) {
  if (!(a.spec == b.spec))
    throw std::invalid_argument("two-run comparison: the maps are on different grids");
  const std::size_t n = a.spec.cellCount();
  if (a.probability.size() != n || b.probability.size() != n || a.observed.size() != n ||
      b.observed.size() != n) {
    throw std::invalid_argument("two-run comparison: the maps' layers do not match their grid");
  }
  TwoRunComparison out;
  for (std::size_t i = 0; i < n; ++i) {
    if (a.observed[i] == 0 || b.observed[i] == 0) continue;
    const bool occupiedA = a.probability[i] > 0.5;
    const bool occupiedB = b.probability[i] > 0.5;
    if (occupiedA == occupiedB)
      ++out.positive;
    else
      ++out.negative;
  }
  return out;
}

}  // namespace sg
