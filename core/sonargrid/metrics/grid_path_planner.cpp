// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/metrics/grid_path_planner.h"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <stdexcept>

namespace sg {
namespace {

constexpr std::int64_t kStraight = 1000;
constexpr std::int64_t kDiagonal = 1414;  // 1000 √2, rounded: integer costs keep ties exact
constexpr std::array<std::array<int, 2>, 8> kMoves{
    {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {1, -1}, {-1, 1}, {-1, -1}}};

// Min-heap order on (f, h, cell): a total order, so the search is the same whatever the heap.
struct Later {
  template <typename N>
  bool operator()(const N& a, const N& b) const {
    if (a.f != b.f) return a.f > b.f;
    if (a.h != b.h) return a.h > b.h;
    return a.cell > b.cell;
  }
};

}  // namespace

GridPathPlanner::GridPathPlanner(int width, int height, std::vector<std::uint8_t> passable)
    : width_(width), height_(height), passable_(std::move(passable)) {
  if (width_ <= 0 || height_ <= 0 ||
      passable_.size() != static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_)) {
    throw std::invalid_argument("path planner: the passable layer does not match the grid");
  }
  if (passable_.size() >= 0xFFFFFFFFu) throw std::invalid_argument("path planner: grid too large");
}

bool GridPathPlanner::canStep(int x, int y, int dx, int dy) const {
  const int nx = x + dx, ny = y + dy;
  if (nx < 0 || ny < 0 || nx >= width_ || ny >= height_) return false;
  const auto at = [this](int cx, int cy) {
    return passable_[static_cast<std::size_t>(cy) * static_cast<std::size_t>(width_) +
                     static_cast<std::size_t>(cx)] != 0;
  };
  if (!at(nx, ny)) return false;
  if (dx != 0 && dy != 0) return at(x + dx, y) && at(x, y + dy);
  return true;
}

std::int64_t GridPathPlanner::heuristic(std::size_t cell, int goalX, int goalY) const {
  const int x = static_cast<int>(cell % static_cast<std::size_t>(width_));
  const int y = static_cast<int>(cell / static_cast<std::size_t>(width_));
  const std::int64_t dx = std::abs(x - goalX), dy = std::abs(y - goalY);
  // Octile distance with the same integer costs: admissible and consistent.
  return kStraight * std::max(dx, dy) + (kDiagonal - kStraight) * std::min(dx, dy);
}

const std::vector<std::int32_t>& GridPathPlanner::components() {
  if (componentsReady_) return components_;
  components_.assign(passable_.size(), -1);
  std::vector<std::uint32_t> stack;
  std::int32_t label = 0;
  for (std::size_t seed = 0; seed < passable_.size(); ++seed) {
    if (passable_[seed] == 0 || components_[seed] != -1) continue;
    components_[seed] = label;
    stack.push_back(static_cast<std::uint32_t>(seed));
    while (!stack.empty()) {
      const std::uint32_t c = stack.back();
      stack.pop_back();
      const int x = static_cast<int>(c % static_cast<std::uint32_t>(width_));
      const int y = static_cast<int>(c / static_cast<std::uint32_t>(width_));
      for (const auto& m : kMoves) {
        if (!canStep(x, y, m[0], m[1])) continue;
        const std::size_t n =
            static_cast<std::size_t>(y + m[1]) * static_cast<std::size_t>(width_) +
            static_cast<std::size_t>(x + m[0]);
        if (components_[n] != -1) continue;
        components_[n] = label;
        stack.push_back(static_cast<std::uint32_t>(n));
      }
    }
    ++label;
  }
  componentsReady_ = true;
  return components_;
}

std::vector<std::size_t> GridPathPlanner::findPath(std::size_t start, std::size_t goal) {
  expansions_ = 0;
  if (start >= passable_.size() || goal >= passable_.size() || !passable(start) || !passable(goal))
    return {};
  if (stamp_.empty()) {
    stamp_.assign(passable_.size(), 0);
    g_.assign(passable_.size(), 0);
    parent_.assign(passable_.size(), 0);
  }
  if (++generation_ == 0) {  // wrapped: forget every stamp
    std::fill(stamp_.begin(), stamp_.end(), 0);
    generation_ = 1;
  }
  const int goalX = static_cast<int>(goal % static_cast<std::size_t>(width_));
  const int goalY = static_cast<int>(goal / static_cast<std::size_t>(width_));
  heap_.clear();
  stamp_[start] = generation_;
  g_[start] = 0;
  parent_[start] = static_cast<std::uint32_t>(start);
  const std::int64_t h0 = heuristic(start, goalX, goalY);
  heap_.push_back(Node{h0, h0, static_cast<std::uint32_t>(start)});
  bool found = false;
  while (!heap_.empty()) {
    std::pop_heap(heap_.begin(), heap_.end(), Later{});
    const Node node = heap_.back();
    heap_.pop_back();
    const std::size_t c = node.cell;
    if (node.f - node.h != g_[c]) continue;  // a stale entry: the cell was reached cheaper since
    ++expansions_;
    if (c == goal) {
      found = true;
      break;
    }
    const int x = static_cast<int>(c % static_cast<std::size_t>(width_));
    const int y = static_cast<int>(c / static_cast<std::size_t>(width_));
    for (const auto& m : kMoves) {
      if (!canStep(x, y, m[0], m[1])) continue;
      const std::size_t n = static_cast<std::size_t>(y + m[1]) * static_cast<std::size_t>(width_) +
                            static_cast<std::size_t>(x + m[0]);
      const std::int64_t g = g_[c] + (m[0] != 0 && m[1] != 0 ? kDiagonal : kStraight);
      if (stamp_[n] == generation_ && g_[n] <= g) continue;
      stamp_[n] = generation_;
      g_[n] = g;
      parent_[n] = static_cast<std::uint32_t>(c);
      const std::int64_t h = heuristic(n, goalX, goalY);
      heap_.push_back(Node{g + h, h, static_cast<std::uint32_t>(n)});
      std::push_heap(heap_.begin(), heap_.end(), Later{});
    }
  }
  if (!found) return {};
  std::vector<std::size_t> path;
  for (std::size_t c = goal;; c = parent_[c]) {
    path.push_back(c);
    if (c == start) break;
  }
  std::reverse(path.begin(), path.end());
  return path;
}

}  // namespace sg
