// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/data/dataset.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "sonargrid/data/scan_poses.h"

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

namespace {

// Every point of a scan that its grid must hold: the robot, each sonar that read, and each echo at
// its range on the acoustic axis and on both cone edges. One definition for sizing the grid and for
// naming the scan that makes it too large.
// A scan without the pose asked for is left out when others have it (scan_poses.h: the mapper
// leaves it out too); a log without any true pose is sized by its odometry.
template <typename Visit>
void forEachPoint(const Dataset& d, const Scan& s, PoseSource source, bool leaveOut, Visit&& visit,
                  bool& anyEcho) {
  if (leaveOut && !hasPose(s, source)) return;
  const Pose2D& robot = d.pose(s, source);
  for (const Reading& r : s.readings) {
    if (r.sonar >= d.ring.size()) continue;  // the mapper reports it
    const Pose2D sensor = robot.compose(d.ring.sonars[r.sonar].pose);
    visit(sensor.position);
    if (r.echo() && r.range < d.ring.maxRange) {
      for (const double a : {0.0, -d.ring.apertureRad / 2, d.ring.apertureRad / 2})
        visit(sensor.transform(Position(r.range * std::cos(a), r.range * std::sin(a))));
      anyEcho = true;
    }
  }
  visit(robot.position);
}

std::string number(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

std::string scanName(const Dataset& d, std::size_t i) {
  return "scan " + std::to_string(i) + " (t = " + number(d.scans[i].time) + " s)";
}

// The middle of the robot's positions, robust to the few far ones that make a grid too large.
Position medianPosition(const Dataset& d, PoseSource source) {
  std::vector<double> xs;
  std::vector<double> ys;
  xs.reserve(d.scans.size());
  ys.reserve(d.scans.size());
  const bool leaveOut = anyScanHasPose(d, source);
  for (const Scan& s : d.scans) {
    if (leaveOut && !hasPose(s, source)) continue;
    xs.push_back(d.pose(s, source).position.x());
    ys.push_back(d.pose(s, source).position.y());
  }
  const auto mid = static_cast<std::ptrdiff_t>(xs.size() / 2);
  std::nth_element(xs.begin(), xs.begin() + mid, xs.end());
  std::nth_element(ys.begin(), ys.begin() + mid, ys.end());
  return {xs[static_cast<std::size_t>(mid)], ys[static_cast<std::size_t>(mid)]};
}

}  // namespace

GridSpec Dataset::fittingGrid(PoseSource source, double cellSize, double margin) const {
  if (scans.empty()) return GridSpec::covering(Position(0, 0), Position(0, 0), cellSize, margin);
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Position lo(kInf, kInf), hi(-kInf, -kInf);
  bool anyEcho = false;
  bool finite = true;
  const bool leaveOut = anyScanHasPose(*this, source);
  for (const Scan& s : scans)
    forEachPoint(
        *this, s, source, leaveOut,
        [&](const Position& p) {
          finite = finite && p.allFinite();
          lo = lo.cwiseMin(p);
          hi = hi.cwiseMax(p);
        },
        anyEcho);
  const double grow = anyEcho ? margin : ring.maxRange + margin;
  if (finite) {
    try {
      return GridSpec::covering(lo, hi, cellSize, grow);
    } catch (const GridLimitError& e) {
      if (!std::isfinite(cellSize) || cellSize <= 0.0 || !std::isfinite(margin)) throw;
      // Only the positions and echoes fit: the log has no echo, and max_range makes it too large.
      bool fitsWithoutMargin = !anyEcho;
      if (fitsWithoutMargin) {
        try {
          (void)GridSpec::covering(lo, hi, cellSize, 0.0);
        } catch (const GridLimitError&) {
          fitsWithoutMargin = false;
        }
      }
      if (fitsWithoutMargin)
        throw GridLimitError("no reading has an echo, so the grid reaches max_range " +
                             number(ring.maxRange) + " m beyond every sonar: " + e.message());
      // The scan that reaches farthest from the middle of the robot's path is the one to check
      // (one corrupt pose among good ones), or, for a log that is simply too large at this cell
      // size, the far end of it.
      const Position middle = medianPosition(*this, source);
      std::size_t worst = 0;
      Position worstPoint = middle;
      double worstDistance = -1.0;
      bool unused = false;
      for (std::size_t i = 0; i < scans.size(); ++i)
        forEachPoint(
            *this, scans[i], source, leaveOut,
            [&](const Position& p) {
              const double d = (p - middle).cwiseAbs().maxCoeff();
              if (d > worstDistance) {
                worstDistance = d;
                worst = i;
                worstPoint = p;
              }
            },
            unused);
      throw GridLimitError(scanName(*this, worst) + " reaches (" + number(worstPoint.x()) + ", " +
                           number(worstPoint.y()) + ") m: " + e.message());
    }
  }
  // A pose or echo that is not finite (a Dataset built in memory; the readers refuse them).
  for (std::size_t i = 0; i < scans.size(); ++i) {
    std::optional<Position> bad;
    bool unused = false;
    forEachPoint(
        *this, scans[i], source, leaveOut,
        [&](const Position& p) {
          if (!bad && !p.allFinite()) bad = p;
        },
        unused);
    if (bad)
      throw GridLimitError(scanName(*this, i) + " has a position that is not finite: (" +
                           number(bad->x()) + ", " + number(bad->y()) + ") m");
  }
  return GridSpec::covering(lo, hi, cellSize, grow);  // not reached: some point was not finite
}

}  // namespace sg
