// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/io/start_pose.h"

#include <cmath>
#include <numbers>
#include <vector>

#include "sonargrid/io/text_lines.h"

namespace sg {

void placeOdometryAt(Dataset& log, const Pose2D& start) {
  if (log.scans.empty()) return;
  const Pose2D first = log.scans.front().odometry;
  const double turn = start.heading - first.heading;
  const Eigen::Matrix2d rotation = Eigen::Rotation2Dd(turn).toRotationMatrix();
  for (Scan& s : log.scans) {
    Pose2D& p = s.odometry;
    p.position = start.position + rotation * (p.position - first.position);
    // Wrapped only when it leaves [-pi, pi): wrapAngle's fmod would move the last bit of a heading
    // that needs none, and a start pose equal to the first odometry must change nothing.
    const double h = p.heading + turn;
    p.heading = h >= -std::numbers::pi && h < std::numbers::pi ? h : wrapAngle(h);
  }
}

std::optional<Pose2D> parseStartPose(std::string_view text, std::string* error) {
  const auto fail = [&](const std::string& why) -> std::optional<Pose2D> {
    if (error != nullptr) *error = why;
    return std::nullopt;
  };
  std::vector<std::string_view> parts;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = text.find(',', start);
    parts.push_back(text.substr(start, comma == std::string_view::npos ? comma : comma - start));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  if (parts.size() != 3)
    return fail("expected X,Y,THETA (metres, metres, degrees), found '" + std::string(text) + "'");
  double v[3] = {0.0, 0.0, 0.0};
  const char* names[3] = {"X", "Y", "THETA"};
  for (std::size_t i = 0; i < 3; ++i) {
    if (!text::parseFinite(parts[i], v[i]))
      return fail("expected a number for " + std::string(names[i]) + " in X,Y,THETA, found '" +
                  std::string(parts[i]) + "'");
  }
  if (std::abs(v[2]) > 360.0)
    return fail("expected THETA in degrees between -360 and 360, found '" + std::string(parts[2]) +
                "'");
  return Pose2D(v[0], v[1], wrapAngle(degToRad(v[2])));
}

std::string formatStartPose(const Pose2D& pose) {
  return text::number(pose.x()) + "," + text::number(pose.y()) + "," +
         text::number(radToDeg(pose.heading));
}

}  // namespace sg
