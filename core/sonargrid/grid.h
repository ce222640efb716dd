// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The grid's storage: its limits (GridSpec) and the update rule's state for every cell, plus which
// cells any reading wrote (the storage / limits / inserter split of Cartographer's Grid2D,
// MapLimits and range data inserter). The grid knows nothing of what its cells mean: the rule
// declares their layout and the value of a cell nobody has seen, and is the only one to read or
// write them.

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <new>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "sonargrid/footprint.h"
#include "sonargrid/grid_spec.h"

namespace sg {

class GridError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// What a rule keeps per cell, in one or more planes: each plane holds one value of a trivially
// copyable type per cell, and says its value in a cell nobody has seen. Parts of a cell's state
// that a reading writes one at a time go in separate planes, so that a plane's cache lines hold
// more of the cells a footprint touches (probability addition: a cone's cell gets free or occupied
// evidence, seldom both); parts always read and written together go in one (Dempster–Shafer).
class CellLayout {
 public:
  static constexpr std::size_t kMaxPlanes = 4;
  static constexpr std::size_t kMaxBytes = 32;   // of one plane's value
  static constexpr std::size_t kAlignment = 64;  // of each plane's storage: a cache line

  CellLayout() = default;  // no planes

  // One plane per argument, its type and its unknown value.
  template <class... Cells>
  static CellLayout of(const Cells&... unknown) {
    static_assert(sizeof...(Cells) >= 1 && sizeof...(Cells) <= kMaxPlanes);
    CellLayout layout;
    (layout.add(unknown), ...);
    return layout;
  }

  std::size_t planes() const { return count_; }
  std::size_t bytes(std::size_t plane) const { return planes_[plane].bytes; }
  const std::byte* unknown(std::size_t plane) const { return planes_[plane].unknown.data(); }
  template <class Cell>
  bool holds(std::size_t plane) const {
    return plane < count_ && planes_[plane].type == &typeTag<Cell>;
  }

 private:
  // One address per cell type: which type a plane was made for, without RTTI.
  template <class Cell>
  static constexpr char typeTag = 0;

  template <class Cell>
  void add(const Cell& unknown) {
    static_assert(std::is_trivially_copyable_v<Cell>);
    static_assert(sizeof(Cell) <= kMaxBytes && alignof(Cell) <= kAlignment);
    Plane& p = planes_[count_++];
    p.type = &typeTag<Cell>;
    p.bytes = sizeof(Cell);
    std::memcpy(p.unknown.data(), &unknown, sizeof(Cell));
  }

  struct Plane {
    const void* type = nullptr;
    std::size_t bytes = 0;
    std::array<std::byte, kMaxBytes> unknown{};
  };
  std::array<Plane, kMaxPlanes> planes_{};
  std::size_t count_ = 0;
};

class Grid {
 public:
  // A grid of no cells, to be given a real one by assignment.
  Grid() = default;
  // Every cell unknown and unobserved. Throws GridError for an empty grid.
  Grid(const GridSpec& spec, const CellLayout& layout);
  Grid(Grid&&) noexcept = default;
  Grid& operator=(Grid&&) noexcept = default;

  const GridSpec& spec() const { return spec_; }
  const CellLayout& layout() const { return layout_; }
  std::size_t cellCount() const { return spec_.cellCount(); }

  // The cells of one plane, row-major as GridSpec::linear() numbers them, typed as the rule
  // declared them. Throws std::logic_error when the layout has no such plane of type Cell (a rule
  // given another rule's grid).
  template <class Cell>
  Cell* cells(std::size_t plane = 0) {
    checkType(layout_.holds<Cell>(plane));
    return std::launder(reinterpret_cast<Cell*>(planes_[plane].get()));
  }
  template <class Cell>
  const Cell* cells(std::size_t plane = 0) const {
    checkType(layout_.holds<Cell>(plane));
    return std::launder(reinterpret_cast<const Cell*>(planes_[plane].get()));
  }

  // Whether at least one reading wrote the cell.
  bool observed(std::size_t cell) const { return (marks_[cell] & kObserved) != 0; }
  // observed() of cells [begin, end) as 0 or 1 into out[begin, end) (OccupancyMap::observed).
  void copyObserved(std::size_t begin, std::size_t end, std::uint8_t* out) const;

  // Every cell unknown and unobserved again.
  void clear();

  // Marks the footprint's cells observed; the rule writes the values. Several threads may mark
  // footprints whose cells lie in disjoint rows at once.
  void markWritten(const Footprint& footprint) {
    // Four at a time: the loop is a load and a store per cell, and its own overhead was a third.
    const CellEvidence* c = footprint.cells.data();
    const CellEvidence* const end = c + footprint.cells.size();
    std::uint8_t* const marks = marks_.data();
    constexpr std::uint8_t kBoth = kObserved;
    for (; end - c >= 4; c += 4) {
      marks[c[0].cell] = kBoth;
      marks[c[1].cell] = kBoth;
      marks[c[2].cell] = kBoth;
      marks[c[3].cell] = kBoth;
    }
    for (; c != end; ++c) marks[c->cell] = kBoth;
  }

 private:
  struct AlignedDelete {
    void operator()(std::byte* p) const {
      ::operator delete[](p, std::align_val_t{CellLayout::kAlignment});
    }
  };
  using Storage = std::unique_ptr<std::byte[], AlignedDelete>;

  static Storage allocate(std::size_t cells, std::size_t bytes);
  static void checkType(bool matches);
  // Writes plane `plane`'s unknown value into cells [begin, end) of `storage`.
  void fillUnknown(std::size_t plane, std::byte* storage, std::size_t begin, std::size_t end) const;

  GridSpec spec_;
  CellLayout layout_;
  std::array<Storage, CellLayout::kMaxPlanes> planes_;
  // Per cell: kObserved once any reading wrote it.
  static constexpr std::uint8_t kObserved = 1;
  std::vector<std::uint8_t> marks_;
};

}  // namespace sg
