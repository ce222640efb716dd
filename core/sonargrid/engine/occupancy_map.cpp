// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/engine/occupancy_map.h"

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

void OccupancyMap::derive(const std::shared_ptr<const DerivedCells>& cells) {
  if (!cells) {  // the layers let go of the cells they read, empty
    probability.clear();
    native.clear();
    evidence.clear();
    filled.clear();
    return;
  }
  const std::size_t n = spec.cellCount();
  probability = MapLayer<double>(cells, DerivedLayer::Probability, n);
  native = MapLayer<double>(cells, DerivedLayer::Native, n);
  evidence = MapLayer<double>(cells, DerivedLayer::Evidence, n);
  filled = MapLayer<std::uint8_t>(cells, DerivedLayer::Filled, n);
}

bool OccupancyMap::derived() const {
  return probability.derived() || native.derived() || evidence.derived() || filled.derived();
}

void OccupancyMap::hold() {
  if (probability.derived()) probability = probability.values();
  if (native.derived()) native = native.values();
  if (evidence.derived()) evidence = evidence.values();
  if (filled.derived()) filled = filled.values();
}

std::size_t OccupancyMap::bytesPerCell() const {
  const std::size_t n = spec.cellCount();
  if (n == 0) return 0;
  std::size_t bytes = (level.size() + observed.size()) * sizeof(std::uint8_t);
  if (!probability.derived()) bytes += probability.size() * sizeof(double);
  if (!native.derived()) bytes += native.size() * sizeof(double);
  if (!evidence.derived()) bytes += evidence.size() * sizeof(double);
  if (!filled.derived()) bytes += filled.size() * sizeof(std::uint8_t);
  return (bytes + n - 1) / n;
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
