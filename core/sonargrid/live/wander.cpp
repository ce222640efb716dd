// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/live/wander.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sg::live {

Wander::Wander(SonarRing ring, WanderSettings settings)
    : ring_(std::move(ring)), settings_(settings) {}

std::pair<double, double> Wander::command(std::span<const double> ranges, const Pose2D& odometry,
                                          double time) {
  if (time < escapeUntil_) {
    const bool backing = time < escapeUntil_ - settings_.backOff;
    return backing ? std::pair{-settings_.slowSpeed, 0.0}
                   : std::pair{0.0, escapeTurn_ * settings_.turnRate};
  }
  const std::pair<double, double> c = avoid(ranges);
  if (c.first <= 0.0 || progressTime_ < 0.0 ||
      (odometry.position - progressFrom_).norm() >= settings_.stuckDistance) {
    progressFrom_ = odometry.position;
    progressTime_ = time;
    return c;
  }
  if (time - progressTime_ < settings_.stuckAfter) return c;
  // Told to drive, not moving: back off, then turn away from the nearer side.
  escapeTurn_ = c.second >= 0.0 ? 1 : -1;
  escapeUntil_ = time + 2.0 * settings_.backOff;
  progressTime_ = -1.0;
  turning_ = 0;
  return {-settings_.slowSpeed, 0.0};
}

std::pair<double, double> Wander::avoid(std::span<const double> ranges) {
  const double far = ring_.maxRange;
  double front = far;
  double left = far;
  double right = far;
  bool frontKnown = false;
  const std::size_t n = std::min(ranges.size(), ring_.size());
  for (std::size_t i = 0; i < n; ++i) {
    const double heading = radToDeg(wrapAngle(ring_.sonars[i].pose.heading));
    const bool isFront = std::abs(heading) <= 30.0;
    if (std::isnan(ranges[i])) {
      if (isFront) return {0.0, 0.0};
      continue;
    }
    const double r = std::min(ranges[i], far);
    if (isFront) {
      front = std::min(front, r);
      frontKnown = true;
    } else if (heading > 30.0 && heading <= 100.0) {
      left = std::min(left, r);
    } else if (heading < -30.0 && heading >= -100.0) {
      right = std::min(right, r);
    }
  }
  if (!frontKnown) return {0.0, 0.0};

  if (turning_ != 0) {
    if (front > settings_.clearDistance && std::min(left, right) > settings_.sideDistance) {
      turning_ = 0;
    } else {
      return {0.0, turning_ * settings_.turnRate};
    }
  }
  if (front < settings_.stopDistance || std::min(left, right) < settings_.sideDistance) {
    turning_ = left >= right ? 1 : -1;
    return {0.0, turning_ * settings_.turnRate};
  }
  const double span = std::max(settings_.clearDistance * 2.0 - settings_.stopDistance, 1e-6);
  const double t = std::clamp((front - settings_.stopDistance) / span, 0.0, 1.0);
  const double speed = settings_.slowSpeed + t * (settings_.cruiseSpeed - settings_.slowSpeed);
  const double steer = settings_.steerGain * (std::min(left, 2.0) - std::min(right, 2.0));
  return {speed, std::clamp(steer, -settings_.turnRate, settings_.turnRate)};
}

}  // namespace sg::live
