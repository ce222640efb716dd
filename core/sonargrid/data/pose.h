// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A planar pose (x, y, heading) in the world frame: metres and radians, counter-clockwise angles,
// x forward on the robot (docs/models.md, conventions).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

namespace sg {

using Position = Eigen::Vector2d;

// Wraps an angle to [-pi, pi).
inline double wrapAngle(double a) {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  a = std::fmod(a + std::numbers::pi, kTwoPi);
  if (a < 0.0) a += kTwoPi;
  return a - std::numbers::pi;
}

inline double degToRad(double deg) {
  return deg * std::numbers::pi / 180.0;
}
inline double radToDeg(double rad) {
  return rad * 180.0 / std::numbers::pi;
}

struct Pose2D {
  Position position{0.0, 0.0};
  double heading = 0.0;  // radians

  Pose2D() = default;
  Pose2D(double x, double y, double theta) : position(x, y), heading(theta) {}

  double x() const { return position.x(); }
  double y() const { return position.y(); }

  // This pose composed with a pose expressed in its own frame (e.g. robot pose * sonar mounting).
  Pose2D compose(const Pose2D& local) const { return compose(local, rotation()); }
  // The same, given rotation() computed once for many local poses (a robot's sonars): a sine and
  // a cosine for them all.
  Pose2D compose(const Pose2D& local, const Eigen::Matrix2d& rotation) const {
    Pose2D out;
    out.position = position + rotation * local.position;
    out.heading = wrapAngle(heading + local.heading);
    return out;
  }
  // The heading's rotation matrix (Eigen's Rotation2D * v is toRotationMatrix() * v).
  Eigen::Matrix2d rotation() const { return Eigen::Rotation2Dd(heading).toRotationMatrix(); }

  // A point given in this pose's frame, expressed in the world frame.
  Position transform(const Position& local) const {
    return position + Eigen::Rotation2Dd(heading) * local;
  }

  bool operator==(const Pose2D& o) const { return position == o.position && heading == o.heading; }
};

// a⁻¹ ∘ b: pose b expressed in the frame of pose a (so a.compose(relativePose(a, b)) is b).
inline Pose2D relativePose(const Pose2D& a, const Pose2D& b) {
  Pose2D r;
  r.position = Eigen::Rotation2Dd(-a.heading).toRotationMatrix() * (b.position - a.position);
  r.heading = wrapAngle(b.heading - a.heading);
  return r;
}

}  // namespace sg
