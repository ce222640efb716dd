// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/grid.h"

#include <algorithm>

namespace sg {

Grid::Storage Grid::allocate(std::size_t cells, std::size_t bytes) {
  // Not value-initialised: fillUnknown() writes every cell.
  return Storage(new (std::align_val_t{CellLayout::kAlignment}) std::byte[cells * bytes]);
}

void Grid::checkType(bool matches) {
  if (!matches) throw std::logic_error("a rule was given a grid made for another rule's cells");
}

Grid::Grid(const GridSpec& spec, const CellLayout& layout) : spec_(spec), layout_(layout) {
  if (spec.width <= 0 || spec.height <= 0 || !(spec.cellSize > 0.0))
    throw GridError("the grid is empty");
  for (std::size_t p = 0; p < layout_.planes(); ++p)
    planes_[p] = allocate(cellCount(), layout_.bytes(p));
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
  for (std::size_t p = 0; p < layout_.planes(); ++p)
    fillUnknown(p, planes_[p].get(), 0, cellCount());
  std::fill(marks_.begin(), marks_.end(), std::uint8_t{0});
}

void Grid::copyObserved(std::size_t begin, std::size_t end, std::uint8_t* out) const {
  const std::uint8_t* const marks = marks_.data();
  for (std::size_t i = begin; i < end; ++i) out[i] = marks[i] & kObserved;
}

}  // namespace sg
