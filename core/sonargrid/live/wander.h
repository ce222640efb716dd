// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A simple sonar obstacle avoidance for recording runs (`sonargrid-cli record --wander`): drive
// forward, slower as the way ahead closes, steer toward the more open side, and turn on the spot
// (keeping one direction until the way is clear) when something is close ahead. It sees only the
// latest range of each transducer, grouped by mounting heading into front (within 30 degrees of
// forward), left and right (30 to 100 degrees) sectors. Sonar cones leave gaps, so a robot can
// still run into a corner none of them sees: when it is told to drive but its odometry has not
// moved for a while (its wheels stall), it backs off and turns away. Plain C++: no Qt.

#include <span>
#include <utility>

#include "sonargrid/data/pose.h"
#include "sonargrid/data/sonar_ring.h"

namespace sg::live {

struct WanderSettings {
  double cruiseSpeed = 0.3;     // m/s with a clear way ahead
  double slowSpeed = 0.1;       // m/s just before turning
  double stopDistance = 0.5;    // m ahead: turn on the spot
  double clearDistance = 0.8;   // m ahead: a turn on the spot ends
  double sideDistance = 0.3;    // m to the side: turn away on the spot
  double turnRate = 0.6;        // rad/s on the spot
  double steerGain = 0.4;       // rad/s per metre of difference between the sides
  double stuckAfter = 1.0;      // s told to drive without moving stuckDistance: stalled
  double stuckDistance = 0.02;  // m
  double backOff = 0.6;         // s backing at slowSpeed, then as long turning on the spot
};

class Wander {
 public:
  explicit Wander(SonarRing ring, WanderSettings settings = {});

  // Velocities (m/s, rad/s) from the latest range of each transducer (metres, infinity for no
  // echo, NaN for none yet) and the odometry at `time` (seconds). Until every front transducer
  // has reported, the robot stands.
  std::pair<double, double> command(std::span<const double> ranges, const Pose2D& odometry,
                                    double time);

 private:
  std::pair<double, double> avoid(std::span<const double> ranges);

  SonarRing ring_;
  WanderSettings settings_;
  int turning_ = 0;  // 0 not turning on the spot, +1 left, -1 right
  // Stall detection: where and when the robot was last seen making progress while driving.
  Position progressFrom_{0.0, 0.0};
  double progressTime_ = -1.0;
  double escapeUntil_ = -1.0;  // backing off and turning until then
  int escapeTurn_ = 1;
};

}  // namespace sg::live
