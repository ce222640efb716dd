// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/engine/row_bands.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace sg {

std::vector<double> estimatedRowWork(std::span<const Beam> beams, const GridSpec& grid,
                                     double reachCap, bool writesWithoutEcho) {
  const auto height = static_cast<std::size_t>(std::max(grid.height, 0));
  // Each beam adds a constant to a run of rows: a difference array, summed once.
  std::vector<double> change(height + 1, 0.0);
  for (std::size_t i = 0; i < beams.size(); i += kEstimateStride) {
    const Beam& b = beams[i];
    if (!b.echo() && !writesWithoutEcho) continue;
    const double metres = std::min(b.echo() ? b.range : b.maxRange, reachCap);
    const double r = metres / grid.cellSize;
    const GridSpec::Counted at = grid.counted(b.sensor.position);
    const double y = at.v + at.shiftY;
    if (!(r > 0.0) || !std::isfinite(y)) continue;  // nothing, or a pose no row can hold
    const double lo = std::clamp(std::floor(y - r), 0.0, static_cast<double>(height));
    const double hi = std::clamp(std::floor(y + r) + 1.0, 0.0, static_cast<double>(height));
    if (!(hi > lo)) continue;
    const double share = r * r / (hi - lo);
    change[static_cast<std::size_t>(lo)] += share;
    change[static_cast<std::size_t>(hi)] -= share;
  }
  std::vector<double> work(height);
  double running = 0.0;
  for (std::size_t row = 0; row < height; ++row) {
    running += change[row];
    work[row] = std::max(running, 0.0);  // the sum's rounding, never below nothing
  }
  return work;
}

std::vector<RowWindow> balancedBands(std::span<const double> rowWork, unsigned count) {
  const int rows = static_cast<int>(rowWork.size());
  std::vector<RowWindow> bands(std::max(count, 1u));
  double total = 0.0;
  for (const double w : rowWork) total += w;
  const auto n = static_cast<int>(bands.size());
  int row = 0;
  double before = 0.0;  // the work of rows [0, row)
  for (int k = 0; k < n; ++k) {
    bands[k].begin = row;
    if (k + 1 == n) {
      row = rows;
    } else if (!(total > 0.0)) {
      row = std::max(row, static_cast<int>(static_cast<long long>(rows) * (k + 1) / n));
    } else {
      const double target = total * (k + 1) / n;
      while (row < rows && before + rowWork[row] / 2 < target) before += rowWork[row++];
    }
    bands[k].end = row;
  }
  return bands;
}

}  // namespace sg
