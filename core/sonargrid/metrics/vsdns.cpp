// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/metrics/vsdns.h"

#include <cmath>
#include <stdexcept>

namespace sg {

void VsdnsAccumulator::reset(std::size_t cells) {
  count_.assign(cells, 0);
  mean_.assign(cells, 0.0);
  m2_.assign(cells, 0.0);
}

void VsdnsAccumulator::add(std::size_t cell, double value) {
  if (cell >= count_.size()) throw std::out_of_range("VSDNS: cell outside the grid");
  // Welford (1962): exact for repeated values (the delta is then 0), stable for long runs.
  const std::uint32_t n = ++count_[cell];
  const double delta = value - mean_[cell];
  mean_[cell] += delta / n;
  m2_[cell] += delta * (value - mean_[cell]);
}

void VsdnsAccumulator::observe(const Footprint& footprint) {
  for (const CellEvidence& c : footprint.cells) add(c.cell, c.probability);
}

double VsdnsAccumulator::sigma(std::size_t cell) const {
  const std::uint32_t n = count_[cell];
  if (n < 2 || !(m2_[cell] > 0.0)) return 0.0;
  return std::sqrt(m2_[cell] / (n - 1));
}

VsdnsAccumulator::Result VsdnsAccumulator::result() const {
  Result r;
  double sum = 0.0;
  for (std::size_t i = 0; i < count_.size(); ++i) {
    const double s = sigma(i);
    if (s == 0.0) continue;
    sum += s;
    ++r.cellsWithSpread;
  }
  if (r.cellsWithSpread > 0) r.vsdns = sum / static_cast<double>(r.cellsWithSpread);
  return r;
}

}  // namespace sg
