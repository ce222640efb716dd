#include "sonargrid/dataset.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sg {

std::size_t Dataset::readingCount() const {
  std::size_t n = 0;
  for (const Scan& s : scans) n += s.readings.size();
  return n;
}

bool Dataset::hasTruth() const {
  return !scans.empty() &&
         std::all_of(scans.begin(), scans.end(), [](const Scan& s) { return s.truth.has_value(); });
}

GridSpec Dataset::fittingGrid(PoseSource source, double cellSize, double margin) const {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Position lo(kInf, kInf), hi(-kInf, -kInf);
  bool anyEcho = false;
  for (const Scan& s : scans) {
    const Pose2D& robot = pose(s, source);
    for (const Reading& r : s.readings) {
      if (r.sonar >= ring.size()) continue;  // the mapper reports it
      const Pose2D sensor = robot.compose(ring.sonars[r.sonar].pose);
      lo = lo.cwiseMin(sensor.position);
      hi = hi.cwiseMax(sensor.position);
      if (r.echo() && r.range < ring.maxRange) {
        for (const double a : {0.0, -ring.apertureRad / 2, ring.apertureRad / 2}) {
          const Position end =
              sensor.transform(Position(r.range * std::cos(a), r.range * std::sin(a)));
          lo = lo.cwiseMin(end);
          hi = hi.cwiseMax(end);
        }
        anyEcho = true;
      }
    }
    lo = lo.cwiseMin(robot.position);
    hi = hi.cwiseMax(robot.position);
  }
  if (scans.empty()) return GridSpec::covering(Position(0, 0), Position(0, 0), cellSize, margin);
  return GridSpec::covering(lo, hi, cellSize, anyEcho ? margin : ring.maxRange + margin);
}

}  // namespace sg
