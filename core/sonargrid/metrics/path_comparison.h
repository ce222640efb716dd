// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Path comparison (paper 001 §4, benchmark 4, after O'Sullivan 2003): would a robot that plans on
// the built map collide with the real world? (docs/metrics.md, "Path comparison")
//   - Start/goal pairs are drawn from the ideal map's free cells that the built map observed, with
//     a fixed-seed generator (SeededRandom), each pair joined by a path in the ideal map: the start
//     uniformly among such cells, the goal uniformly among the other cells of its ideal component.
//   - The robot is a point at cell resolution (no radius: a clearance would be one more parameter
//     the papers do not give). Moves are 8-connected without corner cutting (GridPathPlanner).
//   - On the built map a cell is blocked when it is observed with p > 0.5; never-observed cells
//     are passable (the planner is optimistic about the unknown, as a navigating robot is).
//   - A path found on the built map is a false positive when it enters an occupied cell of the
//     ideal map or steps diagonally between two of them. A pair with no path on the built map is
//     a false negative.
//   - false positives (%) = colliding paths / paths found; false negatives (%) = pairs without a
//     path / pairs.

#include <cstdint>
#include <optional>

#include "sonargrid/engine/occupancy_map.h"
#include "sonargrid/metrics/ideal_map.h"

namespace sg {

inline constexpr int kDefaultPathPairs = 200;
inline constexpr std::uint64_t kDefaultPathSeed = 1990;  // the year of paper 000

struct PathComparison {
  std::size_t pairs = 0;       // drawn (0 when the ideal free space has no two connected cells)
  std::size_t pathsFound = 0;  // on the built map
  std::size_t collisions = 0;  // of the paths found
  std::size_t noPath = 0;
  std::optional<double> falsePositivePct;  // empty when no path was found
  std::optional<double> falseNegativePct;  // empty when no pair could be drawn
};

// Throws std::invalid_argument for maps on different grids or pairs < 0.
PathComparison comparePaths(const OccupancyMap& map, const IdealMap& ideal,
                            int pairs = kDefaultPathPairs, std::uint64_t seed = kDefaultPathSeed);

}  // namespace sg
