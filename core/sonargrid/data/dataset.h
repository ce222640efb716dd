// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A sonar log in memory: the ring that took it and time-ordered scans, each with an odometry pose,
// an optional true pose and the readings taken at that pose.

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "sonargrid/data/pose.h"
#include "sonargrid/data/sonar_ring.h"
#include "sonargrid/engine/grid_spec.h"

namespace sg {

// A reading with no echo (the transducer heard nothing before its maximum range) carries an
// infinite range: it is never an obstacle, and each model says what free space it implies.
struct Reading {
  static constexpr double kNoEcho = std::numeric_limits<double>::infinity();

  std::uint16_t sonar = 0;  // index into the ring
  double range = 0.0;       // metres, or kNoEcho
  double time = 0.0;        // seconds

  bool echo() const { return std::isfinite(range); }
  bool operator==(const Reading&) const = default;
};

struct Scan {
  double time = 0.0;  // seconds; the time of the poses
  Pose2D odometry;
  std::optional<Pose2D> truth;
  std::vector<Reading> readings;

  bool operator==(const Scan&) const = default;
};

enum class PoseSource { Odometry, Truth };

struct Dataset {
  std::string name;  // free text from the log header
  SonarRing ring;
  std::vector<Scan> scans;

  std::size_t readingCount() const;
  bool hasTruth() const;  // every scan carries a true pose
  const Pose2D& pose(const Scan& s, PoseSource source) const {
    return source == PoseSource::Truth && s.truth ? *s.truth : s.odometry;
  }
  // The grid of `cellSize` that holds every robot and sonar position and every echo (the points at
  // the reading's range on the acoustic axis and on both cone edges), grown by `margin` metres.
  // A log without a single echo gets the positions grown by the maximum range.
  // Throws GridLimitError when that grid cannot be made: a position that is not finite, or more
  // cells than kMaxGridCells. Its message names the scan (index and time) that reaches farthest
  // from the middle of the robot's path, that point, the extent and the limit; the caller adds the
  // file name (GridLimitError::inFile).
  GridSpec fittingGrid(PoseSource source, double cellSize, double margin = 0.5) const;

  bool operator==(const Dataset&) const = default;
};

}  // namespace sg
