// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/sim/simulation.h"

#include "sonargrid/sim/physics_parameters.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace sg {
namespace {

// The odometry's noise has its own engine, so that turning drift on or off leaves every sonar
// reading of a seed unchanged. The salt is the 64-bit golden-ratio constant.
constexpr std::uint64_t kOdometrySeedSalt = 0x9E3779B97F4A7C15ULL;
// Odometry is integrated in steps no longer than this (seconds): each is taken as one arc.
constexpr double kOdometryStep = 0.01;

double roundTo(double v, double scale) {
  return std::round(v * scale) / scale;
}

Pose2D logged(const Pose2D& p) {
  return {roundTo(p.x(), 1e4), roundTo(p.y(), 1e4), roundTo(wrapAngle(p.heading), 1e5)};
}

double loggedTime(double t) {
  return roundTo(t, 1e6);
}

double incidenceLimit(const ReferenceObject& o) {
  switch (o.surface) {
    case Surface::Diffuse:
      return kDiffuseIncidenceLimit;
    case Surface::Specular:
      return o.specularLimitDeg ? *o.specularLimitDeg : kPhysicsIncidenceLimit;
    case Surface::Unspecified:
      break;
  }
  return kPhysicsIncidenceLimit;
}

// Odometry followed along the true trajectory up to time t.
class OdometryTrack {
 public:
  OdometryTrack(const Trajectory& path, const SimulationSettings& settings, double wheelbase)
      : path_(path),
        odometry_(path.start(), wheelbase, settings.drift.value_or(OdometryErrors{}),
                  settings.physics.seed ^ kOdometrySeedSalt),
        last_(path.start()),
        drifts_(settings.drift.has_value()) {}

  // Without drift the odometry is the true pose, exactly.
  Pose2D advanceTo(double t) {
    if (!drifts_) return path_.poseAt(t);
    if (t > time_) {
      const int steps = static_cast<int>(std::ceil((t - time_) / kOdometryStep));
      const double t0 = time_;
      for (int k = 1; k <= steps; ++k) {
        const double tk = k == steps ? t : t0 + (t - t0) * k / steps;
        const Pose2D next = path_.poseAt(tk);
        odometry_.step(last_, next);
        last_ = next;
      }
      time_ = t;
    }
    return odometry_.pose();
  }

 private:
  const Trajectory& path_;
  Odometry odometry_;
  Pose2D last_;
  bool drifts_;
  double time_ = 0.0;
};

Scan fireScan(const SonarWorld& world, const SonarRing& ring, const SimulationSettings& settings,
              SimRng& rng, double time, const Pose2D& odometry, const Pose2D& truth,
              const Trajectory* moving) {
  const double interval = 1.0 / (settings.ringHz * static_cast<double>(ring.size()));
  std::vector<Pose2D> sensors;
  sensors.reserve(ring.size());
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Pose2D robot = moving ? moving->poseAt(time + static_cast<double>(i) * interval) : truth;
    sensors.push_back(robot.compose(ring.sonars[i].pose));
  }
  const std::vector<double> ranges = fireRing(world, sensors, ring, settings.physics, rng);
  Scan scan;
  scan.time = loggedTime(time);
  scan.odometry = logged(odometry);
  scan.truth = logged(truth);
  scan.readings.reserve(ring.size());
  for (std::size_t i = 0; i < ring.size(); ++i) {
    Reading r;
    r.sonar = static_cast<std::uint16_t>(i);
    r.time = loggedTime(time + static_cast<double>(i) * interval);
    r.range = ranges[i];
    scan.readings.push_back(r);
  }
  return scan;
}

}  // namespace

const char* routeKindName(RouteKind kind) {
  switch (kind) {
    case RouteKind::InMotion:
      return "in-motion";
    case RouteKind::StopAndScan:
      return "stop-and-scan";
    case RouteKind::UTurn:
      return "u-turn";
  }
  return "in-motion";
}

std::optional<RouteKind> routeKindFromName(const std::string& name) {
  for (RouteKind k : {RouteKind::InMotion, RouteKind::StopAndScan, RouteKind::UTurn}) {
    if (name == routeKindName(k)) return k;
  }
  return std::nullopt;
}

SonarWorld sonarWorld(const ReferenceMap& map) {
  SonarWorld world;
  const double scale = map.metresPerUnit();
  for (const ReferenceObject& o : map.objects) {
    const double limit = incidenceLimit(o);
    if (o.circle) {
      world.circles.push_back({o.circle->centre * scale, o.circle->radius * scale, limit});
      continue;
    }
    for (const auto& [a, b] : map.edgesMetres(o)) world.segments.push_back({a, b, limit});
  }
  return world;
}

std::optional<Pose2D> startPose(const ReferenceMap& map) {
  if (!map.start) return std::nullopt;
  const Position p = map.start->position * map.metresPerUnit();
  return Pose2D(p.x(), p.y(), wrapAngle(degToRad(map.start->headingDeg)));
}

std::optional<Bounds> worldBounds(const SonarWorld& world) {
  if (world.segments.empty() && world.circles.empty()) return std::nullopt;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Bounds b{{kInf, kInf}, {-kInf, -kInf}};
  const auto add = [&](const Position& p) {
    b.lo = b.lo.cwiseMin(p);
    b.hi = b.hi.cwiseMax(p);
  };
  for (const Segment& s : world.segments) {
    add(s.a);
    add(s.b);
  }
  for (const Circle& c : world.circles) {
    add(c.centre - Position(c.radius, c.radius));
    add(c.centre + Position(c.radius, c.radius));
  }
  return b;
}

RobotBody robotBody(const SonarRing& ring) {
  RobotBody body;
  // Wheel separations, approximately, from the makers' published dimensions (docs/simulator.md).
  if (ring.robot == "p3dx") {
    body.wheelbase = 0.33;
  } else if (ring.robot == "amigobot") {
    body.wheelbase = 0.28;
  } else if (ring.robot == "k2a") {
    body.wheelbase = 0.6;
  }
  double farthest = 0.0;
  for (const SonarMount& m : ring.sonars) farthest = std::max(farthest, m.pose.position.norm());
  if (farthest > 0.0) body.radius = farthest;
  return body;
}

OdometryErrors defaultDrift() {
  return driftErrors(defaultPhysicsParameters());
}

std::vector<Position> routeWaypoints(RouteKind kind, const SonarWorld& world,
                                     const SimulationSettings& settings) {
  const std::optional<Bounds> bounds = worldBounds(world);
  if (!bounds) throw std::invalid_argument("the world has no surface: give a route file");
  const Position lo = bounds->lo + Position(settings.routeInset, settings.routeInset);
  const Position hi = bounds->hi - Position(settings.routeInset, settings.routeInset);
  if (!(hi.x() > lo.x()) || !(hi.y() > lo.y())) {
    throw std::invalid_argument("the world is too small for a default route " +
                                std::to_string(settings.routeInset) +
                                " m inside its bounds: give a route file");
  }
  if (kind == RouteKind::UTurn) return sweepWaypoints(lo, hi, settings.sweepSpacing);
  return loopWaypoints(bounds->lo, bounds->hi, settings.routeInset);
}

Trajectory planTrajectory(const std::optional<Pose2D>& start, std::span<const Position> waypoints,
                          const SimulationSettings& settings) {
  if (waypoints.empty()) throw std::invalid_argument("a route needs at least one waypoint");
  Pose2D from;
  std::vector<Position> nodes;
  if (start) {
    from = *start;
    nodes.push_back(start->position);
  } else {
    if (waypoints.size() < 2)
      throw std::invalid_argument(
          "a route without a start pose needs "
          "at least two waypoints");
    const Position d = waypoints[1] - waypoints[0];
    from = Pose2D(waypoints[0].x(), waypoints[0].y(), std::atan2(d.y(), d.x()));
  }
  nodes.insert(nodes.end(), waypoints.begin(), waypoints.end());
  // U-turn sweeps join lanes `sweepSpacing` apart by semicircles.
  const double radius =
      settings.route == RouteKind::UTurn ? 0.5 * settings.sweepSpacing : settings.cornerRadius;
  std::vector<PathPiece> pieces = waypointPath(from, waypoints, radius);
  Trajectory path(from, pieces, settings.limits);
  if (!settings.duration || settings.route == RouteKind::StopAndScan) return path;
  if (!(path.length() > 0.0)) throw std::invalid_argument("the route has no length to repeat");
  // Out and back: the reversed waypoints from wherever the robot stands.
  bool backwards = true;
  while (path.duration() < *settings.duration) {
    std::vector<Position> leg(nodes.begin(), nodes.end());
    if (backwards) std::reverse(leg.begin(), leg.end());
    const std::vector<PathPiece> more = waypointPath(path.end(), leg, radius);
    pieces.insert(pieces.end(), more.begin(), more.end());
    path = Trajectory(from, pieces, settings.limits);
    backwards = !backwards;
  }
  return path;
}

Dataset simulate(const SonarWorld& world, const SonarRing& ring, const Trajectory& path,
                 const SimulationSettings& settings, std::string name) {
  if (!(settings.ringHz > 0.0)) throw std::invalid_argument("the ring rate must be above 0");
  if (ring.size() == 0) throw std::invalid_argument("the ring has no sonar");
  Dataset out;
  out.name = std::move(name);
  out.ring = ring;
  SimRng rng(settings.physics.seed);
  OdometryTrack odometry(path, settings, robotBody(ring).wheelbase);
  if (settings.route == RouteKind::StopAndScan) {
    if (settings.stops < 1) throw std::invalid_argument("stop-and-scan needs at least one stop");
    const double cycle = 1.0 / settings.ringHz;
    const std::vector<double> stops = stopDistances(path.length(), settings.stops);
    for (std::size_t k = 0; k < stops.size(); ++k) {
      // Each earlier stop held the robot still for one ring cycle.
      const double drive = path.timeAtDistance(stops[k]);
      const Pose2D truth = path.poseAt(drive);
      const Pose2D odo = odometry.advanceTo(drive);
      out.scans.push_back(fireScan(world, ring, settings, rng,
                                   drive + static_cast<double>(k) * cycle, odo, truth, nullptr));
    }
    return out;
  }
  const double end =
      settings.duration ? std::min(*settings.duration, path.duration()) : path.duration();
  for (long k = 0;; ++k) {
    // k / rate is the double nearest the decimal time ("0.3", not a running sum's 0.30000000004).
    const double t = static_cast<double>(k) / settings.ringHz;
    if (t > end) break;
    const Pose2D odo = odometry.advanceTo(t);
    out.scans.push_back(fireScan(world, ring, settings, rng, t, odo, path.poseAt(t), &path));
  }
  return out;
}

}  // namespace sg
