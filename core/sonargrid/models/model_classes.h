// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The concrete sensor models, as the registry reaches them. Each class lives in its own .cpp file.

#include <memory>

#include "sonargrid/engine/sensor_model.h"

namespace sg {

std::unique_ptr<SensorModel> makeHpfModel();
std::unique_ptr<SensorModel> makeKonoligeModel();
std::unique_ptr<SensorModel> makeMurphyModel();
std::unique_ptr<SensorModel> makeParameterizedModel();
std::unique_ptr<SensorModel> makeHimmModel();

const ModelInfo& hpfModelInfo();
const ModelInfo& konoligeModelInfo();
const ModelInfo& murphyModelInfo();
const ModelInfo& parameterizedModelInfo();
const ModelInfo& himmModelInfo();

}  // namespace sg
