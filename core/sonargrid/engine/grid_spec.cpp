// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/engine/grid_spec.h"

#include <algorithm>
#include <sstream>

namespace sg {

namespace {
// k cells from 0. When a metre holds a whole number n of cells (0.05 m: 20), k / n is the double
// nearest the decimal value, so origins print as -2.4 rather than -48 · 0.05 = -2.4000000000000004.
double cellMultiple(double k, double cellSize) {
  const double perMetre = std::round(1.0 / cellSize);
  if (perMetre >= 1.0 && std::abs(perMetre * cellSize - 1.0) < 1e-12) return k / perMetre;
  return k * cellSize;
}

// Six significant digits: enough to recognise a coordinate, short enough to read (1e+12, -0.45).
std::string metres(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

std::string box(const Position& lo, const Position& hi) {
  return "x " + metres(lo.x()) + " to " + metres(hi.x()) + " m, y " + metres(lo.y()) + " to " +
         metres(hi.y()) + " m";
}

// A count of cells computed in double: every digit while a double holds the whole number
// exactly, six significant ones beyond (2e+303 rather than 304 digits).
std::string cells(double n) {
  std::ostringstream out;
  if (n < 9e15) {
    out.precision(0);
    out << std::fixed;
  }
  out << n;
  return out.str();
}
}  // namespace

GridLimitError::GridLimitError(const std::string& message, const std::string& file)
    : std::runtime_error(file.empty() ? message : file + ": " + message),
      file_(file),
      message_(message) {}

GridSpec GridSpec::covering(const Position& lo, const Position& hi, double cellSize,
                            double margin) {
  if (!std::isfinite(cellSize) || cellSize <= 0.0)
    throw GridLimitError("the cell size is " + metres(cellSize) +
                         " m; it must be a positive, finite number of metres");
  if (!std::isfinite(margin))
    throw GridLimitError("the margin " + metres(margin) + " m is not finite");
  if (!lo.allFinite() || !hi.allFinite())
    throw GridLimitError("the extent is not finite: " + box(lo, hi));

  GridSpec spec;
  spec.cellSize = cellSize;
  // Every size is computed in double and checked before it becomes an int: an extent of 1e12 m
  // at 5 cm is 2e13 cells, which no int holds.
  const double kx = std::floor((lo.x() - margin) / cellSize);
  const double ky = std::floor((lo.y() - margin) / cellSize);
  const double x0 = cellMultiple(kx, cellSize);
  const double y0 = cellMultiple(ky, cellSize);
  const double x1 = hi.x() + margin;
  const double y1 = hi.y() + margin;
  const double width = std::max(1.0, std::ceil((x1 - x0) / cellSize));
  const double height = std::max(1.0, std::ceil((y1 - y0) / cellSize));
  const auto limit = static_cast<double>(kMaxGridCells);
  // Each side first, so that the product of two huge sides (inf) is never what decides.
  if (!std::isfinite(x0) || !std::isfinite(y0) || !(width <= limit) || !(height <= limit) ||
      width * height > limit) {
    std::string grown = box(lo, hi);
    if (margin != 0.0) grown += " grown by " + metres(margin) + " m";
    throw GridLimitError(grown + " make a grid of " + cells(width) + " x " + cells(height) +
                         " cells of " + metres(cellSize) + " m, more than the grid limit of " +
                         std::to_string(kMaxGridCells) + " cells");
  }
  spec.origin = Position(x0, y0);
  spec.width = static_cast<int>(width);
  spec.height = static_cast<int>(height);
  return spec;
}

}  // namespace sg
