// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/rules/rule_classes.h"

namespace sg {
namespace {
ParameterSpec priorSpec(const std::string& source) {
  return {"prior", "P(H)", "", 0.01, 0.99, 0.5, source, "Occupancy of a cell nobody has seen."};
}
}  // namespace

const RuleInfo& BayesRule::evidenceInfo() {
  static const RuleInfo info{"bayes",
                             "Bayesian update (paper 001)",
                             "paper 001 §3.2",
                             "p(occupied)",
                             {priorSpec("paper 001 §3.2 (0.5: no information)")}};
  return info;
}

const RuleInfo& BayesRule::likelihoodInfo() {
  static const RuleInfo info{
      "bayes-recursive",
      "Recursive Bayes (paper 002)",
      "paper 002 eqs 5–6 (standard recursive form; docs/models.md)",
      "p(occupied)",
      {priorSpec("paper 002 eq 5 (P(H))")}};
  return info;
}

void BayesRule::configure(const ParameterSet& p) {
  prior_ = p.get("prior");
}

void BayesRule::apply(const Footprint& fp, Grid& grid) const {
  BayesCell* const cells = grid.cells<BayesCell>();
  // One loop per input, so the choice is not made per cell.
  auto update = [cells, &fp](auto probability) {
    for (const CellEvidence& c : fp.cells) {
      const double p = probability(c);
      double& m = cells[c.cell].p;
      const double num = p * m;
      const double den = num + (1.0 - p) * (1.0 - m);
      // den = 0 only when certain evidence meets a certain opposite cell; Bayes is undefined there
      // and the cell keeps its value.
      if (den > 0.0) m = num / den;
    }
  };
  if (input_ == Input::Evidence) {
    // Paper 001 maps evidence to [0, 0.5] (empty) and [0.5, 1] (occupied): P = 0.5 + (pO − pE)/2.
    update([](const CellEvidence& c) {
      return 0.5 + 0.5 * (static_cast<double>(c.occupied) - static_cast<double>(c.empty));
    });
  } else {
    update([](const CellEvidence& c) { return static_cast<double>(c.probability); });
  }
}

}  // namespace sg
