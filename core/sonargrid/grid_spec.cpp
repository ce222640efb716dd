#include "sonargrid/grid_spec.h"

#include <algorithm>

namespace sg {

namespace {
// k cells from 0. When a metre holds a whole number n of cells (0.05 m: 20), k / n is the double
// nearest the decimal value, so origins print as -2.4 rather than -48 · 0.05 = -2.4000000000000004.
double cellMultiple(double k, double cellSize) {
  const double perMetre = std::round(1.0 / cellSize);
  if (perMetre >= 1.0 && std::abs(perMetre * cellSize - 1.0) < 1e-12) return k / perMetre;
  return k * cellSize;
}
}  // namespace

GridSpec GridSpec::covering(const Position& lo, const Position& hi, double cellSize,
                            double margin) {
  GridSpec spec;
  spec.cellSize = cellSize;
  const double x0 = cellMultiple(std::floor((lo.x() - margin) / cellSize), cellSize);
  const double y0 = cellMultiple(std::floor((lo.y() - margin) / cellSize), cellSize);
  const double x1 = hi.x() + margin;
  const double y1 = hi.y() + margin;
  spec.origin = Position(x0, y0);
  spec.width = std::max(1, static_cast<int>(std::ceil((x1 - x0) / cellSize)));
  spec.height = std::max(1, static_cast<int>(std::ceil((y1 - y0) / cellSize)));
  return spec;
}

}  // namespace sg
