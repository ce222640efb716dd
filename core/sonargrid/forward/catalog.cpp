// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/forward/catalog.h"

#include <algorithm>

#include "sonargrid/engine/mapper.h"
#include "sonargrid/engine/sensor_model.h"
#include "sonargrid/forward/forward_em.h"

namespace sg::forward {

namespace {
constexpr const char* kRuleTitle = "EM (the forward model's own)";
constexpr const char* kSource = "Thrun, Autonomous Robots 15 (2003); docs/forward-model.md";

bool isEm(const std::string& rule) {
  return rule == kRuleName;
}

void checkModel(const std::string& model) {
  const std::vector<std::string> names = mapModelNames();
  if (std::find(names.begin(), names.end(), model) == names.end())
    throw ParameterError("unknown model '" + model + "'");
}
}  // namespace

bool isForwardModel(const std::string& model) {
  return model == kModelName;
}

std::vector<std::string> mapModelNames() {
  std::vector<std::string> names = sensorModelNames();
  names.emplace_back(kModelName);
  return names;
}

std::vector<std::string> mapRuleNames() {
  std::vector<std::string> names = updateRuleNames();
  names.emplace_back(kRuleName);
  return names;
}

std::string mapModelTitle(const std::string& model) {
  checkModel(model);
  return isForwardModel(model) ? kTitle : sensorModelInfo(model).title;
}

std::string mapModelSource(const std::string& model) {
  checkModel(model);
  return isForwardModel(model) ? kSource : sensorModelInfo(model).source;
}

std::string mapModelPreferredRule(const std::string& model) {
  checkModel(model);
  return isForwardModel(model) ? kRuleName : sensorModelInfo(model).preferredRule;
}

std::vector<ParameterSpec> mapModelParameters(const std::string& model) {
  checkModel(model);
  return isForwardModel(model) ? forwardParameterSpecs() : sensorModelInfo(model).parameters;
}

std::string mapRuleTitle(const std::string& rule) {
  if (isEm(rule)) return kRuleTitle;
  if (!makeUpdateRule(rule)) throw ParameterError("unknown rule '" + rule + "'");
  return updateRuleInfo(rule).title;
}

std::string mapRuleSource(const std::string& rule) {
  if (isEm(rule)) return kSource;
  if (!makeUpdateRule(rule)) throw ParameterError("unknown rule '" + rule + "'");
  return updateRuleInfo(rule).source;
}

std::vector<ParameterSpec> mapRuleParameters(const std::string& rule) {
  if (isEm(rule)) return {};
  if (!makeUpdateRule(rule)) throw ParameterError("unknown rule '" + rule + "'");
  return updateRuleInfo(rule).parameters;
}

std::string mapRuleNativeName(const std::string& rule) {
  if (isEm(rule)) return "EM occupancy m";
  if (!makeUpdateRule(rule)) throw ParameterError("unknown rule '" + rule + "'");
  return updateRuleInfo(rule).nativeName;
}

Compatibility mapCompatibility(const std::string& model, const std::string& rule) {
  if (isForwardModel(model) && !isEm(rule)) {
    return {false,
            "the forward model combines the readings by EM over the whole log, not cell by cell "
            "with an update rule (docs/forward-model.md)"};
  }
  if (isEm(rule) && !isForwardModel(model)) {
    return {false,
            "EM learns the forward model's map; an inverse model's evidence is combined by an "
            "update rule"};
  }
  if (isForwardModel(model)) return {};
  return compatibility(model, rule);
}

ParameterSet mapDefaultParameters(const std::string& model, const std::string& rule) {
  checkModel(model);
  const Compatibility c = mapCompatibility(model, rule);
  if (!c.allowed) throw ParameterError(model + " with " + rule + ": " + c.reason);
  if (isForwardModel(model)) return defaultForwardParameters();
  try {
    return defaultParameters(model, rule);
  } catch (const MapperError& e) {
    throw ParameterError(e.what());
  }
}

}  // namespace sg::forward
