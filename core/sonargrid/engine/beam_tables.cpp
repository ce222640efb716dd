// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/engine/beam_tables.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>
#include <utility>
#include <vector>

#include "sonargrid/base/concurrency.h"

namespace sg {

BeamTables::BeamTables(double cellSize, int radiusCells, int subdivisions)
    : cellSize_(cellSize),
      radius_(radiusCells),
      subdivisions_(subdivisions),
      tableSize_(static_cast<std::size_t>(side()) * static_cast<std::size_t>(side())) {
  // The mirror (View) is exact only where the sub-cell centres are exact in binary.
  if (subdivisions_ < 1 || (subdivisions_ & (subdivisions_ - 1)) != 0)
    throw std::invalid_argument("BeamTables: subdivisions must be a power of two");
  const int count = subdivisions_ * storedRows();
  // kPadding entries past the last table, so that a reader may load a few entries past a row
  // (the last row in memory is the last table's top row, or a mirrored view's bottom row).
  entries_.resize(tableSize_ * static_cast<std::size_t>(count) + kPadding);
  auto fill = [this](int q) {
    const int qx = q % subdivisions_, qy = q / subdivisions_;
    // Sensor at the centre of sub-cell (qx, qy) of cell (0, 0), in cell units.
    const double sx = (qx + 0.5) / subdivisions_;
    const double sy = (qy + 0.5) / subdivisions_;
    Entry* t = entries_.data() + static_cast<std::size_t>(q) * tableSize_;
    for (int dy = -radius_; dy <= radius_; ++dy) {
      for (int dx = -radius_; dx <= radius_; ++dx) {
        const double ex = (dx + 0.5 - sx) * cellSize_;
        const double ey = (dy + 0.5 - sy) * cellSize_;
        Entry& e = t[static_cast<std::size_t>((dy + radius_) * side() + dx + radius_)];
        e.distance = static_cast<float>(std::hypot(ex, ey));
        e.bearing = static_cast<float>(std::atan2(ey, ex));
      }
    }
  };
  // A 10 m sonar at 5 cm cells is 8 tables of 449² entries, some 30 ms of atan2 on one core:
  // the tables are shared out between the policy's threads, each taking every n-th one.
  const unsigned parts = tableSize_ < 10000 ? 1u : std::min(parallelThreads(), unsigned(count));
  runParallel(parts, [&](unsigned k) {
    for (int q = static_cast<int>(k); q < count; q += static_cast<int>(parts)) fill(q);
  });
}

int BeamTables::radiusFor(double cellSize, double reach) {
  // Two cells of slack: the sensor may sit anywhere in its cell and cells are judged by centre.
  const int needed = static_cast<int>(std::ceil(reach / cellSize)) + 2;
  return (needed + kRadiusStep - 1) / kRadiusStep * kRadiusStep;
}

std::shared_ptr<const BeamTables> BeamTables::shared(double cellSize, double reach) {
  static std::mutex mutex;
  // Strong references: a re-map after every slider move must not rebuild the tables. A handful of
  // cell sizes is all a session uses; beyond that the entry with the smallest key goes.
  static std::map<std::pair<double, int>, std::shared_ptr<const BeamTables>> cache;
  constexpr std::size_t kMaxEntries = 4;
  int radius = radiusFor(cellSize, reach);
  std::lock_guard lock(mutex);
  // Any cached table of this cell size that reaches far enough serves.
  for (auto it = cache.lower_bound({cellSize, radius});
       it != cache.end() && it->first.first == cellSize; ++it) {
    return it->second;
  }
  // Outgrown: grow by a quarter at least, so that a slider dragged up its range (a tolerance up to
  // 2 m) rebuilds once, not at every step of kRadiusStep.
  for (const auto& [key, table] : cache) {
    if (key.first != cellSize) continue;
    const int grown = (key.second * 5 / 4 + kRadiusStep - 1) / kRadiusStep * kRadiusStep;
    radius = std::max(radius, grown);
  }
  // The new table serves every reach the smaller ones of its cell size did: they go (a mapper
  // using one keeps it alive).
  std::erase_if(cache, [cellSize](const auto& entry) { return entry.first.first == cellSize; });
  if (cache.size() >= kMaxEntries) cache.erase(cache.begin());
  auto t = std::make_shared<const BeamTables>(cellSize, radius);
  cache[{cellSize, radius}] = t;
  return t;
}

}  // namespace sg
