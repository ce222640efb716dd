// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// How the virtual robot (virtual_robot.h) is set up in a world, shared by `sonargrid-cli robot` and
// the app's "Start Virtual Robot": its sonar as the simulator models it, and the route it drives
// until a client takes it over (docs/live-robot.md, "The virtual robot").

#include <optional>
#include <stdexcept>
#include <vector>

#include "sonargrid/arcos/virtual_robot.h"
#include "sonargrid/reference/reference_map.h"
#include "sonargrid/sim/simulation.h"

namespace sg::arcos {

// A route that passes closer to a surface than the robot's radius.
class RouteClearanceError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// The sonar of `sonargrid-cli simulate` with its declared defaults (physics_parameters.h,
// docs/simulator.md, the `default` preset). The seed is left as it is.
void useSimulatorSonar(SonarPhysics& physics);

// The robot's settings for `robot` (a preset of robotPreset()) whose clock runs `timeScale`
// simulated seconds per real second: the server names itself SonarGridSim with the robot's
// subclass, and its watchdog stays two real seconds (the client's keep-alive runs in real time).
VirtualRobotSettings virtualRobotSettings(const RobotParameters& robot, double timeScale = 1.0);

// One lap of a repeating route: the route out, back, and a turn on the spot into the starting
// heading, so that the lap ends where and as it began and can be driven over and over.
Trajectory outAndBackLap(const std::optional<Pose2D>& start, const std::vector<Position>& waypoints,
                         SimulationSettings settings);

// Stop-and-scan: how long the robot stands at each stop (about three turns of a Pioneer's ring).
inline constexpr double kStopHold = 1.0;

struct VirtualRoute {
  Pose2D start;
  std::optional<RoutePlan> plan;  // none: the robot waits for the client's commands
};

// Where the robot starts and what it drives in `map`: `settings.route` (out and back over and over
// for in-motion and u-turn, once for stop-and-scan) through `waypoints` (empty: the route's
// default), or, with `teleop`, nothing. Throws RouteClearanceError when the route passes within
// the robot's radius of a surface, std::invalid_argument when no route can be planned.
VirtualRoute planVirtualRoute(const ReferenceMap& map, const SonarRing& ring,
                              const SimulationSettings& settings,
                              std::vector<Position> waypoints = {}, bool teleop = false);

}  // namespace sg::arcos
