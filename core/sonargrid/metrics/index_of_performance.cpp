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

const char* iopWeightName(IopWeight w) {
  return w == IopWeight::Evidence ? "evidence" : "level";
}

bool parseIopWeight(const std::string& text, IopWeight& out) {
  if (text == "evidence") {
    out = IopWeight::Evidence;
  } else if (text == "level") {
    out = IopWeight::Level;
  } else {
    return false;
  }
  return true;
}

double iopCellWeight(const OccupancyMap& map, std::size_t i, IopWeight weight) {
  if (weight == IopWeight::Evidence && map.evidence.size() == map.level.size()) {
    const double e = map.evidence[i];
    return 15.0 * (e < 0.0 ? 0.0 : (e > 1.0 ? 1.0 : e));
  }
  return map.level[i];
}

IndexOfPerformance indexOfPerformance(const OccupancyMap& map, const ActualPositionGrid& apg,
                                      const IopOptions& options) {
  if (!(options.filledThreshold >= 0.0 && options.filledThreshold <= 15.0))
    throw std::invalid_argument("IOP: the filled threshold must be between 0 and 15");
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
    const double cv = iopCellWeight(map, i, options.weight);
    if (cv < options.filledThreshold) continue;
    ++out.filledCells;
    weighted += static_cast<double>(distance[i]) * cv;
    out.cvSum += cv;
  }
  if (out.cvSum > 0.0) out.mm = weighted / out.cvSum * map.spec.cellSize * 1000.0;
  return out;
}

}  // namespace sg
