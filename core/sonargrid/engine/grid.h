// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The grid's storage: its limits (GridSpec) and the update rule's state for every cell, plus which
// cells any reading wrote and which rows changed since the last snapshot (docs/models.md, "Batch,
// incremental and live mapping"; the storage / limits / inserter split of Cartographer's Grid2D,
// MapLimits and range data inserter). The grid knows nothing of what its cells mean: the rule
// declares their layout and the value of a cell nobody has seen, and is the only one to read or
// write them.
//
// A grid can grow to cover new readings. It grows by whole cells (the origin moves by a whole
// number of cells), every cell keeps its value at its world position, and the new cells are
// unknown and unobserved. It grows with slack, so a robot that drives on a little at a time makes
// it reallocate a logarithmic number of times, not per scan.
//
// A snapshot shares the grid's cell values rather than copying them (sharedCells()): the planes are
// reference counted, and the grid copies them before writing again while a snapshot still reads
// them (unshare()), so what a snapshot reads never changes (docs/models.md, "Snapshots").

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <new>
#include <span>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "sonargrid/engine/footprint.h"
#include "sonargrid/engine/grid_spec.h"

namespace sg {

// A grid that cannot be made: no cells at all. (Too many cells is GridLimitError, grid_spec.h.)
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

// Rows [begin, end) of a grid; empty when begin == end.
struct RowBand {
  int begin = 0;
  int end = 0;
  bool empty() const { return begin >= end; }
  bool operator==(const RowBand&) const = default;
};

class Grid {
 public:
  // A grid of no cells, to be given a real one by assignment.
  Grid() = default;
  // Every cell unknown and unobserved, every row dirty. Throws GridError for an empty grid. (Its
  // size is the caller's to bound, as GridSpec::covering() does; growth checks kMaxGridCells.)
  Grid(const GridSpec& spec, const CellLayout& layout);
  Grid(Grid&&) noexcept = default;
  Grid& operator=(Grid&&) noexcept = default;
  Grid(const Grid&) = delete;  // sharedCells() shares the values; nothing copies a grid by accident
  Grid& operator=(const Grid&) = delete;

  // A grid of this one's spec, layout and cell values, sharing their storage, for reading them
  // only (from any thread): its cells<Cell>() const give the values as they are now, and it has no
  // marks (observed() and the dirty rows are not its to answer). The values stay as they are for as
  // long as the returned grid lives: this grid copies its planes before writing them while any
  // such grid lives (unshare()).
  Grid sharedCells() const;
  // Whether a grid from sharedCells() still reads the planes. Its end (on any thread) happens
  // before this returns false, so writes that follow do not race its reads.
  bool shared() const { return readers_ && readers_->load(std::memory_order_acquire) > 0; }
  // Makes the planes this grid's own again, copying them while a sharedCells() grid reads them.
  // Whoever writes cells calls it first (the mapper, before each batch of readings); the writing
  // accessors below throw std::logic_error while the planes are shared.
  void unshare();

  const GridSpec& spec() const { return spec_; }
  const CellLayout& layout() const { return layout_; }
  std::size_t cellCount() const { return spec_.cellCount(); }
  // The bytes the grid keeps per cell: every plane's value and the observed/written mark.
  std::size_t bytesPerCell() const {
    std::size_t bytes = sizeof(std::uint8_t);  // marks_
    for (std::size_t p = 0; p < layout_.planes(); ++p) bytes += layout_.bytes(p);
    return bytes;
  }

  // The cells of one plane, row-major as GridSpec::linear() numbers them, typed as the rule
  // declared them. Throws std::logic_error when the layout has no such plane of type Cell (a rule
  // given another rule's grid).
  template <class Cell>
  Cell* cells(std::size_t plane = 0) {
    checkType(layout_.holds<Cell>(plane));
    checkWritable();
    return std::launder(reinterpret_cast<Cell*>(planes_[plane].get()));
  }
  template <class Cell>
  const Cell* cells(std::size_t plane = 0) const {
    checkType(layout_.holds<Cell>(plane));
    return std::launder(reinterpret_cast<const Cell*>(planes_[plane].get()));
  }

  // The cells of a plane of one-byte values, as bytes, whatever the rule's type for them (a rule's
  // byteTransition(), update_rule.h). Throws std::logic_error when the plane's cells are not one
  // byte.
  std::uint8_t* bytes(std::size_t plane = 0) {
    checkType(plane < layout_.planes() && layout_.bytes(plane) == 1);
    checkWritable();
    return reinterpret_cast<std::uint8_t*>(planes_[plane].get());
  }

  // Whether at least one reading wrote the cell.
  bool observed(std::size_t cell) const { return (marks_[cell] & kObserved) != 0; }
  // observed() of cells [begin, end) as 0 or 1 into out[begin, end) (OccupancyMap::observed).
  void copyObserved(std::size_t begin, std::size_t end, std::uint8_t* out) const;

  // Every cell unknown and unobserved again (the spec stays); every row dirty. Shared planes are
  // left to their readers and replaced.
  void clear();

  // Marks the footprint's cells observed and written since the last snapshot (so their rows are
  // dirty); the rule writes the values. One store per cell, as marking them observed alone costs.
  // Several threads may mark footprints whose cells lie in disjoint rows at once.
  void markWritten(const Footprint& footprint) {
    // Four at a time: the loop is a load and a store per cell, and its own overhead was a third.
    const CellEvidence* c = footprint.cells.data();
    const CellEvidence* const end = c + footprint.cells.size();
    std::uint8_t* const marks = marks_.data();
    constexpr std::uint8_t kBoth = kObserved | kWritten;
    for (; end - c >= 4; c += 4) {
      marks[c[0].cell] = kBoth;
      marks[c[1].cell] = kBoth;
      marks[c[2].cell] = kBoth;
      marks[c[3].cell] = kBoth;
    }
    for (; c != end; ++c) marks[c->cell] = kBoth;
  }

  // markWritten() of one cell.
  void markWritten(std::uint32_t cell) { marks_[cell] = kObserved | kWritten; }
  // markWritten() of the listed cells (any cells, in any order), a store each.
  void markWritten(std::span<const std::uint32_t> cells) {
    std::uint8_t* const marks = marks_.data();
    for (const std::uint32_t c : cells) marks[c] = kObserved | kWritten;
  }

  // markWritten() of the listed cells (any cells, in any order), from any number of threads at
  // once, lists that share cells too: each mark is a relaxed atomic store of the one value, a
  // plain byte store on x86. While threads mark this way, nothing else may touch the marks.
  // (Mapper::integrateDirect marks a chunk's cells on the thread that lists them, ahead of the
  // thread that folds them in.) A mark already set is only read: the threads list chunks of one
  // neighbourhood in turn, and a store to a line the other CPU had written took that line from
  // it every time (the history of docs/performance.md, "HIMM: marks read before they are set").
  void markWrittenShared(std::span<const std::uint32_t> cells) {
    std::uint8_t* const marks = marks_.data();
    constexpr std::uint8_t kBoth = kObserved | kWritten;
    for (const std::uint32_t c : cells) {
      std::atomic_ref<std::uint8_t> mark(marks[c]);
      if (mark.load(std::memory_order_relaxed) != kBoth)
        mark.store(kBoth, std::memory_order_relaxed);
    }
  }

  // markWritten() for `count` consecutive cells from `cell` (a run, footprint.h). In stores of
  // eight, four or one marks, inline: a call to memset per run, most of them a few dozen cells,
  // took 4 % of a one-thread re-map of hpf × bayes-recursive.
  void markWritten(std::uint32_t cell, int count) {
    std::uint8_t* const p = marks_.data() + cell;
    const auto n = static_cast<std::size_t>(count);
    constexpr std::uint8_t kBoth = kObserved | kWritten;
    if (n >= 8) {
      constexpr std::uint64_t kEight = 0x0101010101010101ull * kBoth;
      for (std::size_t i = 0; i + 8 < n; i += 8) std::memcpy(p + i, &kEight, 8);
      std::memcpy(p + n - 8, &kEight, 8);  // the last eight, overlapping the ones before
    } else if (n >= 4) {
      constexpr std::uint32_t kFour = 0x01010101u * kBoth;
      std::memcpy(p, &kFour, 4);
      std::memcpy(p + n - 4, &kFour, 4);
    } else if (n > 0) {
      p[0] = kBoth;
      p[n / 2] = kBoth;
      p[n - 1] = kBoth;
    }
  }

  // Whether every cell of the world box [lo, hi] is in the grid.
  bool covers(const Position& lo, const Position& hi) const;
  // Grows the grid, if it must, until it covers the world box [lo, hi], with slack: a side that
  // must grow grows by at least half the grid's size along it, unless that would pass
  // kMaxGridCells. Returns whether the spec changed (then every row is dirty). Throws
  // GridLimitError when the box needs more than kMaxGridCells cells or is not finite; the grid is
  // then unchanged.
  bool growToCover(const Position& lo, const Position& hi);

  // Dirty rows: those written since the last takeDirtyRuns(), or every row after construction,
  // clear() or growth. Finding them reads a byte per cell (the marks), which is what keeps
  // markWritten() at one store per cell; a snapshot then computes only the dirty rows' cells.
  bool rowDirty(int row) const;
  std::vector<int> dirtyRows() const;
  // The dirty rows as runs of consecutive rows, lowest first; afterwards no row is dirty.
  std::vector<RowBand> takeDirtyRuns();

 private:
  struct AlignedDelete {
    void operator()(std::byte* p) const {
      ::operator delete[](p, std::align_val_t{CellLayout::kAlignment});
    }
  };
  // Reference counted: sharedCells() hands the planes to a snapshot.
  using Storage = std::shared_ptr<std::byte[]>;
  // A sharedCells() grid's hold on the planes: counts it among the readers while it lives, and its
  // release (on the reader's thread) is what shared()'s acquire load sees. (Not the planes'
  // reference count, whose load is relaxed and so orders nothing.)
  class Lease {
   public:
    Lease() = default;
    explicit Lease(std::shared_ptr<std::atomic<int>> readers) : readers_(std::move(readers)) {
      readers_->fetch_add(1, std::memory_order_relaxed);  // by the writer's own thread
    }
    Lease(Lease&&) noexcept = default;
    Lease& operator=(Lease&& o) noexcept {
      if (this != &o) {
        release();
        readers_ = std::move(o.readers_);
      }
      return *this;
    }
    Lease(const Lease&) = delete;
    Lease& operator=(const Lease&) = delete;
    ~Lease() { release(); }

   private:
    void release() {
      if (readers_) readers_->fetch_sub(1, std::memory_order_release);
      readers_.reset();
    }
    std::shared_ptr<std::atomic<int>> readers_;
  };
  // New planes nobody reads yet (construction, clear() or unshare() of shared ones, growth).
  void ownPlanes() { readers_ = std::make_shared<std::atomic<int>>(0); }

  // Cells a box lacks on each side.
  struct Need {
    double left, right, bottom, top;
  };
  Need need(const Position& lo, const Position& hi) const;
  static Storage allocate(std::size_t cells, std::size_t bytes);
  static void checkType(bool matches);
  // Throws std::logic_error while a sharedCells() grid reads the planes (unshare() first).
  void checkWritable() const {
    if (shared()) throwShared();
  }
  [[noreturn]] static void throwShared();
  // Writes plane `plane`'s unknown value into cells [begin, end) of `storage`.
  void fillUnknown(std::size_t plane, std::byte* storage, std::size_t begin, std::size_t end) const;

  GridSpec spec_;
  CellLayout layout_;
  std::array<Storage, CellLayout::kMaxPlanes> planes_;
  // Per cell: kObserved once any reading wrote it, kWritten while that is news to a snapshot.
  static constexpr std::uint8_t kObserved = 1, kWritten = 2;
  std::vector<std::uint8_t> marks_;
  bool allDirty_ = true;
  // The count of sharedCells() grids reading planes_ (shared with them), and a sharedCells()
  // grid's own place in that count.
  std::shared_ptr<std::atomic<int>> readers_;
  Lease lease_;
};

}  // namespace sg
