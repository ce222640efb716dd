// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/rules/cell_updates.h"
#include "sonargrid/rules/rule_classes.h"
#include "sonargrid/rules/run_kernels.h"

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
  static const RuleInfo info{"bayes-recursive",
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
    for (const CellEvidence& c : fp.cells) cellrule::bayes(probability(c), cells[c.cell]);
  };
  if (input_ == Input::Evidence) {
    // Paper 001 maps evidence to [0, 0.5] (empty) and [0.5, 1] (occupied): P = 0.5 + (pO − pE)/2.
    update([](const CellEvidence& c) { return cellrule::bayesEvidence(c.empty, c.occupied); });
  } else {
    update([](const CellEvidence& c) { return static_cast<double>(c.probability); });
  }
}

bool BayesRule::applyUniform(const CellEvidence& evidence, std::span<const std::uint32_t> cells,
                             Grid& grid) const {
  const double p = input_ == Input::Evidence
                       ? cellrule::bayesEvidence(evidence.empty, evidence.occupied)
                       : static_cast<double>(evidence.probability);
  runs::bayesUniform(p, cells, grid.cells<BayesCell>());
  return true;
}

void BayesRule::applyRuns(const EvidenceRuns& runs, Grid& grid, EvidenceRuns* /*deferred*/) const {
  runs::bayes(runs, grid.cells<BayesCell>(), input_ == Input::Likelihood);
}

}  // namespace sg
