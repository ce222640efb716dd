// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// An immutable snapshot of a built map: what views, exporters and metrics read. Every update rule
// yields the same layers (docs/models.md; paper 000 §4.3).
//
// A mapped snapshot keeps what a view draws, the level and the observed flag, a byte each per
// cell; its p(occupied), native value, evidence and filled flag are read from the rule's cell
// values, which the snapshot shares with the mapper's grid (grid.h, sharedCells()) instead of
// copying (docs/models.md, "Snapshots"). A map made by hand or read from a file holds those layers
// as values instead (MapLayer).

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <iterator>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "sonargrid/engine/grid_spec.h"

namespace sg {

inline constexpr int kLevels = 16;  // certainty values 0..15 (paper 000 §4.3)

// The layers a rule derives from its cell values.
enum class DerivedLayer { Probability, Native, Evidence, Filled };

// What a rule says of each cell of a grid (update_rule.h gives it from a rule and the cell values
// a snapshot shares). Read from any number of threads at once.
class DerivedCells {
 public:
  virtual ~DerivedCells() = default;
  // One cell's value of `layer` (Filled: 0 or 1).
  virtual double value(DerivedLayer layer, std::size_t cell) const = 0;
  // Cells [begin, end) of `layer` into out[0, end − begin): doubles, or bytes for Filled.
  virtual void fill(DerivedLayer layer, std::size_t begin, std::size_t end, void* out) const = 0;
};

// One layer of a snapshot, T per cell: its values, or (a mapped snapshot's) read cell by cell from
// the rule (DerivedCells), which keeps no copy of them. Reading is the same either way. Writing
// (the non-const operator[], data(), the vector-like mutators) first makes a derived layer hold
// its values, as a copy that then belongs to this map alone.
template <class T>
class MapLayer {
 public:
  MapLayer() = default;
  MapLayer(std::vector<T> values) : values_(std::move(values)) {}  // NOLINT: a layer of values
  MapLayer(std::initializer_list<T> values) : values_(values) {}
  // `size` cells of `layer` as `cells` derives them.
  MapLayer(std::shared_ptr<const DerivedCells> cells, DerivedLayer layer, std::size_t size)
      : cells_(std::move(cells)), layer_(layer), size_(size) {}

  MapLayer& operator=(std::vector<T> values) {
    values_ = std::move(values);
    cells_.reset();
    return *this;
  }
  MapLayer& operator=(std::initializer_list<T> values) { return *this = std::vector<T>(values); }

  std::size_t size() const { return cells_ ? size_ : values_.size(); }
  bool empty() const { return size() == 0; }
  // Whether the values are read from a rule's cells rather than held.
  bool derived() const { return cells_ != nullptr; }

  T operator[](std::size_t i) const {
    return cells_ ? static_cast<T>(cells_->value(layer_, i)) : values_[i];
  }
  T& operator[](std::size_t i) {
    hold();
    return values_[i];
  }
  T* data() {
    hold();
    return values_.data();
  }
  // Every value, in order (a copy).
  std::vector<T> values() const {
    if (!cells_) return values_;
    std::vector<T> out(size_);
    if (size_ > 0) cells_->fill(layer_, 0, size_, out.data());
    return out;
  }

  void resize(std::size_t n) {
    hold();
    values_.resize(n);
  }
  void resize(std::size_t n, const T& value) {
    hold();
    values_.resize(n, value);
  }
  void assign(std::size_t n, const T& value) { *this = std::vector<T>(n, value); }
  void push_back(const T& value) {
    hold();
    values_.push_back(value);
  }
  void pop_back() {
    hold();
    values_.pop_back();
  }
  void clear() { *this = std::vector<T>(); }

  // Values in order, by index (as operator[] const reads them), each given by value.
  class const_iterator {
   public:
    using iterator_category = std::input_iterator_tag;
    using value_type = T;
    using difference_type = std::ptrdiff_t;
    using pointer = void;
    using reference = T;
    const_iterator() = default;
    const_iterator(const MapLayer* layer, std::size_t i) : layer_(layer), i_(i) {}
    T operator*() const { return (*layer_)[i_]; }
    const_iterator& operator++() {
      ++i_;
      return *this;
    }
    const_iterator operator++(int) {
      const_iterator before = *this;
      ++i_;
      return before;
    }
    bool operator==(const const_iterator& o) const { return layer_ == o.layer_ && i_ == o.i_; }
    bool operator!=(const const_iterator& o) const { return !(*this == o); }

   private:
    const MapLayer* layer_ = nullptr;
    std::size_t i_ = 0;
  };
  const_iterator begin() const { return {this, 0}; }
  const_iterator end() const { return {this, size()}; }

  // Same size and the same bits in every value (a NaN equals itself; 0 and −0 differ): what
  // "bit-identical maps" means.
  bool identical(const MapLayer& o) const {
    if (size() != o.size()) return false;
    for (std::size_t i = 0; i < size(); ++i) {
      const T x = (*this)[i], y = o[i];
      if (std::memcmp(&x, &y, sizeof(T)) != 0) return false;
    }
    return true;
  }
  // Same size and equal values (==, cell by cell).
  bool operator==(const MapLayer& o) const {
    if (size() != o.size()) return false;
    for (std::size_t i = 0; i < size(); ++i)
      if (!((*this)[i] == o[i])) return false;
    return true;
  }

 private:
  void hold() {
    if (!cells_) return;
    values_ = values();
    cells_.reset();
  }

  std::vector<T> values_;
  std::shared_ptr<const DerivedCells> cells_;
  DerivedLayer layer_ = DerivedLayer::Probability;
  std::size_t size_ = 0;
};

struct OccupancyMap {
  GridSpec spec;
  std::string model;                   // registry names, e.g. "hpf"
  std::string rule;                    // e.g. "addition"
  MapLayer<double> probability;        // p(occupied) in [0, 1]; 0.5 where nothing is known
  MapLayer<double> native;             // the rule's own value (e.g. log-odds, HIMM CV, Occ−Emp)
  std::vector<std::uint8_t> level;     // 0..15, monotonic in the rule's value
  MapLayer<std::uint8_t> filled;       // 1 where occupied evidence beats free evidence
  std::vector<std::uint8_t> observed;  // 1 where at least one reading wrote the cell
  // The rule's own certainty that the cell is occupied, in [0, 1]: HIMM CV / CVmax, addition Occ,
  // Dempster–Shafer m(occ), a probabilistic rule max(0, 2p − 1). What IOP's evidence weight reads
  // (docs/metrics.md). Empty for a map that carries no rule's evidence (unobserved(), a map read
  // from a ROS map): its level stands in.
  MapLayer<double> evidence;

  // A map of `spec` where nothing was observed: p 0.5, level 8, nothing filled.
  static OccupancyMap unobserved(const GridSpec& spec);

  // The four derived layers read from `cells` (a mapped snapshot's), over spec.cellCount() cells;
  // with nullptr, the four layers empty.
  void derive(const std::shared_ptr<const DerivedCells>& cells);
  // Whether any layer is read from a rule's cells.
  bool derived() const;
  // Every layer held as values (a copy of what the rule's cells say), the rule's cells let go.
  void hold();
  // The bytes the map itself keeps per cell: its held layers' values (a derived layer keeps none;
  // the cells it reads belong to the grid, Grid::bytesPerCell()).
  std::size_t bytesPerCell() const;

  std::size_t filledCount() const;
  std::vector<std::size_t> levelHistogram() const;  // kLevels counts over all cells
};

// Level of a probability: round(15 p), the convention every exporter and importer shares.
inline std::uint8_t levelOfProbability(double p) {
  const double v = 15.0 * (p < 0.0 ? 0.0 : (p > 1.0 ? 1.0 : p));
  return static_cast<std::uint8_t>(v + 0.5);
}

}  // namespace sg
