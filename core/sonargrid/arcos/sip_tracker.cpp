// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/arcos/sip_tracker.h"

#include <limits>

namespace sg::arcos {

int wrappedDelta15(std::uint16_t from, std::uint16_t to) {
  const int d = (static_cast<int>(to) - static_cast<int>(from)) & 0x7FFF;
  return d >= 0x4000 ? d - 0x8000 : d;
}

int signExtend15(std::uint16_t v) {
  const int x = v & 0x7FFF;
  return x >= 0x4000 ? x - 0x8000 : x;
}

SipTracker::SipTracker(RobotParameters robot) : robot_(std::move(robot)) {
  reset();
}

void SipTracker::reset() {
  started_ = false;
  truth_.reset();
  latest_.assign(robot_.ring.size(), std::numeric_limits<double>::quiet_NaN());
}

void SipTracker::setTruth(const SimStat& stat) {
  truth_ = truePose(stat);
}

Pose2D SipTracker::truePose(const SimStat& stat) const {
  return Pose2D(stat.trueX / 1000.0, stat.trueY / 1000.0,
                wrapAngle(degToRad(static_cast<double>(stat.trueThetaDeg))));
}

double SipTracker::rangeMetres(std::uint16_t range) const {
  const double mm = range * robot_.rangeConvFactor;
  return mm >= robot_.maxRangeMm ? Reading::kNoEcho : mm / 1000.0;
}

Scan SipTracker::apply(const Sip& sip, double time) {
  if (!started_) {
    // The counters wrap every 0x8000 units (15.9 m on a Pioneer 3-DX): the first SIP is read as a
    // signed position, which is exact within half of that of the robot's origin; every later one
    // adds the wrapped change, so the pose is right however far the robot then drives.
    xMm_ = signExtend15(sip.xpos) * robot_.distConvFactor;
    yMm_ = signExtend15(sip.ypos) * robot_.distConvFactor;
    started_ = true;
  } else {
    xMm_ += wrappedDelta15(lastX_, sip.xpos) * robot_.distConvFactor;
    yMm_ += wrappedDelta15(lastY_, sip.ypos) * robot_.distConvFactor;
  }
  lastX_ = sip.xpos;
  lastY_ = sip.ypos;
  odometry_ = Pose2D(xMm_ / 1000.0, yMm_ / 1000.0, wrapAngle(sip.thpos * robot_.angleConvFactor));

  Scan scan;
  scan.time = time;
  scan.odometry = odometry_;
  scan.truth = truth_;
  truth_.reset();
  scan.readings.reserve(sip.sonars.size());
  for (const SonarEcho& e : sip.sonars) {
    if (e.number >= robot_.ring.size()) {
      ++dropped_;
      continue;
    }
    Reading r;
    r.sonar = e.number;
    r.range = rangeMetres(e.range);
    r.time = time;
    latest_[e.number] = r.range;
    scan.readings.push_back(r);
  }
  return scan;
}

}  // namespace sg::arcos
