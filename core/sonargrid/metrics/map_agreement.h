// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Cell-by-cell agreement of a built map's p(occ) with the ideal map (ideal p: 1 on the APG, 0 in
// free space), over the evaluated cells (ideal known and built observed; see ideal_map.h):
//   correlation (paper 001 §4 benchmark 1, after Baron 1981): Pearson's r × 100;
//   map score (paper 001 benchmark 2, after Martin & Moravec 1996): 100 · mean (p − ideal)²;
//   map score of occupied cells (benchmark 3): the same over cells with p > 0.5 or ideal = 1;
//   Moravec–Blackwell match: Σ (1 + log2(p·q + (1 − p)(1 − q))) bits, q the ideal value;
//   cross-entropy: mean −log2 of the probability given to the true state, in bits per cell;
//   Brier score: mean (p − ideal)² (map score / 100: both names are in use).
// Inside logarithms p is clamped to [kProbabilityFloor, 1 − kProbabilityFloor]: a map may hold an
// exact 0 or 1 (HIMM CV 0, a saturated log-odds cell), and one such wrong cell would make the
// match −∞. With the clamp, match = cells · (1 − cross-entropy) exactly.

#include <cstddef>
#include <optional>

#include "sonargrid/engine/occupancy_map.h"
#include "sonargrid/metrics/ideal_map.h"

namespace sg {

inline constexpr double kProbabilityFloor = 1e-3;

struct MapAgreement {
  std::size_t cellsEvaluated = 0;
  std::size_t cellsOccupiedEvaluated = 0;  // of them, p > 0.5 or ideal occupied
  std::optional<double> correlationPct;    // empty without variance in either map
  std::optional<double> mapScorePct;       // empty without evaluated cells (and below)
  std::optional<double> mapScoreOccupiedPct;
  std::optional<double> matchBits;
  std::optional<double> crossEntropyBits;
  std::optional<double> brier;
};

// Throws std::invalid_argument when the maps are on different grids.
MapAgreement mapAgreement(const OccupancyMap& map, const IdealMap& ideal);

}  // namespace sg
