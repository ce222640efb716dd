// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Routes the simulated robot drives (docs/simulator.md, "Routes"): a polyline of waypoints turned
// into a drivable path with rounded corners, the back-and-forth lanes of a U-turn sweep (paper 002
// §4), the stops of a stop-and-scan run (paper 000 §4.2), and the route file that lists waypoints.

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sonargrid/data/pose.h"
#include "sonargrid/sim/differential_drive.h"
#include "sonargrid/sim/ray_sonar.h"

namespace sg {

// From `start`: a turn on the spot toward the first waypoint, then straight legs from waypoint to
// waypoint, each corner rounded by an arc of `cornerRadius` (smaller where a leg is too short: an
// arc never takes more than half of either leg). A reversal (a 180-degree corner) is a turn on the
// spot. A first waypoint equal to the start position is skipped.
std::vector<PathPiece> waypointPath(const Pose2D& start, std::span<const Position> waypoints,
                                    double cornerRadius);

// Lanes along the longer side of the rectangle [lo, hi], `spacing` apart, the first along its lower
// (or left) edge, joined end to end: a zigzag whose short legs are `spacing` long, so that
// waypointPath with a corner radius of spacing / 2 joins the lanes by semicircular U-turns.
std::vector<Position> sweepWaypoints(const Position& lo, const Position& hi, double spacing);

// A rectangle loop `inset` inside [lo, hi], counter-clockwise from the middle of its lower side and
// back there.
std::vector<Position> loopWaypoints(const Position& lo, const Position& hi, double inset);

// Where a stop-and-scan run stops: the middles of `stops` equal parts of a path `length` long,
// s_k = length (2k + 1) / (2 stops), so that the stops are evenly spread and none sits at an end.
std::vector<double> stopDistances(double length, int stops);

// The route file: one waypoint "X Y" (metres) per line; blank lines and '#' comments are ignored.
// Throws LogError naming the file, the line and what was expected.
std::vector<Position> parseRouteText(std::string_view text, const std::string& displayName);
std::vector<Position> readRouteFile(const std::string& path);

// The route drawn for a world: the route file `route.txt` beside the world file, as every bundled
// dataset keeps one (datasets/README.md), read with readRouteFile(); empty when there is none. A
// world's own route goes around its obstacles, where the route a RouteKind plans from the world's
// bounds alone may cross them (the virtual robot's default, issue 49).
std::vector<Position> worldRoute(const std::string& worldPath);

// The closest the robot (a disc of `radius` metres) comes to a surface along the trajectory,
// sampled every `step` metres and at each turn: where and how close. Empty for an empty world.
struct Clearance {
  double distance = 0.0;  // from the robot centre to the nearest surface
  Position where;
};
std::optional<Clearance> closestApproach(const SonarWorld& world, const Trajectory& path,
                                         double step = 0.02);

}  // namespace sg
