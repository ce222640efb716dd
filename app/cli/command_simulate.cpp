// SPDX-License-Identifier: GPL-3.0-or-later
// `sonargrid-cli simulate`: a simulated sonar log of a robot driving a route through a world given
// as a reference map (docs/cli.md, docs/simulator.md). The same arguments always write the same
// bytes: every random number comes from --seed.

#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "commands.h"
#include "sonargrid/base/log_error.h"
#include "sonargrid/io/sglog.h"
#include "sonargrid/reference/reference_json.h"
#include "sonargrid/sim/simulation.h"

namespace sg::cli {
namespace {

bool onOff(Arguments& args, const std::string& name, bool fallback) {
  const auto v = args.value(name);
  if (!v) return fallback;
  if (*v == "on") return true;
  if (*v == "off") return false;
  throw UsageError(name + " expects on or off, got '" + *v + "'");
}

std::string metres(double v) {
  std::ostringstream s;
  s.precision(3);
  s << std::fixed << v;
  return s.str();
}

}  // namespace

int runSimulate(Arguments& args) {
  const std::string worldPath = args.required("--world");
  const std::string robot = args.required("--robot");
  const std::string routeName = args.required("--route");
  const std::string outPath = args.required("--out");
  const std::optional<std::string> routeFile = args.value("--route-file");

  SonarRing ring;
  if (!SonarRing::preset(robot, ring))
    throw UsageError("--robot expects k2a, p3dx or amigobot, got '" + robot + "'");
  SimulationSettings settings;
  const std::optional<RouteKind> kind = routeKindFromName(routeName);
  if (!kind) {
    throw UsageError("--route expects in-motion, stop-and-scan or u-turn, got '" + routeName + "'");
  }
  settings.route = *kind;
  // 0: the flag was not given.
  const int stops = args.integer("--stops", 0, 1, 10000);
  if (stops != 0 && settings.route != RouteKind::StopAndScan)
    throw UsageError("--stops is only for --route stop-and-scan");
  if (stops != 0) settings.stops = stops;
  const double duration = args.number("--duration", 0.0, 0.001, 1e6);
  if (duration != 0.0 && settings.route == RouteKind::StopAndScan)
    throw UsageError("--duration is not for --route stop-and-scan (it scans at --stops stops)");
  if (duration != 0.0) settings.duration = duration;
  if (const auto seed = args.value("--seed")) settings.physics.seed = parseSeed(*seed);
  if (onOff(args, "--drift", false)) settings.drift = defaultDrift();

  // Physics and motion settings (docs/simulator.md gives each default and its source).
  SonarPhysics& p = settings.physics;
  p.rangeNoiseSd = args.number("--noise", 0.01, 0.0, 1.0);
  p.misreadRate = args.number("--misread-rate", 0.01, 0.0, 1.0);
  p.crosstalkRate = args.number("--crosstalk-rate", 0.0, 0.0, 1.0);
  p.maxIncidenceDeg = args.number("--specular-limit", 20.0, 0.0, 90.0);
  p.specularEcho = onOff(args, "--multipath", true) ? SpecularEcho::Multipath : SpecularEcho::None;
  p.raysPerCone = args.integer("--rays", 9, 1, 1000);
  ring.minRange = args.number("--min-range", 0.15, 0.0, 100.0);
  ring.maxRange = args.number("--max-range", 10.0, 0.01, 100.0);
  if (!(ring.maxRange > ring.minRange)) throw UsageError("--max-range must exceed --min-range");
  settings.ringHz = args.number("--ring-hz", 10.0, 0.01, 1000.0);
  settings.limits.speed = args.number("--speed", 0.3, 0.01, 10.0);
  args.finish();

  ReferenceMap map;
  std::vector<Position> waypoints;
  try {
    map = readReferenceJson(worldPath);
    if (routeFile) waypoints = readRouteFile(*routeFile);
  } catch (const LogError& e) {
    throw InputError(e.what());
  }
  const SonarWorld world = sonarWorld(map);
  const std::optional<Pose2D> start = startPose(map);
  std::optional<Trajectory> path;
  try {
    if (!routeFile) waypoints = routeWaypoints(settings.route, world, settings);
    path = planTrajectory(start, waypoints, settings);
  } catch (const std::invalid_argument& e) {
    throw InputError(worldPath + ": " + e.what());
  }
  const RobotBody body = robotBody(ring);
  if (const auto near = closestApproach(world, *path); near && near->distance < body.radius) {
    throw InputError("the route passes " + metres(near->distance) + " m from a surface at (" +
                     metres(near->where.x()) + ", " + metres(near->where.y()) + "), inside the " +
                     robot + "'s radius of " + metres(body.radius) +
                     " m: give a route that keeps clear (--route-file)");
  }

  // No path in the name: the same world and flags give the same bytes wherever they are run.
  const std::string name = "simulated " + robot + ", " + routeName + " route in " +
                           std::filesystem::path(worldPath).filename().string() + ", seed " +
                           std::to_string(p.seed) + ", drift " + (settings.drift ? "on" : "off");
  const Dataset log = simulate(world, ring, *path, settings, name);
  writeSglog(log, outPath);

  std::size_t echoes = 0;
  for (const Scan& s : log.scans) {
    for (const Reading& r : s.readings) echoes += r.echo() ? 1 : 0;
  }
  std::cout << outPath << ": " << log.scans.size() << " scans, " << log.readingCount()
            << " readings, " << echoes << " echoes; route " << metres(path->length()) << " m, "
            << metres(log.scans.empty() ? 0.0 : log.scans.back().time) << " s\n";
  return 0;
}

}  // namespace sg::cli
