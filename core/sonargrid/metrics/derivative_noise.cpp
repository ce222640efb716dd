// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/metrics/derivative_noise.h"

#include <cmath>
#include <stdexcept>

namespace sg {

DerivativeNoise derivativeNoise(const OccupancyMap& map) {
  const GridSpec& spec = map.spec;
  if (map.probability.size() != spec.cellCount() || map.observed.size() != spec.cellCount()) {
    throw std::invalid_argument("derivative noise: the map's layers do not match its grid");
  }
  DerivativeNoise out;
  const auto w = static_cast<std::size_t>(spec.width);
  for (int y = 1; y + 1 < spec.height; ++y) {
    for (int x = 1; x + 1 < spec.width; ++x) {
      const std::size_t centre = static_cast<std::size_t>(y) * w + static_cast<std::size_t>(x);
      bool complete = true;
      double s = 0.0;
      for (int dy = -1; dy <= 1 && complete; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const std::size_t i =
              static_cast<std::size_t>(y + dy) * w + static_cast<std::size_t>(x + dx);
          if (map.observed[i] == 0) {
            complete = false;
            break;
          }
          s += std::abs(map.probability[i] - map.probability[centre]);
        }
      }
      if (!complete) continue;
      out.sum += s / 8.0;  // m·n − 1 = 8
      ++out.cellsScored;
    }
  }
  if (out.cellsScored > 0) out.mean = out.sum / static_cast<double>(out.cellsScored);
  return out;
}

}  // namespace sg
