// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Differential-drive motion: paths made of constant-curvature pieces, driven at a speed and a turn
// rate (Trajectory), and the odometry such a robot computes from its two wheel encoders, with the
// systematic and random errors of Borenstein and Feng's UMBmark error model (OdometryErrors).

#include <cstdint>
#include <span>
#include <vector>

#include "sonargrid/data/pose.h"
#include "sonargrid/sim/ray_sonar.h"

namespace sg {

// A straight (curvature 0), an arc (curvature 1/radius, positive turning left), or a turn on the
// spot (length 0, `turn` radians, positive counter-clockwise).
struct PathPiece {
  double length = 0.0;     // metres
  double curvature = 0.0;  // 1/m
  double turn = 0.0;       // radians; only for a turn on the spot
};

// The pose after `fraction` (0..1) of `piece`, from `pose`: exact arc geometry.
Pose2D advanceAlong(const Pose2D& pose, const PathPiece& piece, double fraction);

// Body velocities v (m/s) and omega (rad/s) held for dt seconds: the robot moves on a circular arc
// of radius v / omega (a straight line when omega is 0).
Pose2D integrateUnicycle(const Pose2D& pose, double v, double omega, double dt);

struct DriveLimits {
  double speed = 0.3;                // m/s on straights and arcs
  double turnRate = degToRad(45.0);  // rad/s: turns on the spot, and the cap on arcs (v <= w r)
};

// A path driven from `start` piece by piece, at the limits' speed (slower on an arc tighter than
// speed / turnRate) and turn rate.
class Trajectory {
 public:
  Trajectory(const Pose2D& start, std::vector<PathPiece> pieces, const DriveLimits& limits);

  double duration() const { return times_.back(); }
  double length() const { return lengths_.back(); }
  const std::vector<PathPiece>& pieces() const { return pieces_; }
  const Pose2D& start() const { return starts_.front(); }
  Pose2D end() const { return starts_.back(); }

  // The pose at time t, clamped to [0, duration].
  Pose2D poseAt(double t) const;
  // The first time the robot has driven `s` metres (turns on the spot add time, not length).
  double timeAtDistance(double s) const;

 private:
  std::vector<PathPiece> pieces_;
  std::vector<Pose2D> starts_;   // starts_[k] begins piece k; the last one is the end of the path
  std::vector<double> times_;    // cumulative, times_[0] = 0
  std::vector<double> lengths_;  // cumulative
};

// UMBmark-style odometry errors (Borenstein & Feng 1996): each wheel's measured distance is off by
// a fixed scale factor, the wheelbase the odometry assumes is off by another, and each wheel adds
// zero-mean noise whose variance grows with the distance it rolls.
struct OdometryErrors {
  double leftScale = 0.0;  // measured = true * (1 + leftScale)
  double rightScale = 0.0;
  double wheelbaseScale = 0.0;  // the odometry's wheelbase = true wheelbase * (1 + wheelbaseScale)
  double wheelNoise = 0.0;      // m per sqrt(m): sd of a wheel's error over one metre rolled
};

// Dead reckoning from the wheel distances of a differential drive.
class Odometry {
 public:
  Odometry(const Pose2D& start, double wheelbase, const OdometryErrors& errors, std::uint64_t seed);

  // Folds in the true motion from `from` to `to`, a step short enough to be one circular arc.
  void step(const Pose2D& from, const Pose2D& to);
  const Pose2D& pose() const { return pose_; }

 private:
  Pose2D pose_;
  double wheelbase_;
  OdometryErrors errors_;
  SimRng rng_;
};

}  // namespace sg
