// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The geometry of a grid: origin (world position of the lower-left corner of cell (0, 0)), square
// cell size and size in cells. Cell (ix, iy) covers [ox + ix*c, ox + (ix+1)*c) x [oy + iy*c, ...);
// row iy grows with world y. Cells are stored row-major: index = iy * width + ix.

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

#include "sonargrid/data/pose.h"

namespace sg {

using CellIndex = Eigen::Vector2i;  // (ix, iy)

// The most cells a grid may have (docs/formats.md, "Grid limits"). A grid this large already holds
// several gigabytes of mapper state, so anything beyond it is a unit mistake or a corrupt pose, not
// a map; and below 2^31 every cell index, and every row * width + column, fits an int.
inline constexpr std::size_t kMaxGridCells = 200'000'000;
static_assert(kMaxGridCells < (std::size_t{1} << 31));

// A grid that cannot be made: an extent or cell size that is not finite, or more cells than
// kMaxGridCells. what() says which numbers, and the limit.
class GridLimitError : public std::runtime_error {
 public:
  explicit GridLimitError(const std::string& message, const std::string& file = {});

  // The same error with "FILE: " in front, for a caller that knows which file the extent came
  // from (the core's Dataset has only the name from the log's header).
  GridLimitError inFile(const std::string& file) const { return GridLimitError(message_, file); }
  const std::string& file() const { return file_; }
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  std::string message_;
};

struct GridSpec {
  Position origin{0.0, 0.0};
  double cellSize = 0.05;  // metres
  int width = 0;
  int height = 0;
  // Where the models count cells from. A grid that grew (Grid::growToCover) goes on counting from
  // the origin it had before: `base` is that origin, and (baseX, baseY) is the cell of this grid
  // that was its cell (0, 0). A position counted from a moved origin can land, to the last bit,
  // on the other side of a cell boundary (the simulated logs' poses and ranges fall on them); so
  // counted, a reading meets the same cells whether the grid grew on the way or was that large
  // from the start (Mapper::append: a live map is bit-identical to a batch map on its limits).
  // A grid that never grew counts from its origin.
  std::optional<Position> base;
  int baseX = 0;
  int baseY = 0;

  std::size_t cellCount() const {
    return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  }
  double widthMetres() const { return width * cellSize; }
  double heightMetres() const { return height * cellSize; }

  bool contains(const CellIndex& c) const {
    return c.x() >= 0 && c.y() >= 0 && c.x() < width && c.y() < height;
  }

  // The cell containing world point p (it may lie outside the grid: check contains()). A point
  // farther than 2^28 cells from the origin, or not finite, gives a cell at +-2^28 on that axis:
  // outside every grid (kMaxGridCells < 2^28 per side), and the sum or difference of two indices
  // still fits an int.
  CellIndex worldToCell(const Position& p) const {
    const Counted at = counted(p);
    return {cellCoordinate(at.u) + at.shiftX, cellCoordinate(at.v) + at.shiftY};
  }
  // A position in cells counted from the base (u, v: their bits do not depend on where the origin
  // is now), and what to add to a whole cell of them to index this grid.
  struct Counted {
    double u, v;
    int shiftX, shiftY;
  };
  Counted counted(const Position& p) const {
    const Position& b = base ? *base : origin;
    return {(p.x() - b.x()) / cellSize, (p.y() - b.y()) / cellSize, baseX, baseY};
  }
  static int cellCoordinate(double cells) {
    constexpr double kFar = 1 << 28;
    if (cells >= kFar) return 1 << 28;
    if (!(cells > -kFar)) return -(1 << 28);  // NaN as well
    return static_cast<int>(std::floor(cells));
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
  // Throws GridLimitError when a bound, the cell size or the margin is not finite (or the cell
  // size not > 0), or the grid would have more than kMaxGridCells cells.
  static GridSpec covering(const Position& lo, const Position& hi, double cellSize, double margin);
};

}  // namespace sg
