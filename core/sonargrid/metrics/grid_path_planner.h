// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A* on a grid, 8-connected, for the path comparison benchmark (paper 001 §4, benchmark 4).
// A diagonal step is allowed only when both cells beside it are passable (no squeezing between
// two blocked corners). Costs are integers (1000 straight, 1414 diagonal) with the octile
// heuristic, and ties are broken by (f, h, cell index), so the path found is the same on every
// platform. Buffers are kept between searches; a generation stamp replaces clearing them.

#include <cstdint>
#include <vector>

#include "sonargrid/engine/grid_spec.h"

namespace sg {

class GridPathPlanner {
 public:
  // `passable` is row-major like GridSpec, 1 where a robot may go.
  GridPathPlanner(int width, int height, std::vector<std::uint8_t> passable);

  int width() const { return width_; }
  int height() const { return height_; }
  bool passable(std::size_t cell) const { return passable_[cell] != 0; }

  // Connected components under the same moves as the search: a label per cell, -1 where blocked.
  // Two cells have a path between them exactly when their labels are equal and not -1.
  const std::vector<std::int32_t>& components();

  // The cells of a shortest path from start to goal, both included; empty when there is none.
  std::vector<std::size_t> findPath(std::size_t start, std::size_t goal);

  std::size_t lastExpansions() const { return expansions_; }

 private:
  struct Node {
    std::int64_t f;
    std::int64_t h;
    std::uint32_t cell;
  };
  bool canStep(int x, int y, int dx, int dy) const;
  std::int64_t heuristic(std::size_t cell, int goalX, int goalY) const;

  int width_;
  int height_;
  std::vector<std::uint8_t> passable_;
  std::vector<std::int32_t> components_;
  bool componentsReady_ = false;
  std::vector<std::uint32_t> stamp_;
  std::vector<std::int64_t> g_;
  std::vector<std::uint32_t> parent_;
  std::vector<Node> heap_;
  std::uint32_t generation_ = 0;
  std::size_t expansions_ = 0;
};

}  // namespace sg
