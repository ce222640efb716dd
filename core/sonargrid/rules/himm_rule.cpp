// SPDX-License-Identifier: BSD-3-Clause
// HIMM's histogram grid (paper 000 §2.2): +I⁺ (3) for the echo cell, −I⁻ (1) for the cells before
// it, CV clamped to [0, 15].

#include "sonargrid/rules/rule_classes.h"

namespace sg {

const RuleInfo& HimmRule::staticInfo() {
  static const RuleInfo info{"himm",
                             "HIMM histogram",
                             "paper 000 §2.2",
                             "certainty value CV (0..15)",
                             {
                                 {"increment", "I⁺", "", 1.0, 15.0, 3.0, "paper 000 §2.2 (I⁺ = 3)",
                                  "Added to the echo cell.", true},
                                 {"decrement", "I⁻", "", 0.0, 15.0, 1.0, "paper 000 §2.2 (I⁻ = 1)",
                                  "Taken from each cell before the echo.", true},
                                 {"cv_max", "CV_max", "", 1.0, 15.0, 15.0,
                                  "paper 000 §2.2 (CV_max = 15)", "Ceiling of a cell's CV.", true},
                             }};
  return info;
}

void HimmRule::configure(const ParameterSet& p) {
  increment_ = static_cast<int>(p.get("increment"));
  decrement_ = static_cast<int>(p.get("decrement"));
  cvMax_ = static_cast<int>(p.get("cv_max"));
}

void HimmRule::apply(const Footprint& fp, Grid& grid) const {
  HimmCell* const cells = grid.cells<HimmCell>();
  for (const CellEvidence& c : fp.cells) cells[c.cell].cv = updated(cells[c.cell].cv, c);
}

bool HimmRule::byteTransition(const CellEvidence& evidence,
                              std::array<std::uint8_t, 256>& table) const {
  for (int v = 0; v < 256; ++v) table[v] = updated(static_cast<std::uint8_t>(v), evidence);
  return true;
}

}  // namespace sg
