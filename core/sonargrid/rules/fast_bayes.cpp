// SPDX-License-Identifier: BSD-3-Clause
// Bayes' rule on single-precision cells (FastBayesRule, Precision::Fast; docs/models.md, "Exact
// and fast engines"): the exact rule's step (cell_updates.h) on each cell's p widened to double,
// rounded once to the float cell. The run kernel (run_kernels.cpp, floatBayes) does the same in
// lanes, so every path gives a cell the same bits.

#include "sonargrid/rules/cell_updates.h"
#include "sonargrid/rules/rule_classes.h"
#include "sonargrid/rules/run_kernels.h"

namespace sg {

void FastBayesRule::configure(const ParameterSet& p) {
  priorP_ = p.get("prior");
  prior_ = cellOf(priorP_);
}

double FastBayesRule::readingProbability(const CellEvidence& c) const {
  return input_ == BayesRule::Input::Evidence ? cellrule::bayesEvidence(c.empty, c.occupied)
                                              : static_cast<double>(c.probability);
}

void FastBayesRule::apply(const Footprint& fp, Grid& grid) const {
  BayesFloatCell* const cells = grid.cells<BayesFloatCell>();
  for (const CellEvidence& c : fp.cells) cellrule::floatBayes(readingProbability(c), cells[c.cell]);
}

bool FastBayesRule::applyUniform(const CellEvidence& evidence, std::span<const std::uint32_t> cells,
                                 Grid& grid) const {
  BayesFloatCell* const plane = grid.cells<BayesFloatCell>();
  const double p = readingProbability(evidence);
  for (const std::uint32_t c : cells) cellrule::floatBayes(p, plane[c]);
  return true;
}

void FastBayesRule::applyRuns(const EvidenceRuns& runs, Grid& grid,
                              EvidenceRuns* /*deferred*/) const {
  runs::floatBayes(runs, grid.cells<BayesFloatCell>(), input_ == BayesRule::Input::Likelihood);
}

}  // namespace sg
