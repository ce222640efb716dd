// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Map entropy (Martin & Moravec 1996, "Robot Evidence Grids", CMU-RI-TR-96-06; named by paper
// 002): the information a map still lacks, summed over its cells as independent binary variables,
//   H(cell) = −p log2 p − (1 − p) log2 (1 − p)   bits   (0 log2 0 taken as 0),
// so a cell at p = 0.5 holds 1 bit of uncertainty and a cell at 0 or 1 none. Lower is better: a
// map that has made up its mind. It rewards confidence, not truth (a confidently wrong map scores
// well), which is why docs/metrics.md lists it with the goodness measures that need no reference.

#include <cstddef>
#include <optional>

#include "sonargrid/engine/occupancy_map.h"

namespace sg {

struct MapEntropy {
  double totalBits = 0.0;     // Σ H over every cell of the grid (never observed: 1 bit each)
  double observedBits = 0.0;  // Σ H over the observed cells
  std::size_t cellsObserved = 0;
  std::optional<double> meanBits;  // observedBits / cellsObserved; empty when nothing observed
};

// The entropy of one cell at probability p, clamped to [0, 1].
double cellEntropyBits(double p);

// Throws std::invalid_argument when the layers do not match the grid.
MapEntropy mapEntropy(const OccupancyMap& map);

}  // namespace sg
