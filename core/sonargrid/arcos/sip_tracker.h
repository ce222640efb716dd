// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// SIPs to scans: the robot's odometry pose integrated from the 15-bit wrapping position counters,
// its heading, the sonar readings of each SIP, and the simulator's true pose of the SIMSTAT that
// came just before it (docs/live-robot.md, "From SIPs to scans").

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "sonargrid/arcos/messages.h"
#include "sonargrid/arcos/robot_params.h"
#include "sonargrid/data/dataset.h"

namespace sg::arcos {

// The signed difference of two 15-bit counters, taking the shorter way round the wrap.
int wrappedDelta15(std::uint16_t from, std::uint16_t to);
// A 15-bit counter read as a signed number (0x4000..0x7FFF are negative).
int signExtend15(std::uint16_t v);

class SipTracker {
 public:
  explicit SipTracker(RobotParameters robot);

  const RobotParameters& robot() const { return robot_; }

  // A new connection: the next SIP sets the pose afresh and a pending true pose is dropped.
  void reset();
  // The true pose of the next SIP.
  void setTruth(const SimStat& stat);
  // Folds in a SIP received at `time` (seconds) and returns its scan: the odometry pose after it,
  // the true pose of the SIMSTAT before it (if any), and one reading per sonar it carries, at
  // `time`. Readings of transducers the ring does not have are dropped and counted.
  Scan apply(const Sip& sip, double time);

  const Pose2D& odometry() const { return odometry_; }
  // The latest range of every transducer (metres, Reading::kNoEcho, or NaN before its first).
  std::span<const double> latestRanges() const { return latest_; }
  std::uint64_t droppedReadings() const { return dropped_; }

  // Robot units to SI.
  Pose2D truePose(const SimStat& stat) const;
  double rangeMetres(std::uint16_t range) const;

 private:
  RobotParameters robot_;
  bool started_ = false;
  std::uint16_t lastX_ = 0;
  std::uint16_t lastY_ = 0;
  double xMm_ = 0.0;
  double yMm_ = 0.0;
  Pose2D odometry_;
  std::optional<Pose2D> truth_;
  std::vector<double> latest_;
  std::uint64_t dropped_ = 0;
};

}  // namespace sg::arcos
