// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/metrics/map_entropy.h"

#include <cmath>
#include <stdexcept>

namespace sg {

double cellEntropyBits(double p) {
  if (!(p > 0.0) || !(p < 1.0)) return 0.0;  // 0 log 0 = 0; NaN counts as known (never stored)
  return -p * std::log2(p) - (1.0 - p) * std::log2(1.0 - p);
}

MapEntropy mapEntropy(const OccupancyMap& map) {
  const std::size_t n = map.spec.cellCount();
  if (map.probability.size() != n || map.observed.size() != n)
    throw std::invalid_argument("mapEntropy: the map's layers do not match its grid");
  MapEntropy out;
  for (std::size_t i = 0; i < n; ++i) {
    const double h = cellEntropyBits(map.probability[i]);
    out.totalBits += h;
    if (map.observed[i] == 0) continue;
    out.observedBits += h;
    ++out.cellsObserved;
  }
  if (out.cellsObserved > 0)
    out.meanBits = out.observedBits / static_cast<double>(out.cellsObserved);
  return out;
}

}  // namespace sg
