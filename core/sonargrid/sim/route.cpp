// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/sim/route.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <stdexcept>

#include "sonargrid/base/file_text.h"
#include "sonargrid/base/log_error.h"

namespace sg {
namespace {

double headingOf(const Position& v) {
  return std::atan2(v.y(), v.x());
}

double distanceToSegment(const Position& p, const Segment& s) {
  const Position edge = s.b - s.a;
  const double l2 = edge.squaredNorm();
  const double u = l2 > 0.0 ? std::clamp((p - s.a).dot(edge) / l2, 0.0, 1.0) : 0.0;
  return (s.a + u * edge - p).norm();
}

double distanceToWorld(const Position& p, const SonarWorld& world) {
  double best = std::numeric_limits<double>::infinity();
  for (const Segment& s : world.segments) best = std::min(best, distanceToSegment(p, s));
  for (const Circle& c : world.circles)
    best = std::min(best, std::abs((p - c.centre).norm() - c.radius));
  return best;
}

}  // namespace

std::vector<PathPiece> waypointPath(const Pose2D& start, std::span<const Position> waypoints,
                                    double cornerRadius) {
  std::vector<Position> nodes{start.position};
  for (const Position& w : waypoints) {
    if ((w - nodes.back()).norm() > 1e-9) nodes.push_back(w);
  }
  std::vector<PathPiece> out;
  if (nodes.size() < 2) return out;
  const std::size_t legs = nodes.size() - 1;
  std::vector<double> length(legs), heading(legs);
  for (std::size_t i = 0; i < legs; ++i) {
    length[i] = (nodes[i + 1] - nodes[i]).norm();
    heading[i] = headingOf(nodes[i + 1] - nodes[i]);
  }
  // Corner k joins leg k - 1 to leg k: its turn, arc radius and the length it cuts off each leg.
  std::vector<double> turn(legs, 0.0), radius(legs, 0.0), trim(legs, 0.0);
  for (std::size_t k = 1; k < legs; ++k) {
    turn[k] = wrapAngle(heading[k] - heading[k - 1]);
    const double a = std::abs(turn[k]);
    if (a < 1e-9 || std::numbers::pi - a < 1e-6 || cornerRadius <= 0.0) continue;
    const double t = std::tan(0.5 * a);
    radius[k] = std::min(cornerRadius, 0.5 * std::min(length[k - 1], length[k]) / t);
    trim[k] = radius[k] * t;
  }
  const double first = wrapAngle(heading[0] - start.heading);
  if (std::abs(first) > 1e-12) out.push_back({0.0, 0.0, first});
  for (std::size_t i = 0; i < legs; ++i) {
    const double straight = length[i] - trim[i] - (i + 1 < legs ? trim[i + 1] : 0.0);
    if (straight > 1e-12) out.push_back({straight, 0.0, 0.0});
    if (i + 1 == legs) break;
    const std::size_t k = i + 1;
    if (radius[k] > 0.0) {
      out.push_back({radius[k] * std::abs(turn[k]), std::copysign(1.0 / radius[k], turn[k]), 0.0});
    } else if (std::abs(turn[k]) >= 1e-9) {
      out.push_back({0.0, 0.0, turn[k]});
    }
  }
  return out;
}

std::vector<Position> sweepWaypoints(const Position& lo, const Position& hi, double spacing) {
  if (!(spacing > 0.0)) throw std::invalid_argument("sweepWaypoints: spacing must be above 0");
  const bool alongX = hi.x() - lo.x() >= hi.y() - lo.y();
  const int axis = alongX ? 1 : 0;  // the coordinate that steps from lane to lane
  const int along = 1 - axis;
  std::vector<Position> out;
  for (int k = 0;; ++k) {
    const double c = lo[axis] + k * spacing;
    if (c > hi[axis] + 1e-9) break;
    Position a, b;
    a[axis] = c;
    b[axis] = c;
    a[along] = k % 2 == 0 ? lo[along] : hi[along];
    b[along] = k % 2 == 0 ? hi[along] : lo[along];
    out.push_back(a);
    out.push_back(b);
  }
  return out;
}

std::vector<Position> loopWaypoints(const Position& lo, const Position& hi, double inset) {
  const Position a = lo + Position(inset, inset);
  const Position b = hi - Position(inset, inset);
  const Position middle(0.5 * (a.x() + b.x()), a.y());
  return {middle, {b.x(), a.y()}, b, {a.x(), b.y()}, a, middle};
}

std::vector<double> stopDistances(double length, int stops) {
  std::vector<double> out;
  for (int k = 0; k < stops; ++k) out.push_back(length * (2.0 * k + 1.0) / (2.0 * stops));
  return out;
}

std::vector<Position> parseRouteText(std::string_view text, const std::string& displayName) {
  std::vector<Position> out;
  std::size_t lineNo = 0;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t eol = std::min(text.find('\n', pos), text.size());
    std::string_view line = text.substr(pos, eol - pos);
    pos = eol + 1;
    ++lineNo;
    if (const std::size_t hash = line.find('#'); hash != std::string_view::npos)
      line = line.substr(0, hash);
    std::vector<double> numbers;
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
      if (i == line.size()) break;
      std::size_t j = i;
      while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != '\r') ++j;
      const std::string_view field = line.substr(i, j - i);
      double v = 0.0;
      const auto [ptr, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
      if (ec != std::errc() || ptr != field.data() + field.size() || !std::isfinite(v)) {
        throw LogError(displayName, lineNo, "waypoint",
                       "expected a number, got '" + file_text::shown(field) + "'");
      }
      numbers.push_back(v);
      i = j;
    }
    if (numbers.empty()) continue;
    if (numbers.size() != 2) {
      throw LogError(displayName, lineNo, "waypoint",
                     "expected two numbers 'X Y' (metres), got " + std::to_string(numbers.size()));
    }
    out.emplace_back(numbers[0], numbers[1]);
  }
  if (out.empty()) throw LogError(displayName, 0, "", "no waypoint; expected lines 'X Y' (metres)");
  return out;
}

std::vector<Position> readRouteFile(const std::string& path) {
  return parseRouteText(file_text::readFileBytes(path), path);
}

std::vector<Position> worldRoute(const std::string& worldPath) {
  const std::filesystem::path route = std::filesystem::path(worldPath).parent_path() / "route.txt";
  std::error_code error;
  if (!std::filesystem::is_regular_file(route, error)) return {};
  return readRouteFile(route.string());
}

std::optional<Clearance> closestApproach(const SonarWorld& world, const Trajectory& path,
                                         double step) {
  if (world.segments.empty() && world.circles.empty()) return std::nullopt;
  Clearance best{std::numeric_limits<double>::infinity(), path.start().position};
  const auto check = [&](const Position& p) {
    const double d = distanceToWorld(p, world);
    if (d < best.distance) best = {d, p};
  };
  Pose2D pose = path.start();
  check(pose.position);
  for (const PathPiece& piece : path.pieces()) {
    const int samples = std::max(1, static_cast<int>(std::ceil(piece.length / step)));
    for (int k = 1; k <= samples; ++k)
      check(advanceAlong(pose, piece, static_cast<double>(k) / samples).position);
    pose = advanceAlong(pose, piece, 1.0);
  }
  return best;
}

}  // namespace sg
