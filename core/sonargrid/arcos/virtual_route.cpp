// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/arcos/virtual_route.h"

#include "sonargrid/sim/physics_parameters.h"

#include <cstdint>
#include <sstream>
#include <string>

namespace sg::arcos {
namespace {

std::string fixed(double v, int decimals) {
  std::ostringstream s;
  s.precision(decimals);
  s << std::fixed << v;
  return s.str();
}

}  // namespace

void useSimulatorSonar(SonarPhysics& p) {
  // The declared defaults (physics_parameters.h); the robot's own ring keeps its range window.
  const std::uint64_t seed = p.seed;
  SonarRing scratch;
  applyPhysics(defaultPhysicsParameters(), p, scratch);
  p.seed = seed;
}

VirtualRobotSettings virtualRobotSettings(const RobotParameters& robot, double timeScale) {
  VirtualRobotSettings settings;
  useSimulatorSonar(settings.physics);
  settings.robot = robot;
  settings.watchdog *= timeScale;
  settings.server = {"SonarGridSim", "Pioneer", robot.preset == "amigobot" ? "amigo" : "p3dx"};
  return settings;
}

Trajectory outAndBackLap(const std::optional<Pose2D>& start, const std::vector<Position>& waypoints,
                         SimulationSettings settings) {
  settings.duration.reset();
  const Trajectory out = planTrajectory(start, waypoints, settings);
  // A duration just past the route out makes planTrajectory add exactly the leg back.
  settings.duration = out.duration() + 1e-6;
  const Trajectory lap = planTrajectory(start, waypoints, settings);
  std::vector<PathPiece> pieces = lap.pieces();
  const double turn = wrapAngle(lap.start().heading - lap.end().heading);
  if (turn != 0.0) pieces.push_back(PathPiece{0.0, 0.0, turn});
  return Trajectory(lap.start(), std::move(pieces), settings.limits);
}

VirtualRoute planVirtualRoute(const ReferenceMap& map, const SonarRing& ring,
                              const SimulationSettings& sim, std::vector<Position> waypoints,
                              bool teleop) {
  const SonarWorld world = sonarWorld(map);
  if (waypoints.empty()) waypoints = routeWaypoints(sim.route, world, sim);
  const bool repeat = sim.route != RouteKind::StopAndScan;
  const Trajectory path = repeat ? outAndBackLap(startPose(map), waypoints, sim)
                                 : planTrajectory(startPose(map), waypoints, sim);
  VirtualRoute out;
  out.start = path.start();
  if (teleop) return out;
  const RobotBody body = robotBody(ring);
  if (const auto near = closestApproach(world, path); near && near->distance < body.radius) {
    throw RouteClearanceError("the route passes " + fixed(near->distance, 3) +
                              " m from a surface at (" + fixed(near->where.x(), 3) + ", " +
                              fixed(near->where.y(), 3) + "), inside the " + ring.robot +
                              "'s radius of " + fixed(body.radius, 3) +
                              " m: give a route that keeps clear (--route-file)");
  }
  out.plan = RoutePlan{path, {}, 0.0, repeat};
  if (sim.route == RouteKind::StopAndScan) {
    for (const double s : stopDistances(path.length(), sim.stops))
      out.plan->stops.push_back(path.timeAtDistance(s));
    out.plan->hold = kStopHold;
  }
  return out;
}

}  // namespace sg::arcos
