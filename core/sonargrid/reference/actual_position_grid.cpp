// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/reference/actual_position_grid.h"

#include <algorithm>
#include <cmath>

namespace sg {
namespace {

// Within this many cells of a whole number, a coordinate is on the cell boundary.
constexpr double kSnap = 1e-6;

double snapped(double u) {
  const double r = std::round(u);
  return std::abs(u - r) < kSnap ? r : u;
}

// The cell indices [first, last] of the closed range [lo, hi] of cell coordinates, clipped to
// [0, size - 1]; first > last when nothing is inside the grid.
std::pair<int, int> touchedRange(double lo, double hi, int size) {
  const double first = std::max(0.0, std::ceil(lo) - 1.0);
  const double last = std::min(static_cast<double>(size - 1), std::floor(hi));
  if (!(first <= last)) return {1, 0};
  return {static_cast<int>(first), static_cast<int>(last)};
}

// The cells [first, last] that the open range (lo, hi) overlaps with positive length.
std::pair<int, int> overlappedRange(double lo, double hi, int size) {
  const double first = std::max(0.0, std::floor(lo));
  const double last = std::min(static_cast<double>(size - 1), std::ceil(hi) - 1.0);
  if (!(first <= last)) return {1, 0};
  return {static_cast<int>(first), static_cast<int>(last)};
}

}  // namespace

std::size_t ActualPositionGrid::count() const {
  return static_cast<std::size_t>(std::count(cells.begin(), cells.end(), std::uint8_t{1}));
}

void markSupercover(const GridSpec& spec, const Position& a, const Position& b,
                    std::vector<std::uint8_t>& cells) {
  const double c = spec.cellSize;
  double u0 = snapped((a.x() - spec.origin.x()) / c);
  double v0 = snapped((a.y() - spec.origin.y()) / c);
  double u1 = snapped((b.x() - spec.origin.x()) / c);
  double v1 = snapped((b.y() - spec.origin.y()) / c);
  if (!std::isfinite(u0) || !std::isfinite(v0) || !std::isfinite(u1) || !std::isfinite(v1)) return;
  if (u0 > u1) {
    std::swap(u0, u1);
    std::swap(v0, v1);
  }
  const auto [firstColumn, lastColumn] = touchedRange(u0, u1, spec.width);
  for (int ix = firstColumn; ix <= lastColumn; ++ix) {
    // The part of the segment inside the closed column [ix, ix + 1].
    const double ua = std::max(u0, static_cast<double>(ix));
    const double ub = std::min(u1, static_cast<double>(ix + 1));
    double va = v0;
    double vb = v1;
    if (u1 > u0) {
      const double slope = (v1 - v0) / (u1 - u0);
      va = snapped(v0 + (ua - u0) * slope);
      vb = snapped(v0 + (ub - u0) * slope);
    }
    const auto [firstRow, lastRow] = touchedRange(std::min(va, vb), std::max(va, vb), spec.height);
    for (int iy = firstRow; iy <= lastRow; ++iy) cells[spec.linear(CellIndex(ix, iy))] = 1;
  }
}

void markRasterObstacles(const GridSpec& spec, const ObstacleRaster& raster,
                         std::vector<std::uint8_t>& cells) {
  const GridSpec& r = raster.spec;
  const double c = spec.cellSize;
  for (int ry = 0; ry < r.height; ++ry) {
    const double y0 = r.origin.y() + ry * r.cellSize;
    const auto [firstRow, lastRow] =
        overlappedRange(snapped((y0 - spec.origin.y()) / c),
                        snapped((y0 + r.cellSize - spec.origin.y()) / c), spec.height);
    if (firstRow > lastRow) continue;
    for (int rx = 0; rx < r.width; ++rx) {
      if (raster.cells[r.linear(CellIndex(rx, ry))] != RasterCell::Obstacle) continue;
      const double x0 = r.origin.x() + rx * r.cellSize;
      const auto [firstColumn, lastColumn] =
          overlappedRange(snapped((x0 - spec.origin.x()) / c),
                          snapped((x0 + r.cellSize - spec.origin.x()) / c), spec.width);
      for (int iy = firstRow; iy <= lastRow; ++iy) {
        for (int ix = firstColumn; ix <= lastColumn; ++ix)
          cells[spec.linear(CellIndex(ix, iy))] = 1;
      }
    }
  }
}

ActualPositionGrid ActualPositionGrid::rasterise(const ReferenceMap& reference,
                                                 const GridSpec& spec) {
  ActualPositionGrid apg;
  apg.spec = spec;
  apg.cells.assign(spec.cellCount(), 0);
  for (const ReferenceObject& object : reference.objects) {
    for (const auto& [a, b] : reference.edgesMetres(object)) markSupercover(spec, a, b, apg.cells);
  }
  if (reference.raster) markRasterObstacles(spec, *reference.raster, apg.cells);
  return apg;
}

}  // namespace sg
