#include "sonargrid/dataset.h"

#include <algorithm>

namespace sg {

std::size_t Dataset::readingCount() const {
  std::size_t n = 0;
  for (const Scan& s : scans) n += s.readings.size();
  return n;
}

bool Dataset::hasTruth() const {
  return !scans.empty() && std::all_of(scans.begin(), scans.end(), [](const Scan& s) { return s.truth.has_value(); });
}

GridSpec Dataset::fittingGrid(PoseSource source, double cellSize, double margin) const {
  if (scans.empty()) return GridSpec::covering(Position(0, 0), Position(0, 0), cellSize, margin);
  Position lo = pose(scans.front(), source).position;
  Position hi = lo;
  for (const Scan& s : scans) {
    const Position& p = pose(s, source).position;
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  double reach = 0.0;
  for (const SonarMount& m : ring.sonars) reach = std::max(reach, m.pose.position.norm());
  return GridSpec::covering(lo, hi, cellSize, reach + ring.maxRange + margin);
}

}  // namespace sg
