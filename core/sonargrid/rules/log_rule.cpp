// SPDX-License-Identifier: BSD-3-Clause
// Paper 001 §3.3: Emp ← Emp·(1 − pE), Occ ← Occ·(1 + pO), both from 1, combined "using logarithms
// and addition". The transcription prints log10(Emp) * log10(Occ), which is ≤ 0 whatever the
// evidence; the notes fix it as Map = log10(Emp) + log10(Occ), cut to [−2, +2].
// Only the sum is ever read, and it is log10(Emp·Occ), so one layer holds the product Emp·Occ and a
// reading multiplies it by (1 − pE)(1 + pO): one multiplication per cell instead of a logarithm.
// The product is held within [1e-300, 1e300] so it never under- or overflows; that bound is 298
// decades beyond the cut-offs. pE = 1 still makes it 0 for good, as the paper's product does.

#include <algorithm>
#include <cmath>

#include "sonargrid/rules/cell_updates.h"
#include "sonargrid/rules/rule_classes.h"
#include "sonargrid/rules/run_kernels.h"

namespace sg {

const RuleInfo& LogRule::staticInfo() {
  static const RuleInfo info{
      "log",
      "Log update (paper 001)",
      "paper 001 §3.3; sum of logs (docs/models.md)",
      "log10(Emp) + log10(Occ), cut to [cut_min, cut_max]",
      {
          {"cut_min", "Map_min", "", -10.0, -0.1, -2.0, "paper 001 §3.3 (cut-offs [−2, +2])",
           "Map values at or below this are certainly free."},
          {"cut_max", "Map_max", "", 0.1, 10.0, 2.0, "paper 001 §3.3 (cut-offs [−2, +2])",
           "Map values at or above this are certainly occupied."},
      }};
  return info;
}

void LogRule::configure(const ParameterSet& p) {
  cutMin_ = p.get("cut_min");
  cutMax_ = p.get("cut_max");
}

void LogRule::apply(const Footprint& fp, Grid& grid) const {
  LogCell* const cells = grid.cells<LogCell>();
  for (const CellEvidence& c : fp.cells) cellrule::logProduct(c.empty, c.occupied, cells[c.cell]);
}

bool LogRule::applyUniform(const CellEvidence& evidence, std::span<const std::uint32_t> cells,
                           Grid& grid) const {
  // A multiply and three compares a cell: in lanes (run_kernels.h) the gather and scatter cost
  // more than they save.
  LogCell* const g = grid.cells<LogCell>();
  for (const std::uint32_t c : cells) cellrule::logProduct(evidence.empty, evidence.occupied, g[c]);
  return true;
}

void LogRule::applyRuns(const EvidenceRuns& runs, Grid& grid, EvidenceRuns* /*deferred*/) const {
  runs::logProduct(runs, grid.cells<LogCell>());
}

double LogRule::nativeOf(const LogCell& c) const {
  return std::clamp(std::log10(c.product), cutMin_, cutMax_);
}

double LogRule::occupancyOf(const LogCell& c) const {
  // Piecewise linear in the cut value: cut_min ↦ 0, 0 (no net evidence) ↦ 0.5, cut_max ↦ 1.
  const double m = nativeOf(c);
  return m >= 0.0 ? 0.5 + 0.5 * m / cutMax_ : 0.5 - 0.5 * m / cutMin_;
}

}  // namespace sg
