// SPDX-License-Identifier: GPL-3.0-or-later
// `sonargrid-cli simulate`: a simulated sonar log of a robot driving a route through a world given
// as a reference map (docs/cli.md, docs/simulator.md). The same arguments always write the same
// bytes: every random number comes from --seed.

#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "commands.h"
#include "sonargrid/base/log_error.h"
#include "sonargrid/io/sglog.h"
#include "sonargrid/reference/reference_json.h"
#include "sonargrid/sim/physics_parameters.h"
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

// The flags that set a declared physics parameter (physics_parameters.h), flag first.
constexpr std::pair<const char*, const char*> kPhysicsFlags[] = {
    {"--noise", "noise"},
    {"--specular-limit", "specular_limit"},
    {"--multipath", "multipath"},
    {"--bounces", "max_bounces"},
    {"--reflection-loss", "reflection_loss"},
    {"--misread-rate", "misread_rate"},
    {"--crosstalk-rate", "crosstalk_rate"},
    {"--rays", "rays"},
    {"--min-range", "min_range"},
    {"--max-range", "max_range"},
};

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
  const bool drift = onOff(args, "--drift", false);

  // Physics (docs/simulator.md gives each default and its source): a preset from the one
  // declaration (physics_parameters.h), then any flag that names a parameter.
  const std::string presetName = args.value("--physics").value_or("default");
  std::optional<ParameterSet> physics = physicsPreset(presetName);
  if (!physics)
    throw UsageError("--physics expects clean, default or harsh, got '" + presetName + "'");
  for (const auto& [flag, name] : kPhysicsFlags) {
    const std::optional<std::string> text = args.value(flag);
    if (!text) continue;
    double value = 0.0;
    if (name == std::string("multipath")) {
      if (*text != "on" && *text != "off")
        throw UsageError(std::string(flag) + " expects on or off, got '" + *text + "'");
      value = *text == "on" ? 1.0 : 0.0;
    } else {
      value = parseNumber(*text, flag);
    }
    try {
      physics->set(name, value);
    } catch (const ParameterError& e) {
      throw UsageError(std::string(flag) + ": " + e.what());
    }
  }
  SonarPhysics& p = settings.physics;
  applyPhysics(*physics, p, ring);
  if (!(ring.maxRange > ring.minRange)) throw UsageError("--max-range must exceed --min-range");
  if (drift) settings.drift = driftErrors(*physics);
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
