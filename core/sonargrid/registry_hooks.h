// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Test hooks into the model and rule registries. The Mapper and the parameter sweep build their
// model and rule by name; these let a test put its own around them (one that fails on purpose on
// a worker thread, tests/core/tst_concurrency.cpp) without a second way to build a mapper.

#include <functional>
#include <memory>

#include "sonargrid/models/sensor_model.h"
#include "sonargrid/rules/update_rule.h"

namespace sg::testing {

// Every model makeSensorModel() (and every rule makeUpdateRule()) makes from now on, configured
// with its defaults, is passed through `wrap`, and what it returns is used. An empty function
// removes the wrapper. Set it only while no mapper is being built.
using SensorModelWrapper =
    std::function<std::unique_ptr<SensorModel>(std::unique_ptr<SensorModel>)>;
using UpdateRuleWrapper = std::function<std::unique_ptr<UpdateRule>(std::unique_ptr<UpdateRule>)>;
void wrapSensorModels(SensorModelWrapper wrap);
void wrapUpdateRules(UpdateRuleWrapper wrap);

// Whether the cone models may evaluate their rows in eight lanes where the CPU has AVX2 (the
// default, true) or must use the baseline's four (false), so that a test on an AVX2 machine checks
// both. Set it only while no mapper is mapping. Returns the previous setting.
bool useWideLanes(bool allowed);

}  // namespace sg::testing
