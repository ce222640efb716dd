// SPDX-License-Identifier: BSD-3-Clause
// Clamped log-odds: L ← clamp(L + logit(p) − logit(prior), logit(clamp_min), logit(clamp_max))
// (Thrun, Burgard & Fox 2005 §9.2; the clamping thresholds are OctoMap's defaults). The layer holds
// the odds exp(L): adding logits is multiplying odds and the clamp is monotonic, so it is the same
// rule with a division per cell where the log form needs a logarithm.

#include <algorithm>
#include <cmath>

#include "sonargrid/rules/cell_updates.h"
#include "sonargrid/rules/rule_classes.h"
#include "sonargrid/rules/run_kernels.h"

namespace sg {
namespace {
double odds(double p) {
  return p / (1.0 - p);
}
}  // namespace

const RuleInfo& LogOddsRule::staticInfo() {
  static const RuleInfo info{
      "logodds",
      "Clamped log-odds",
      "Thrun et al. 2005 §9.2; OctoMap AbstractOccupancyOcTree (clamping 0.12 / 0.97)",
      "log-odds L",
      {
          {"prior", "P(H)", "", 0.01, 0.99, 0.5, "Thrun et al. 2005 §9.2 (l₀)",
           "Occupancy of a cell nobody has seen."},
          {"clamp_min", "p_min", "", 0.001, 0.5, 0.12,
           "OctoMap default clamping threshold (0.1192)",
           "Lower clamp of a cell's probability; keeps cells able to change."},
          {"clamp_max", "p_max", "", 0.5, 0.999, 0.97, "OctoMap default clamping threshold (0.971)",
           "Upper clamp of a cell's probability."},
      }};
  return info;
}

void LogOddsRule::configure(const ParameterSet& p) {
  priorOdds_ = odds(p.get("prior"));
  minOdds_ = odds(p.get("clamp_min"));
  maxOdds_ = odds(p.get("clamp_max"));
}

void LogOddsRule::apply(const Footprint& fp, Grid& grid) const {
  LogOddsCell* const cells = grid.cells<LogOddsCell>();
  const double invPrior = 1.0 / priorOdds_;
  for (const CellEvidence& c : fp.cells)
    cellrule::logOdds(c.probability, invPrior, minOdds_, maxOdds_, cells[c.cell]);
}

bool LogOddsRule::applyUniform(const CellEvidence& evidence, std::span<const std::uint32_t> cells,
                               Grid& grid) const {
  runs::logOddsUniform(evidence.probability, cells, grid.cells<LogOddsCell>(), 1.0 / priorOdds_,
                       minOdds_, maxOdds_);
  return true;
}

void LogOddsRule::applyRuns(const EvidenceRuns& runs, Grid& grid,
                            EvidenceRuns* /*deferred*/) const {
  runs::logOdds(runs, grid.cells<LogOddsCell>(), 1.0 / priorOdds_, minOdds_, maxOdds_);
}

double LogOddsRule::nativeOf(const LogOddsCell& c) const {
  return std::log(c.odds);
}

double LogOddsRule::occupancyOf(const LogOddsCell& c) const {
  return c.odds / (1.0 + c.odds);
}

}  // namespace sg
