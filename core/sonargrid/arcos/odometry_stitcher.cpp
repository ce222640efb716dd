// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/arcos/odometry_stitcher.h"

#include <cmath>
#include <utility>

namespace sg::arcos {

namespace {

bool samePose(const Pose2D& a, const Pose2D& b) {
  return (a.position - b.position).norm() <= OdometryStitcher::kSamePlaceM &&
         std::abs(wrapAngle(a.heading - b.heading)) <= OdometryStitcher::kSameHeadingRad;
}

}  // namespace

void OdometryStitcher::newSegment() {
  fresh_ = true;
  settled_ = true;
}

void OdometryStitcher::add(Scan scan, bool truthExpected, std::vector<Scan>& out) {
  if (fresh_) {
    fresh_ = false;
    ++segments_;
    // The first segment is the log's frame; a later one must be placed.
    settled_ = !lastPlaced_.has_value();
  }
  if (settled_) {
    release(std::move(scan), out);
    return;
  }
  held_.push_back(std::move(scan));
  const bool canMeasure = truthExpected && lastTruth_.has_value();
  if (held_.back().truth && canMeasure) {
    settle(held_.size() - 1, out);
  } else if (!canMeasure || held_.size() >= kMaxHeld) {
    settle(0, out);
  }
}

void OdometryStitcher::flush(std::vector<Scan>& out) {
  if (!held_.empty()) settle(0, out);
}

void OdometryStitcher::settle(std::size_t k, std::vector<Scan>& out) {
  const Scan& s = held_[k];
  // What the true poses say the robot drove from the last scan to scan k (nothing without them).
  const bool measured = s.truth && lastTruth_;
  const Pose2D moved = measured ? relativePose(*lastTruth_, *s.truth) : Pose2D();
  // The odometry moved as the robot did: the controller kept it, and the segment continues.
  if (!samePose(relativePose(*lastDelivered_, s.odometry), moved)) {
    ++stitched_;
    if (measured && !samePose(moved, Pose2D())) {
      // The robot drove on while the link was down: scan k is where the true poses put it.
      offset_ = lastPlaced_->compose(moved).compose(relativePose(s.odometry, Pose2D()));
    } else {
      // It stood still (true poses come in whole millimetres and degrees: a move below their
      // resolution is no move). The controller restarted its odometry at 0 where the robot stood,
      // the last pose; odometry that restarted elsewhere starts at the last pose.
      const Pose2D& first = held_.front().odometry;
      const bool fromZero =
          first.position.norm() <= kRestartNearM && std::abs(first.heading) <= kRestartNearRad;
      offset_ = fromZero ? *lastPlaced_ : lastPlaced_->compose(relativePose(first, Pose2D()));
    }
  }
  settled_ = true;
  std::vector<Scan> held = std::exchange(held_, {});
  for (Scan& h : held) release(std::move(h), out);
}

void OdometryStitcher::release(Scan scan, std::vector<Scan>& out) {
  lastDelivered_ = scan.odometry;
  if (offset_) scan.odometry = offset_->compose(scan.odometry);
  lastPlaced_ = scan.odometry;
  lastTruth_ = scan.truth;
  out.push_back(std::move(scan));
}

}  // namespace sg::arcos
