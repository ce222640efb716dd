// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/sim/differential_drive.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace sg {

Pose2D advanceAlong(const Pose2D& pose, const PathPiece& piece, double fraction) {
  if (piece.length == 0.0) return {pose.x(), pose.y(), pose.heading + fraction * piece.turn};
  const double d = fraction * piece.length;
  const double h0 = pose.heading;
  if (piece.curvature == 0.0) return {pose.x() + d * std::cos(h0), pose.y() + d * std::sin(h0), h0};
  const double r = 1.0 / piece.curvature;
  const double h1 = h0 + d * piece.curvature;
  return {pose.x() + r * (std::sin(h1) - std::sin(h0)),
          pose.y() + r * (std::cos(h0) - std::cos(h1)), h1};
}

Pose2D integrateUnicycle(const Pose2D& pose, double v, double omega, double dt) {
  const double h0 = pose.heading;
  const double h1 = h0 + omega * dt;
  if (omega == 0.0) return {pose.x() + v * dt * std::cos(h0), pose.y() + v * dt * std::sin(h0), h0};
  const double r = v / omega;
  return {pose.x() + r * (std::sin(h1) - std::sin(h0)),
          pose.y() + r * (std::cos(h0) - std::cos(h1)), h1};
}

Trajectory::Trajectory(const Pose2D& start, std::vector<PathPiece> pieces,
                       const DriveLimits& limits)
    : pieces_(std::move(pieces)) {
  if (!(limits.speed > 0.0) || !(limits.turnRate > 0.0))
    throw std::invalid_argument("Trajectory: speed and turn rate must be above 0");
  starts_.push_back(start);
  times_.push_back(0.0);
  lengths_.push_back(0.0);
  for (const PathPiece& p : pieces_) {
    double seconds = 0.0;
    if (p.length == 0.0) {
      seconds = std::abs(p.turn) / limits.turnRate;
    } else {
      const double v = p.curvature == 0.0
                           ? limits.speed
                           : std::min(limits.speed, limits.turnRate / std::abs(p.curvature));
      seconds = p.length / v;
    }
    starts_.push_back(advanceAlong(starts_.back(), p, 1.0));
    times_.push_back(times_.back() + seconds);
    lengths_.push_back(lengths_.back() + p.length);
  }
}

Pose2D Trajectory::poseAt(double t) const {
  if (pieces_.empty() || t <= 0.0) return starts_.front();
  if (t >= duration()) return starts_.back();
  // The piece k with times_[k] <= t < times_[k + 1].
  const auto it = std::upper_bound(times_.begin(), times_.end(), t);
  const std::size_t k = static_cast<std::size_t>(it - times_.begin()) - 1;
  const double span = times_[k + 1] - times_[k];
  return advanceAlong(starts_[k], pieces_[k], span > 0.0 ? (t - times_[k]) / span : 1.0);
}

double Trajectory::timeAtDistance(double s) const {
  if (s <= 0.0) return 0.0;
  for (std::size_t k = 0; k < pieces_.size(); ++k) {
    if (pieces_[k].length > 0.0 && lengths_[k + 1] >= s) {
      return times_[k] + (times_[k + 1] - times_[k]) * (s - lengths_[k]) / pieces_[k].length;
    }
  }
  return duration();
}

Odometry::Odometry(const Pose2D& start, double wheelbase, const OdometryErrors& errors,
                   std::uint64_t seed)
    : pose_(start), wheelbase_(wheelbase), errors_(errors), rng_(seed) {
  if (!(wheelbase > 0.0)) throw std::invalid_argument("Odometry: wheelbase must be above 0");
}

void Odometry::step(const Pose2D& from, const Pose2D& to) {
  // The true step as a circular arc: turned angle and signed arc length from the chord.
  const double dTheta = wrapAngle(to.heading - from.heading);
  const Position chord = to.position - from.position;
  const double chordLength = chord.norm();
  const double half = 0.5 * dTheta;
  double ds = std::abs(half) < 1e-12 ? chordLength : chordLength * half / std::sin(half);
  const Position ahead(std::cos(from.heading + half), std::sin(from.heading + half));
  if (chord.dot(ahead) < 0.0) ds = -ds;
  // What each wheel rolled, and what its encoder made of it.
  const double left = ds - 0.5 * wheelbase_ * dTheta;
  const double right = ds + 0.5 * wheelbase_ * dTheta;
  double measuredLeft = left * (1.0 + errors_.leftScale);
  double measuredRight = right * (1.0 + errors_.rightScale);
  if (errors_.wheelNoise > 0.0) {
    measuredLeft += errors_.wheelNoise * std::sqrt(std::abs(left)) * standardNormal(rng_);
    measuredRight += errors_.wheelNoise * std::sqrt(std::abs(right)) * standardNormal(rng_);
  }
  const double odoDs = 0.5 * (measuredLeft + measuredRight);
  const double odoTheta =
      (measuredRight - measuredLeft) / (wheelbase_ * (1.0 + errors_.wheelbaseScale));
  // Dead reckoning on the arc the encoders describe.
  const double h0 = pose_.heading;
  if (std::abs(odoTheta) < 1e-12) {
    pose_ =
        Pose2D(pose_.x() + odoDs * std::cos(h0), pose_.y() + odoDs * std::sin(h0), wrapAngle(h0));
  } else {
    const double r = odoDs / odoTheta;
    const double h1 = h0 + odoTheta;
    pose_ = Pose2D(pose_.x() + r * (std::sin(h1) - std::sin(h0)),
                   pose_.y() + r * (std::cos(h0) - std::cos(h1)), wrapAngle(h1));
  }
}

}  // namespace sg
