// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/metrics/path_comparison.h"

#include <cstdlib>
#include <stdexcept>
#include <vector>

#include "sonargrid/metrics/grid_path_planner.h"
#include "sonargrid/metrics/seeded_random.h"

namespace sg {
namespace {

bool collides(const std::vector<std::size_t>& path, const IdealMap& ideal) {
  const auto w = static_cast<std::size_t>(ideal.spec.width);
  for (std::size_t k = 0; k < path.size(); ++k) {
    if (ideal.cells[path[k]] == IdealCell::Occupied) return true;
    if (k == 0) continue;
    const std::size_t a = path[k - 1], b = path[k];
    const std::size_t ax = a % w, ay = a / w, bx = b % w, by = b / w;
    if (ax != bx && ay != by) {
      // The two cells beside a diagonal step: (bx, ay) and (ax, by).
      if (ideal.cells[ay * w + bx] == IdealCell::Occupied &&
          ideal.cells[by * w + ax] == IdealCell::Occupied) {
        return true;
      }
    }
  }
  return false;
}

}  // namespace

PathComparison comparePaths(const OccupancyMap& map, const IdealMap& ideal, int pairs,
                            std::uint64_t seed) {
  if (!(map.spec == ideal.spec))
    throw std::invalid_argument("path comparison: the ideal map is on another grid");
  if (pairs < 0)
    throw std::invalid_argument("path comparison: the number of pairs must not be negative");
  const std::size_t n = map.spec.cellCount();
  if (map.probability.size() != n || map.observed.size() != n) {
    throw std::invalid_argument("path comparison: the map's layers do not match its grid");
  }

  // Ideal connectivity through free cells only.
  std::vector<std::uint8_t> idealPassable(n);
  for (std::size_t i = 0; i < n; ++i) idealPassable[i] = ideal.cells[i] == IdealCell::Free ? 1 : 0;
  GridPathPlanner idealPlanner(map.spec.width, map.spec.height, std::move(idealPassable));
  const std::vector<std::int32_t>& idealComponent = idealPlanner.components();

  // Candidate endpoints, grouped by ideal component, in cell order.
  std::vector<std::vector<std::size_t>> byComponent;
  for (std::size_t i = 0; i < n; ++i) {
    if (ideal.cells[i] != IdealCell::Free || map.observed[i] == 0) continue;
    const auto c = static_cast<std::size_t>(idealComponent[i]);
    if (byComponent.size() <= c) byComponent.resize(c + 1);
    byComponent[c].push_back(i);
  }
  // Starts: candidates with at least one other candidate in their component; (component, slot).
  std::vector<std::pair<std::size_t, std::size_t>> starts;
  for (std::size_t c = 0; c < byComponent.size(); ++c) {
    if (byComponent[c].size() < 2) continue;
    for (std::size_t s = 0; s < byComponent[c].size(); ++s) starts.emplace_back(c, s);
  }
  PathComparison out;
  if (starts.empty() || pairs == 0) return out;

  std::vector<std::uint8_t> builtPassable(n);
  for (std::size_t i = 0; i < n; ++i) {
    builtPassable[i] = map.observed[i] != 0 && map.probability[i] > 0.5 ? 0 : 1;
  }
  GridPathPlanner planner(map.spec.width, map.spec.height, std::move(builtPassable));
  const std::vector<std::int32_t>& builtComponent = planner.components();

  SeededRandom random(seed);
  for (int k = 0; k < pairs; ++k) {
    const auto [component, slot] = starts[random.below(starts.size())];
    const std::vector<std::size_t>& cells = byComponent[component];
    std::size_t other = random.below(cells.size() - 1);
    if (other >= slot) ++other;  // any cell of the component but the start
    const std::size_t start = cells[slot];
    const std::size_t goal = cells[other];
    ++out.pairs;
    // Components settle "no path" without searching the whole grid.
    if (builtComponent[start] < 0 || builtComponent[start] != builtComponent[goal]) {
      ++out.noPath;
      continue;
    }
    const std::vector<std::size_t> path = planner.findPath(start, goal);
    if (path.empty()) {
      ++out.noPath;
      continue;
    }
    ++out.pathsFound;
    if (collides(path, ideal)) ++out.collisions;
  }
  out.falseNegativePct = 100.0 * static_cast<double>(out.noPath) / static_cast<double>(out.pairs);
  if (out.pathsFound > 0) {
    out.falsePositivePct =
        100.0 * static_cast<double>(out.collisions) / static_cast<double>(out.pathsFound);
  }
  return out;
}

}  // namespace sg
