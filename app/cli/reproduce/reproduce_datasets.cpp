// SPDX-License-Identifier: GPL-3.0-or-later
// The simulated datasets of `reproduce` under a physics preset (docs/reproduction.md): the same
// runs as datasets/generate.sh (robot, route, stops, duration, seeds, drift on), written by the
// same simulator calls as `sonargrid-cli simulate`, so that under the `default` preset they are
// the bundled logs byte for byte (tst_reproduce checks one).

#include <iomanip>
#include <sstream>

#include "arguments.h"
#include "reproduce/reproduce.h"
#include "sonargrid/base/log_error.h"
#include "sonargrid/io/sglog.h"
#include "sonargrid/reference/reference_json.h"
#include "sonargrid/sim/physics_parameters.h"
#include "sonargrid/sim/simulation.h"

namespace sg::cli::reproduce {
namespace {

struct Run {
  const char* robot;
  RouteKind route;
  int stops;        // stop-and-scan only; 0 otherwise
  double duration;  // 0: the route once
  std::uint64_t seed;
  std::string file;
};

// datasets/generate.sh, run for run.
std::vector<Run> runsOf(const std::string& folder) {
  std::vector<Run> runs;
  if (folder == "raschke-multi" || folder == "raschke-single") {
    for (int run = 1; run <= 10; ++run) {
      std::ostringstream n;
      n << std::setw(2) << std::setfill('0') << run;
      const auto seed = static_cast<std::uint64_t>(run);
      runs.push_back({"k2a", RouteKind::InMotion, 0, 0.0, seed, "in-motion-" + n.str() + ".sglog"});
      runs.push_back(
          {"k2a", RouteKind::StopAndScan, 4, 0.0, seed, "stop-and-scan-" + n.str() + ".sglog"});
    }
  } else if (folder == "arafat-room") {
    for (std::uint64_t run = 1; run <= 2; ++run)
      runs.push_back(
          {"amigobot", RouteKind::UTurn, 0, 240.0, run, "run-" + std::to_string(run) + ".sglog"});
  } else {
    throw std::invalid_argument("no recipe for the dataset '" + folder + "'");
  }
  return runs;
}

}  // namespace

void simulateDatasets(const fs::path& source, const fs::path& out, const std::string& preset,
                      const std::vector<std::string>& folders) {
  const std::optional<ParameterSet> physics = physicsPreset(preset);
  if (!physics) throw std::invalid_argument("unknown physics preset '" + preset + "'");
  for (const std::string& folder : folders) {
    const fs::path world = source / folder / "world.json";
    const fs::path routeFile = source / folder / "route.txt";
    for (const fs::path& p : {world, routeFile}) {
      if (!fs::exists(p))
        throw InputError(p.string() + ": needed to simulate the " + preset +
                         " preset (give the datasets folder with --datasets DIR, or --physics "
                         "default for logs without their world and route)");
    }
    ReferenceMap map;
    std::vector<Position> waypoints;
    try {
      map = readReferenceJson(world.string());
      waypoints = readRouteFile(routeFile.string());
    } catch (const LogError& e) {
      throw InputError(e.what());
    }
    const SonarWorld sonar = sonarWorld(map);
    std::error_code ec;
    fs::create_directories(out / folder, ec);
    if (ec) throw std::runtime_error("cannot create '" + (out / folder).string() + "'");
    fs::copy_file(world, out / folder / "world.json", fs::copy_options::overwrite_existing);
    for (const Run& run : runsOf(folder)) {
      SonarRing ring;
      SonarRing::preset(run.robot, ring);
      SimulationSettings settings;
      settings.route = run.route;
      if (run.stops > 0) settings.stops = run.stops;
      if (run.duration > 0.0) settings.duration = run.duration;
      settings.physics.seed = run.seed;
      applyPhysics(*physics, settings.physics, ring);
      settings.drift = driftErrors(*physics);
      std::optional<Trajectory> path;
      try {
        path = planTrajectory(startPose(map), waypoints, settings);
      } catch (const std::invalid_argument& e) {
        throw InputError(world.string() + ": " + e.what());
      }
      // `simulate`'s name for the same run (command_simulate.cpp), so the bytes match.
      const std::string name = std::string("simulated ") + run.robot + ", " +
                               routeKindName(run.route) + " route in world.json, seed " +
                               std::to_string(run.seed) + ", drift on";
      writeSglog(simulate(sonar, ring, *path, settings, name), (out / folder / run.file).string());
    }
  }
}

}  // namespace sg::cli::reproduce
