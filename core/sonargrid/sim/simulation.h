// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The full simulator behind `sonargrid-cli simulate` (docs/simulator.md): a world from a reference
// map, a route, a differential-drive robot with optional odometry drift, and its sonar ring fired
// in motion (HIMM style, paper 000 §2.2), at well-spaced stops (HPF style, paper 000 §4.2) or on
// back-and-forth U-turn sweeps (paper 002 §4). The log carries odometry and true poses.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "sonargrid/data/dataset.h"
#include "sonargrid/reference/reference_map.h"
#include "sonargrid/sim/differential_drive.h"
#include "sonargrid/sim/ray_sonar.h"
#include "sonargrid/sim/route.h"

namespace sg {

enum class RouteKind { InMotion, StopAndScan, UTurn };

// "in-motion", "stop-and-scan", "u-turn".
const char* routeKindName(RouteKind kind);
std::optional<RouteKind> routeKindFromName(const std::string& name);

// The segments and circles sound meets, in metres. A surface's specular limit: diffuse 90 degrees;
// specular its own specular_limit_deg, or the physics default; unspecified the physics default.
SonarWorld sonarWorld(const ReferenceMap& map);

// The map's start pose in metres and radians, if it has one.
std::optional<Pose2D> startPose(const ReferenceMap& map);

// Corners of the box holding every surface of the world.
struct Bounds {
  Position lo, hi;
};
std::optional<Bounds> worldBounds(const SonarWorld& world);

// The robot's body as the simulator needs it.
struct RobotBody {
  double wheelbase = 0.33;  // metres between the drive wheels (odometry)
  double radius = 0.25;     // metres: the farthest sonar from the centre; routes keep this clear
};
RobotBody robotBody(const SonarRing& ring);

// Odometry errors with `--drift on` (docs/simulator.md, "Odometry drift").
OdometryErrors defaultDrift();

struct SimulationSettings {
  RouteKind route = RouteKind::InMotion;
  int stops = 4;                   // stop-and-scan: scans at this many stops
  std::optional<double> duration;  // in-motion and u-turn: drive the route out and back until then
  double ringHz = 10.0;            // ring cycles per second; the sonars fire evenly within a cycle
  DriveLimits limits;
  double cornerRadius = 0.3;            // metres: waypoint corners are rounded by arcs this large
  double routeInset = 0.8;              // default routes keep this far inside the world's bounds
  double sweepSpacing = 0.8;            // default U-turn lanes, metres apart
  std::optional<OdometryErrors> drift;  // none: odometry equals the true pose
  SonarPhysics physics;                 // physics.seed seeds everything
};

// The route as waypoints: `routeFile` when given, otherwise a default from the world's bounds:
// a rounded rectangle loop for in-motion and stop-and-scan, back-and-forth lanes for u-turn.
std::vector<Position> routeWaypoints(RouteKind kind, const SonarWorld& world,
                                     const SimulationSettings& settings);

// The path from `start` (the map's start pose; without one, the first waypoint facing the second)
// through the waypoints; for in-motion and u-turn with a duration, repeated back and forth until
// the duration is covered.
Trajectory planTrajectory(const std::optional<Pose2D>& start, std::span<const Position> waypoints,
                          const SimulationSettings& settings);

// Drives the trajectory and logs the ring: one scan per ring cycle (in motion), or one per stop.
// Sonar i of a cycle fires at cycle time + i / (ringHz * ring size) from the true pose of that
// moment. Logged poses are kept to 0.1 mm and 10 microradians, times to the microsecond.
Dataset simulate(const SonarWorld& world, const SonarRing& ring, const Trajectory& path,
                 const SimulationSettings& settings, std::string name);

}  // namespace sg
