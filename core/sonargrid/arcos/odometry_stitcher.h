// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Odometry across reconnects (docs/live-robot.md, "Reconnects"). A controller restarts its
// odometry at 0 when a client connects (AMRISim does so for every session, a real Pioneer when it
// is switched back on), so the scans of a second connection would jump back to the origin. Each
// connection's scans are a segment; a segment whose odometry does not continue the previous one
// is stitched onto it: moved rigidly so that it goes on from the previous segment's last pose, by
// what the simulator's true poses say the robot drove while the link was down, else as if the
// robot stood still (a robot without its client stops): a controller restarts its odometry at 0
// where the robot stands, so that origin goes to the last pose. The log has no jump.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "sonargrid/data/dataset.h"

namespace sg::arcos {

class OdometryStitcher {
 public:
  // A new connection began: the scans that follow are a new segment.
  void newSegment();
  // Takes a scan as the connection delivered it and appends to `out` the scans ready, their
  // odometry in the first segment's frame. `truthExpected`: the robot is a simulator that sends
  // true poses; then the first scans of a stitched segment wait (at most kMaxHeld of them) for
  // one, which tells how far the robot moved while the link was down.
  void add(Scan scan, bool truthExpected, std::vector<Scan>& out);
  // The connection ended: the scans still waiting are stitched as if the robot had not moved.
  void flush(std::vector<Scan>& out);

  // Segments that delivered a scan, and those of them whose odometry was stitched.
  std::uint64_t segments() const { return segments_; }
  std::uint64_t stitched() const { return stitched_; }

  // Scans a stitched segment waits for a true pose at most (a simulator's first SIP may come
  // before its first SIMSTAT).
  static constexpr std::size_t kMaxHeld = 10;
  // A new segment whose first odometry is within this of the previous segment's last (or moved
  // as the true poses moved) continues it: the controller kept its odometry.
  // Also the smallest move of the true poses taken as one (they come in whole mm and degrees).
  static constexpr double kSamePlaceM = 0.05;
  static constexpr double kSameHeadingRad = 0.05;
  // A restarted odometry this near (0, 0, 0) at the segment's first scan restarted where the robot
  // stood when the link went down: its origin is placed there.
  static constexpr double kRestartNearM = 0.25;
  static constexpr double kRestartNearRad = 0.25;

 private:
  // Decides the segment's frame from its scan `k` (held_[k]) and emits the held scans.
  void settle(std::size_t k, std::vector<Scan>& out);
  void release(Scan scan, std::vector<Scan>& out);

  std::uint64_t segments_ = 0;
  std::uint64_t stitched_ = 0;
  bool fresh_ = true;             // no scan of the current segment emitted or held yet
  bool settled_ = true;           // the current segment's frame is decided
  std::optional<Pose2D> offset_;  // placed = offset * delivered; none: as delivered
  // The last scan emitted: its odometry as delivered and as placed, and its true pose.
  std::optional<Pose2D> lastDelivered_;
  std::optional<Pose2D> lastPlaced_;
  std::optional<Pose2D> lastTruth_;
  std::vector<Scan> held_;
};

}  // namespace sg::arcos
