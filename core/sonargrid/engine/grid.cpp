// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/engine/grid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace sg {

namespace {

// k cells from 0, for an origin on the lattice of whole cells: when a metre holds a whole number n
// of cells (0.05 m: 20), k / n is the double nearest the decimal value, so a grown origin prints as
// -7.6 rather than -7.6000000000000005, as GridSpec::covering() writes it.
double cellMultiple(double k, double cellSize) {
  const double perMetre = std::round(1.0 / cellSize);
  if (perMetre >= 1.0 && std::abs(perMetre * cellSize - 1.0) < 1e-12) return k / perMetre;
  return k * cellSize;
}

// The origin `cells` whole cells below `origin` (negative: above).
double shiftedOrigin(double origin, double cells, double cellSize) {
  const double k = std::round(origin / cellSize);
  if (std::abs(origin / cellSize - k) < 1e-9) return cellMultiple(k - cells, cellSize);
  return origin - cells * cellSize;
}

}  // namespace

Grid::Storage Grid::allocate(std::size_t cells, std::size_t bytes) {
  // Not value-initialised: fillUnknown() writes every cell.
  return Storage(new (std::align_val_t{CellLayout::kAlignment}) std::byte[cells * bytes],
                 AlignedDelete{});
}

void Grid::checkType(bool matches) {
  if (!matches) throw std::logic_error("a rule was given a grid made for another rule's cells");
}

void Grid::throwShared() {
  throw std::logic_error("a grid's cells were to be written while a snapshot shares them");
}

Grid Grid::sharedCells() const {
  Grid g;
  g.spec_ = spec_;
  g.layout_ = layout_;
  g.planes_ = planes_;
  g.readers_ = readers_;
  g.lease_ = Lease(readers_);
  return g;
}

void Grid::unshare() {
  if (!shared()) return;
  // The readers keep the old planes; this grid writes copies.
  for (std::size_t p = 0; p < layout_.planes(); ++p) {
    Storage own = allocate(cellCount(), layout_.bytes(p));
    std::memcpy(own.get(), planes_[p].get(), cellCount() * layout_.bytes(p));
    planes_[p] = std::move(own);
  }
  ownPlanes();
}

Grid::Grid(const GridSpec& spec, const CellLayout& layout) : spec_(spec), layout_(layout) {
  if (spec.width <= 0 || spec.height <= 0 || !(spec.cellSize > 0.0))
    throw GridError("the grid is empty");
  // Every grid, not only a log's fitting one (GridSpec::covering), stays within the core's cap.
  if (cellCount() > static_cast<std::size_t>(kMaxGridCells)) {
    throw GridLimitError("a grid of " + std::to_string(spec.width) + " x " +
                         std::to_string(spec.height) + " cells is more than the grid limit of " +
                         std::to_string(kMaxGridCells) + " cells");
  }
  for (std::size_t p = 0; p < layout_.planes(); ++p)
    planes_[p] = allocate(cellCount(), layout_.bytes(p));
  ownPlanes();
  marks_.resize(cellCount());
  clear();
}

void Grid::fillUnknown(std::size_t plane, std::byte* storage, std::size_t begin,
                       std::size_t end) const {
  if (begin >= end) return;
  const std::size_t bytes = layout_.bytes(plane);
  std::byte* const first = storage + begin * bytes;
  const std::size_t total = (end - begin) * bytes;
  const std::byte* unknown = layout_.unknown(plane);
  if (std::all_of(unknown, unknown + bytes, [](std::byte b) { return b == std::byte{0}; })) {
    std::memset(first, 0, total);
    return;
  }
  // One cell, then doubling copies of what is written: a few large memcpy calls.
  std::memcpy(first, unknown, bytes);
  for (std::size_t done = bytes; done < total;) {
    const std::size_t n = std::min(done, total - done);
    std::memcpy(first + done, first, n);
    done += n;
  }
}

void Grid::clear() {
  if (shared()) {  // the readers keep the old planes
    for (std::size_t p = 0; p < layout_.planes(); ++p)
      planes_[p] = allocate(cellCount(), layout_.bytes(p));
    ownPlanes();
  }
  for (std::size_t p = 0; p < layout_.planes(); ++p)
    fillUnknown(p, planes_[p].get(), 0, cellCount());
  std::fill(marks_.begin(), marks_.end(), std::uint8_t{0});
  allDirty_ = true;
}

void Grid::copyObserved(std::size_t begin, std::size_t end, std::uint8_t* out) const {
  if (end > marks_.size())
    throw std::logic_error("a grid of shared cells was asked which cells were observed");
  const std::uint8_t* const marks = marks_.data();
  for (std::size_t i = begin; i < end; ++i) out[i] = marks[i] & kObserved;
}

Grid::Need Grid::need(const Position& lo, const Position& hi) const {
  // Cells in the present numbering, as doubles: a wild pose must not overflow an int.
  const double c = spec_.cellSize;
  const double x0 = std::floor((lo.x() - spec_.origin.x()) / c);
  const double y0 = std::floor((lo.y() - spec_.origin.y()) / c);
  const double x1 = std::floor((hi.x() - spec_.origin.x()) / c);
  const double y1 = std::floor((hi.y() - spec_.origin.y()) / c);
  const double w = spec_.width, h = spec_.height;
  return {std::max(0.0, -x0), std::max(0.0, x1 - (w - 1)), std::max(0.0, -y0),
          std::max(0.0, y1 - (h - 1))};
}

bool Grid::covers(const Position& lo, const Position& hi) const {
  const Need n = need(lo, hi);
  return n.left == 0 && n.right == 0 && n.bottom == 0 && n.top == 0;
}

bool Grid::growToCover(const Position& lo, const Position& hi) {
  if (!lo.allFinite() || !hi.allFinite()) {
    throw GridLimitError("cannot grow the grid to cover a position that is not finite");
  }
  if (covers(lo, hi)) return false;
  const Need n = need(lo, hi);
  const double needLeft = n.left, needRight = n.right, needBottom = n.bottom, needTop = n.top;
  const double c = spec_.cellSize;
  const double w = spec_.width, h = spec_.height;

  const double cap = static_cast<double>(kMaxGridCells);
  auto cells = [&](double l, double r, double b, double t) { return (w + l + r) * (h + b + t); };
  if (!(cells(needLeft, needRight, needBottom, needTop) <= cap)) {
    std::ostringstream msg;
    msg << "the grid would need " << w + needLeft + needRight << " x " << h + needBottom + needTop
        << " cells of " << c << " m to cover [" << lo.x() << ", " << hi.x() << "] x [" << lo.y()
        << ", " << hi.y() << "] m, more than the limit of " << kMaxGridCells
        << " cells; choose larger cells";
    throw GridLimitError(msg.str());
  }
  // Slack: half the grid's extent along that axis on each side that must grow, so that a robot
  // driving on regrows after as far again; less where that would pass the limit.
  auto slack = [](double need, double size) {
    return need > 0 ? std::max(need, std::ceil(size / 2)) : 0.0;
  };
  double left = slack(needLeft, w), right = slack(needRight, w);
  double bottom = slack(needBottom, h), top = slack(needTop, h);
  if (!(cells(left, right, bottom, top) <= cap)) {
    left = needLeft, right = needRight, bottom = needBottom, top = needTop;
  }

  GridSpec grown = spec_;
  grown.origin = Position(shiftedOrigin(spec_.origin.x(), left, c),
                          shiftedOrigin(spec_.origin.y(), bottom, c));
  // Cells are still counted from where the grid started (GridSpec::base).
  if (!grown.base) grown.base = spec_.origin;
  grown.baseX = spec_.baseX + static_cast<int>(left);
  grown.baseY = spec_.baseY + static_cast<int>(bottom);
  grown.width = static_cast<int>(w + left + right);
  grown.height = static_cast<int>(h + bottom + top);
  const auto dx = static_cast<std::size_t>(left), dy = static_cast<std::size_t>(bottom);
  const auto oldWidth = static_cast<std::size_t>(spec_.width);
  const auto newWidth = static_cast<std::size_t>(grown.width);
  const std::size_t oldRows = static_cast<std::size_t>(spec_.height);

  // Each plane: unknown below and above the old rows and left and right of them, the old rows
  // copied across.
  std::array<Storage, CellLayout::kMaxPlanes> planes;
  for (std::size_t p = 0; p < layout_.planes(); ++p) {
    const std::size_t bytes = layout_.bytes(p);
    planes[p] = allocate(grown.cellCount(), bytes);
    std::byte* const to = planes[p].get();
    const std::byte* const from = planes_[p].get();
    fillUnknown(p, to, 0, dy * newWidth);
    for (std::size_t y = 0; y < oldRows; ++y) {
      const std::size_t row = (y + dy) * newWidth;
      fillUnknown(p, to, row, row + dx);
      std::memcpy(to + (row + dx) * bytes, from + y * oldWidth * bytes, oldWidth * bytes);
      fillUnknown(p, to, row + dx + oldWidth, row + newWidth);
    }
    fillUnknown(p, to, (dy + oldRows) * newWidth, grown.cellCount());
  }
  std::vector<std::uint8_t> marks(grown.cellCount(), 0);
  for (std::size_t y = 0; y < oldRows; ++y) {
    std::memcpy(marks.data() + (y + dy) * newWidth + dx, marks_.data() + y * oldWidth, oldWidth);
  }

  spec_ = grown;
  planes_ = std::move(planes);
  ownPlanes();  // any readers keep the old planes
  marks_ = std::move(marks);
  allDirty_ = true;
  return true;
}

bool Grid::rowDirty(int row) const {
  if (allDirty_) return true;
  const auto width = static_cast<std::size_t>(spec_.width);
  const std::uint8_t* const marks = marks_.data() + static_cast<std::size_t>(row) * width;
  std::uint8_t any = 0;
  for (std::size_t x = 0; x < width; ++x) any |= marks[x];  // no early exit: it vectorises
  return (any & kWritten) != 0;
}

std::vector<int> Grid::dirtyRows() const {
  std::vector<int> rows;
  for (int y = 0; y < spec_.height; ++y)
    if (rowDirty(y)) rows.push_back(y);
  return rows;
}

std::vector<RowBand> Grid::takeDirtyRuns() {
  std::vector<RowBand> runs;
  const int height = spec_.height;
  const auto width = static_cast<std::size_t>(spec_.width);
  for (int y = 0; y < height; ++y) {
    if (!rowDirty(y)) continue;
    if (!runs.empty() && runs.back().end == y)
      ++runs.back().end;
    else
      runs.push_back(RowBand{y, y + 1});
    std::uint8_t* const marks = marks_.data() + static_cast<std::size_t>(y) * width;
    for (std::size_t x = 0; x < width; ++x) marks[x] &= kObserved;
  }
  allDirty_ = false;
  return runs;
}

}  // namespace sg
