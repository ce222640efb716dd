// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// An immutable snapshot of a built map: what views, exporters and metrics read. Every update rule
// yields the same layers (docs/models.md; paper 000 §4.3).

#include <cstdint>
#include <string>
#include <vector>

#include "sonargrid/grid_spec.h"

namespace sg {

inline constexpr int kLevels = 16;  // certainty values 0..15 (paper 000 §4.3)

struct OccupancyMap {
  GridSpec spec;
  std::string model;                   // registry names, e.g. "hpf"
  std::string rule;                    // e.g. "addition"
  std::vector<double> probability;     // p(occupied) in [0, 1]; 0.5 where nothing is known
  std::vector<double> native;          // the rule's own value (e.g. log-odds, HIMM CV, Occ−Emp)
  std::vector<std::uint8_t> level;     // 0..15, monotonic in the rule's value
  std::vector<std::uint8_t> filled;    // 1 where occupied evidence beats free evidence
  std::vector<std::uint8_t> observed;  // 1 where at least one reading wrote the cell
  // The rule's own certainty that the cell is occupied, in [0, 1]: HIMM CV / CVmax, addition Occ,
  // Dempster–Shafer m(occ), a probabilistic rule max(0, 2p − 1). What IOP's evidence weight reads
  // (docs/metrics.md). Empty for a map that carries no rule's evidence (unobserved(), a map read
  // from a ROS map): its level stands in.
  std::vector<double> evidence;

  // A map of `spec` where nothing was observed: p 0.5, level 8, nothing filled.
  static OccupancyMap unobserved(const GridSpec& spec);

  std::size_t filledCount() const;
  std::vector<std::size_t> levelHistogram() const;  // kLevels counts over all cells
};

// Level of a probability: round(15 p), the convention every exporter and importer shares.
inline std::uint8_t levelOfProbability(double p) {
  const double v = 15.0 * (p < 0.0 ? 0.0 : (p > 1.0 ? 1.0 : p));
  return static_cast<std::uint8_t>(v + 0.5);
}

}  // namespace sg
