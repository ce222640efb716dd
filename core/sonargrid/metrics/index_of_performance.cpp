// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/metrics/index_of_performance.h"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace sg {

std::vector<float> distanceToApg(const ActualPositionGrid& apg) {
  const GridSpec& spec = apg.spec;
  if (apg.cells.size() != spec.cellCount())
    throw std::invalid_argument("APG: layer size does not match its grid");
  if (apg.empty()) throw std::invalid_argument("APG: no reference edge crosses the grid");
  // distanceTransform measures the distance to the nearest zero pixel: APG cells are the zeros.
  cv::Mat source(spec.height, spec.width, CV_8UC1);
  for (int iy = 0; iy < spec.height; ++iy) {
    auto* row = source.ptr<std::uint8_t>(iy);
    for (int ix = 0; ix < spec.width; ++ix)
      row[ix] = apg.cells[spec.linear(CellIndex(ix, iy))] != 0 ? 0 : 255;
  }
  cv::Mat distance;
  cv::distanceTransform(source, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  std::vector<float> out(spec.cellCount());
  for (int iy = 0; iy < spec.height; ++iy) {
    const float* row = distance.ptr<float>(iy);
    for (int ix = 0; ix < spec.width; ++ix) out[spec.linear(CellIndex(ix, iy))] = row[ix];
  }
  return out;
}

IndexOfPerformance indexOfPerformance(const OccupancyMap& map, const ActualPositionGrid& apg) {
  if (!(map.spec == apg.spec))
    throw std::invalid_argument("IOP: the APG is not drawn on the map's grid");
  if (map.filled.size() != map.spec.cellCount() || map.level.size() != map.spec.cellCount()) {
    throw std::invalid_argument("IOP: the map's layers do not match its grid");
  }
  const std::vector<float> distance = distanceToApg(apg);
  IndexOfPerformance out;
  double weighted = 0.0;
  for (std::size_t i = 0; i < distance.size(); ++i) {
    if (map.filled[i] == 0) continue;
    ++out.filledCells;
    const double cv = map.level[i];
    weighted += static_cast<double>(distance[i]) * cv;
    out.cvSum += cv;
  }
  if (out.cvSum > 0.0) out.mm = weighted / out.cvSum * map.spec.cellSize * 1000.0;
  return out;
}

}  // namespace sg
