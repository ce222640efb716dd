// Paper 001 §3.3: Emp ← Emp·(1 − pE), Occ ← Occ·(1 + pO), both from 1, combined "using logarithms
// and addition". The transcription prints log10(Emp) * log10(Occ), which is ≤ 0 whatever the
// evidence; the notes fix it as Map = log10(Emp) + log10(Occ), cut to [−2, +2]. Keeping the two
// layers as sums of logs is the same quantity without underflow after thousands of readings.

#include <algorithm>
#include <cmath>

#include "sonargrid/rules/rule_classes.h"

namespace sg {

const RuleInfo& LogRule::staticInfo() {
  static const RuleInfo info{
      "log",
      "Log update (paper 001)",
      "paper 001 §3.3; sum of logs per notes/models-and-metrics.md",
      "log10(Emp) + log10(Occ), cut to [cut_min, cut_max]",
      {
          {"cut_min", "min", "", -10.0, -0.1, -2.0, "paper 001 §3.3 (cut-offs [−2, +2])",
           "Map values at or below this are certainly free."},
          {"cut_max", "max", "", 0.1, 10.0, 2.0, "paper 001 §3.3 (cut-offs [−2, +2])",
           "Map values at or above this are certainly occupied."},
      }};
  return info;
}

void LogRule::configure(const ParameterSet& p) {
  cutMin_ = p.get("cut_min");
  cutMax_ = p.get("cut_max");
}

void LogRule::reset(std::size_t cells) {
  logEmp_.assign(cells, 0.0);
  logOcc_.assign(cells, 0.0);
}

void LogRule::apply(const Footprint& fp) {
  for (const CellEvidence& c : fp.cells) {
    // pE = 1 makes Emp 0 (−∞ in logs) for good, exactly as the product form would.
    if (c.empty > 0.0) logEmp_[c.cell] += std::log10(1.0 - c.empty);
    if (c.occupied > 0.0) logOcc_[c.cell] += std::log10(1.0 + c.occupied);
  }
}

double LogRule::native(std::size_t i) const { return std::clamp(logEmp_[i] + logOcc_[i], cutMin_, cutMax_); }

double LogRule::occupancy(std::size_t i) const {
  // Piecewise linear in the cut value: cut_min ↦ 0, 0 (no net evidence) ↦ 0.5, cut_max ↦ 1.
  const double m = native(i);
  return m >= 0.0 ? 0.5 + 0.5 * m / cutMax_ : 0.5 - 0.5 * m / cutMin_;
}

}  // namespace sg
