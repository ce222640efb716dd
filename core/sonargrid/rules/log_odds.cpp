// Clamped log-odds: L ← clamp(L + logit(p) − logit(prior), logit(clamp_min), logit(clamp_max))
// (Thrun, Burgard & Fox 2005 §9.2; the clamping thresholds are OctoMap's defaults).

#include <algorithm>
#include <cmath>

#include "sonargrid/rules/rule_classes.h"

namespace sg {
namespace {
double logit(double p) { return std::log(p / (1.0 - p)); }
// Keeps a model's 0 or 1 from becoming an infinite step; the clamp bounds the layer anyway.
constexpr double kProbabilityFloor = 1e-6;
}  // namespace

const RuleInfo& LogOddsRule::staticInfo() {
  static const RuleInfo info{
      "logodds",
      "Clamped log-odds",
      "Thrun et al. 2005 §9.2; OctoMap AbstractOccupancyOcTree (clamping 0.12 / 0.97)",
      "log-odds L",
      {
          {"prior", "P(H)", "", 0.01, 0.99, 0.5, "Thrun et al. 2005 §9.2 (l₀)", "Occupancy of a cell nobody has seen."},
          {"clamp_min", "p_min", "", 0.001, 0.5, 0.12, "OctoMap default clamping threshold (0.1192)",
           "Lower clamp of a cell's probability; keeps cells able to change."},
          {"clamp_max", "p_max", "", 0.5, 0.999, 0.97, "OctoMap default clamping threshold (0.971)",
           "Upper clamp of a cell's probability."},
      }};
  return info;
}

void LogOddsRule::configure(const ParameterSet& p) {
  priorLogOdds_ = logit(p.get("prior"));
  minLogOdds_ = logit(p.get("clamp_min"));
  maxLogOdds_ = logit(p.get("clamp_max"));
}

void LogOddsRule::reset(std::size_t cells) { logOdds_.assign(cells, priorLogOdds_); }

void LogOddsRule::apply(const Footprint& fp) {
  for (const CellEvidence& c : fp.cells) {
    const double p = std::clamp(c.probability, kProbabilityFloor, 1.0 - kProbabilityFloor);
    double& l = logOdds_[c.cell];
    l = std::clamp(l + logit(p) - priorLogOdds_, minLogOdds_, maxLogOdds_);
  }
}

double LogOddsRule::occupancy(std::size_t i) const { return 1.0 / (1.0 + std::exp(-logOdds_[i])); }

}  // namespace sg
