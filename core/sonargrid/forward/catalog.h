// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Every way SonarGrid makes a map, for what lists and configures them (the app's choosers and
// menus, project files): the inverse models, each with an update rule (engine/sensor_model.h,
// engine/update_rule.h), and the forward model learned by EM, whose rule is EM itself
// (forward/forward_em.h, docs/forward-model.md). The Mapper knows only the first; a caller maps
// with the forward model where isForwardModel() says so.

#include <string>
#include <vector>

#include "sonargrid/engine/update_rule.h"
#include "sonargrid/params/parameters.h"

namespace sg::forward {

bool isForwardModel(const std::string& model);

// The inverse models' names (sensorModelNames()), then the forward model's.
std::vector<std::string> mapModelNames();
// The update rules' names (updateRuleNames()), then EM's.
std::vector<std::string> mapRuleNames();

// Title, source and the rule its paper pairs it with; ParameterError for an unknown name.
std::string mapModelTitle(const std::string& model);
std::string mapModelSource(const std::string& model);
std::string mapModelPreferredRule(const std::string& model);
std::vector<ParameterSpec> mapModelParameters(const std::string& model);
// A rule's title, source and parameters (EM declares none: the forward model's carry its cap).
std::string mapRuleTitle(const std::string& rule);
std::string mapRuleSource(const std::string& rule);
std::vector<ParameterSpec> mapRuleParameters(const std::string& rule);
// What a map's native layer holds under `rule` (RuleInfo::nativeName; EM: its occupancy m*).
std::string mapRuleNativeName(const std::string& rule);

// Whether the pair makes a map: compatibility() for an inverse model and a rule; the forward
// model goes with EM alone, and EM with the forward model alone.
Compatibility mapCompatibility(const std::string& model, const std::string& rule);
// Every parameter the pair declares, at its default (defaultParameters() for an inverse pair).
// ParameterError for an unknown name or a pair that does not go together.
ParameterSet mapDefaultParameters(const std::string& model, const std::string& rule);

}  // namespace sg::forward
