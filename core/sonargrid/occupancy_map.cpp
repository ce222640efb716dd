// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/occupancy_map.h"

#include <algorithm>

namespace sg {

OccupancyMap OccupancyMap::unobserved(const GridSpec& spec) {
  OccupancyMap m;
  m.spec = spec;
  const std::size_t n = spec.cellCount();
  m.probability.assign(n, 0.5);
  m.native.assign(n, 0.0);
  m.level.assign(n, levelOfProbability(0.5));
  m.filled.assign(n, 0);
  m.observed.assign(n, 0);
  return m;
}

std::size_t OccupancyMap::filledCount() const {
  return static_cast<std::size_t>(std::count(filled.begin(), filled.end(), std::uint8_t{1}));
}

std::vector<std::size_t> OccupancyMap::levelHistogram() const {
  std::vector<std::size_t> h(kLevels, 0);
  for (std::uint8_t l : level) ++h[l < kLevels ? l : kLevels - 1];
  return h;
}

}  // namespace sg
