// SPDX-License-Identifier: BSD-3-Clause
#include <algorithm>
#include <stdexcept>

#include "sonargrid/rules/cell_updates.h"
#include "sonargrid/rules/rule_classes.h"
#include "sonargrid/testing/registry_hooks.h"

namespace sg {
namespace {
testing::UpdateRuleWrapper& ruleWrapper() {
  static testing::UpdateRuleWrapper wrap;
  return wrap;
}
}  // namespace

void testing::wrapUpdateRules(UpdateRuleWrapper wrap) {
  ruleWrapper() = std::move(wrap);
}

std::vector<std::string> updateRuleNames() {
  return {"addition", "bayes", "bayes-recursive", "log", "logodds", "himm", "dempster-shafer"};
}

Precision precisionFromName(const std::string& name) {
  if (name == "exact") return Precision::Exact;
  if (name == "fast") return Precision::Fast;
  throw std::invalid_argument("unknown precision '" + name + "' (exact or fast)");
}

bool hasFastCells(const std::string& model, const std::string& rule) {
  return model != "himm" && (rule == "bayes" || rule == "bayes-recursive");
}

std::unique_ptr<UpdateRule> makeUpdateRule(const std::string& name, Precision precision) {
  std::unique_ptr<UpdateRule> r;
  if (precision == Precision::Fast && name == "bayes")
    r = std::make_unique<FastBayesRule>(BayesRule::Input::Evidence);
  else if (precision == Precision::Fast && name == "bayes-recursive")
    r = std::make_unique<FastBayesRule>(BayesRule::Input::Likelihood);
  else if (name == "addition")
    r = std::make_unique<AdditionRule>();
  else if (name == "bayes")
    r = std::make_unique<BayesRule>(BayesRule::Input::Evidence);
  else if (name == "bayes-recursive")
    r = std::make_unique<BayesRule>(BayesRule::Input::Likelihood);
  else if (name == "log")
    r = std::make_unique<LogRule>();
  else if (name == "logodds")
    r = std::make_unique<LogOddsRule>();
  else if (name == "himm")
    r = std::make_unique<HimmRule>();
  else if (name == "dempster-shafer")
    r = std::make_unique<DempsterShaferRule>();
  if (r) r->configure(ParameterSet(r->info().parameters));
  if (r && ruleWrapper()) r = ruleWrapper()(std::move(r));
  return r;
}

const RuleInfo& updateRuleInfo(const std::string& name) {
  if (name == "addition") return AdditionRule::staticInfo();
  if (name == "bayes") return BayesRule::evidenceInfo();
  if (name == "bayes-recursive") return BayesRule::likelihoodInfo();
  if (name == "log") return LogRule::staticInfo();
  if (name == "logodds") return LogOddsRule::staticInfo();
  if (name == "himm") return HimmRule::staticInfo();
  if (name == "dempster-shafer") return DempsterShaferRule::staticInfo();
  throw std::invalid_argument("unknown update rule '" + name + "'");
}

Compatibility compatibility(const std::string& model, const std::string& rule) {
  // docs/models.md carries this table with the same reasons.
  if (rule == "himm" && model != "himm") {
    return {false,
            "the HIMM histogram adds I+ to one cell per reading on the acoustic axis (paper 000 "
            "§2.2); a cone "
            "model writes hundreds of cells per reading and would raise the whole arc"};
  }
  if (model == "himm" && rule == "addition") {
    return {false,
            "probability addition normalises each reading's occupied arc to sum 1 (paper 001 "
            "§3.1); HIMM's arc "
            "is one cell, so every echo would set Occ to 1"};
  }
  return {};
}

std::string unusedParameterReason(const std::string& model, const std::string& rule,
                                  const std::string& parameter) {
  if (model == "himm" && rule == "himm" && (parameter == "p_hit" || parameter == "p_miss")) {
    return "the himm rule adds I+ to the echo cell and subtracts I- before it whatever the "
           "probabilities (paper 000 §2.2): it only needs p_hit above 0.5 and p_miss below, which "
           "their ranges give; the probabilistic rules read them";
  }
  return {};
}

void UpdateRule::applyRuns(const EvidenceRuns& runs, Grid& grid, EvidenceRuns* deferred) const {
  if (needsTotals()) {
    // Every run deferred as it is, its values copied after those deferred before (no room past
    // them: the default applyDeferred() reads them one at a time).
    std::size_t used = deferred->valuesEnd();
    for (const EvidenceRuns::Run& run : runs.runs) {
      const auto count = static_cast<std::size_t>(run.count);
      for (auto* values : {&deferred->empty, &deferred->occupied, &deferred->probability})
        if (values->size() < used + count) values->resize(used + count);
      std::copy_n(runs.empty.data() + run.first, count, deferred->empty.data() + used);
      std::copy_n(runs.occupied.data() + run.first, count, deferred->occupied.data() + used);
      std::copy_n(runs.probability.data() + run.first, count, deferred->probability.data() + used);
      deferred->runs.push_back({run.cell, run.count, static_cast<std::uint32_t>(used)});
      used += count;
    }
    return;
  }
  thread_local Footprint part;
  part.clear();
  for (const EvidenceRuns::Run& run : runs.runs)
    for (int k = 0; k < run.count; ++k) part.cells.push_back(cellrule::cellOfRun(runs, run, k));
  apply(part, grid);
}

void UpdateRule::applyDeferred(const EvidenceRuns& deferred, std::size_t firstRun,
                               std::size_t endRun, const FootprintTotals& totals,
                               Grid& grid) const {
  thread_local Footprint part;
  part.clear();
  for (std::size_t r = firstRun; r < endRun; ++r) {
    const EvidenceRuns::Run& run = deferred.runs[r];
    for (int k = 0; k < run.count; ++k) part.cells.push_back(cellrule::cellOfRun(deferred, run, k));
  }
  applyPart(part, totals, grid);
}

}  // namespace sg
