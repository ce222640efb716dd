// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Test hooks into the model and rule registries. The Mapper and the parameter sweep build their
// model and rule by name; these let a test put its own around them (one that fails on purpose on
// a worker thread, tests/core/tst_concurrency.cpp) without a second way to build a mapper.

#include <functional>
#include <memory>

#include "sonargrid/engine/sensor_model.h"
#include "sonargrid/engine/update_rule.h"

namespace sg {
enum class ConeLanes : int;  // lanes.h
}  // namespace sg

namespace sg::testing {

// Every model makeSensorModel() (and every rule makeUpdateRule()) makes from now on, configured
// with its defaults, is passed through `wrap`, and what it returns is used. An empty function
// removes the wrapper. Set it only while no mapper is being built.
using SensorModelWrapper =
    std::function<std::unique_ptr<SensorModel>(std::unique_ptr<SensorModel>)>;
using UpdateRuleWrapper = std::function<std::unique_ptr<UpdateRule>(std::unique_ptr<UpdateRule>)>;
void wrapSensorModels(SensorModelWrapper wrap);
void wrapUpdateRules(UpdateRuleWrapper wrap);

// The widest code the cone models may evaluate their rows with, and the rules' run kernels update
// cells with, where the CPU has it (ConeLanes, lanes.h: the baseline's four lanes, eight with AVX2,
// eight with AVX-512, where the run kernels take eight masked lanes; by default the widest), so
// that a test on a machine with AVX-512 checks all of them. Set it only while no mapper is
// mapping. Returns the previous setting.
ConeLanes limitConeLanes(ConeLanes widest);

// Whether Konolige's float lanes may take λ = 1 − g where a group of lanes lies well short of the
// echo (konolige.cpp, KonoligeShape::allAtFlatEnd), rather than the whole formula, which gives the
// same bits there: a test compares the two. By default they may. Set it only while no mapper is
// mapping. Returns the previous setting.
bool konoligeFlatEnd(bool allowed);

}  // namespace sg::testing
