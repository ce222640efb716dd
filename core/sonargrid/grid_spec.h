#pragma once
// The geometry of a grid: origin (world position of the lower-left corner of cell (0, 0)), square
// cell size and size in cells. Cell (ix, iy) covers [ox + ix*c, ox + (ix+1)*c) x [oy + iy*c, ...);
// row iy grows with world y. Cells are stored row-major: index = iy * width + ix.

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <optional>

#include "sonargrid/pose.h"

namespace sg {

using CellIndex = Eigen::Vector2i;  // (ix, iy)

struct GridSpec {
  Position origin{0.0, 0.0};
  double cellSize = 0.05;  // metres
  int width = 0;
  int height = 0;

  std::size_t cellCount() const {
    return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  }
  double widthMetres() const { return width * cellSize; }
  double heightMetres() const { return height * cellSize; }

  bool contains(const CellIndex& c) const {
    return c.x() >= 0 && c.y() >= 0 && c.x() < width && c.y() < height;
  }

  // The cell containing world point p (it may lie outside the grid: check contains()).
  CellIndex worldToCell(const Position& p) const {
    return {static_cast<int>(std::floor((p.x() - origin.x()) / cellSize)),
            static_cast<int>(std::floor((p.y() - origin.y()) / cellSize))};
  }
  Position cellCentre(const CellIndex& c) const {
    return {origin.x() + (c.x() + 0.5) * cellSize, origin.y() + (c.y() + 0.5) * cellSize};
  }
  std::size_t linear(const CellIndex& c) const {
    return static_cast<std::size_t>(c.y()) * static_cast<std::size_t>(width) +
           static_cast<std::size_t>(c.x());
  }
  CellIndex fromLinear(std::size_t i) const {
    return {static_cast<int>(i % static_cast<std::size_t>(width)),
            static_cast<int>(i / static_cast<std::size_t>(width))};
  }

  bool operator==(const GridSpec&) const = default;

  // A grid of `cellSize` covering the box [lo, hi] grown by `margin` on every side. The origin is
  // snapped to a multiple of the cell size so that maps of the same place line up cell for cell.
  static GridSpec covering(const Position& lo, const Position& hi, double cellSize, double margin);
};

}  // namespace sg
