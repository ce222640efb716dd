#include "sonargrid/grid_spec.h"

#include <algorithm>

namespace sg {

GridSpec GridSpec::covering(const Position& lo, const Position& hi, double cellSize, double margin) {
  GridSpec spec;
  spec.cellSize = cellSize;
  const double x0 = std::floor((lo.x() - margin) / cellSize) * cellSize;
  const double y0 = std::floor((lo.y() - margin) / cellSize) * cellSize;
  const double x1 = hi.x() + margin;
  const double y1 = hi.y() + margin;
  spec.origin = Position(x0, y0);
  spec.width = std::max(1, static_cast<int>(std::ceil((x1 - x0) / cellSize)));
  spec.height = std::max(1, static_cast<int>(std::ceil((y1 - y0) / cellSize)));
  return spec;
}

}  // namespace sg
