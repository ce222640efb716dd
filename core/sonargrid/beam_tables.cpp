#include "sonargrid/beam_tables.h"

#include <cmath>
#include <map>
#include <mutex>
#include <utility>

namespace sg {

BeamTables::BeamTables(double cellSize, int radiusCells, int subdivisions)
    : cellSize_(cellSize),
      radius_(radiusCells),
      subdivisions_(subdivisions),
      tableSize_(static_cast<std::size_t>(side()) * static_cast<std::size_t>(side())) {
  // kPadding entries past the last table, so that a reader may load a few entries past a row.
  entries_.resize(tableSize_ * static_cast<std::size_t>(subdivisions_ * subdivisions_) + kPadding);
  for (int qy = 0; qy < subdivisions_; ++qy) {
    for (int qx = 0; qx < subdivisions_; ++qx) {
      // Sensor at the centre of sub-cell (qx, qy) of cell (0, 0), in cell units.
      const double sx = (qx + 0.5) / subdivisions_;
      const double sy = (qy + 0.5) / subdivisions_;
      Entry* t = entries_.data() + static_cast<std::size_t>(qy * subdivisions_ + qx) * tableSize_;
      for (int dy = -radius_; dy <= radius_; ++dy) {
        for (int dx = -radius_; dx <= radius_; ++dx) {
          const double ex = (dx + 0.5 - sx) * cellSize_;
          const double ey = (dy + 0.5 - sy) * cellSize_;
          Entry& e = t[static_cast<std::size_t>((dy + radius_) * side() + dx + radius_)];
          e.distance = static_cast<float>(std::hypot(ex, ey));
          e.bearing = static_cast<float>(std::atan2(ey, ex));
        }
      }
    }
  }
}

std::shared_ptr<const BeamTables> BeamTables::shared(double cellSize, double reach) {
  static std::mutex mutex;
  // Strong references: a re-map after every slider move must not rebuild the tables. A handful of
  // cell sizes is all a session uses; beyond that the entry with the smallest key goes.
  static std::map<std::pair<double, int>, std::shared_ptr<const BeamTables>> cache;
  constexpr std::size_t kMaxEntries = 4;
  // Two cells of slack: the sensor may sit anywhere in its cell and cells are judged by centre.
  const int radius = static_cast<int>(std::ceil(reach / cellSize)) + 2;
  std::lock_guard lock(mutex);
  // Any cached table of this cell size that reaches far enough serves.
  for (auto it = cache.lower_bound({cellSize, radius});
       it != cache.end() && it->first.first == cellSize; ++it) {
    return it->second;
  }
  if (cache.size() >= kMaxEntries) cache.erase(cache.begin());
  auto t = std::make_shared<const BeamTables>(cellSize, radius);
  cache[{cellSize, radius}] = t;
  return t;
}

}  // namespace sg
