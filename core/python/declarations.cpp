// SPDX-License-Identifier: BSD-3-Clause
#include "declarations.h"

#include <string>

#include "sonargrid/engine/sensor_model.h"
#include "sonargrid/engine/update_rule.h"
#include "sonargrid/forward/forward_em.h"

namespace py = pybind11;

namespace sg::python {

py::list parameterList(const std::vector<ParameterSpec>& specs) {
  py::list list;
  for (const ParameterSpec& s : specs) {
    py::dict d;
    d["name"] = s.name;
    d["symbol"] = s.symbol;
    d["unit"] = s.unit;
    d["min"] = s.min;
    d["max"] = s.max;
    d["default"] = s.defaultValue;
    d["source"] = s.source;
    d["integer"] = s.integer;
    d["description"] = s.description;
    list.append(d);
  }
  return list;
}

// The structure of `sonargrid-cli models --json`.
py::dict modelsPy() {
  py::dict out;
  py::list models, rules, compatible;
  // A model's or a rule's declaration (ModelInfo and RuleInfo share these three fields).
  auto declared = [](const auto& info) {
    py::dict d;
    d["name"] = info.name;
    d["title"] = info.title;
    d["parameters"] = parameterList(info.parameters);
    return d;
  };
  for (const std::string& name : sensorModelNames()) models.append(declared(sensorModelInfo(name)));
  for (const std::string& name : updateRuleNames()) rules.append(declared(updateRuleInfo(name)));
  for (const std::string& m : sensorModelNames())
    for (const std::string& r : updateRuleNames())
      if (compatibility(m, r).allowed) compatible.append(py::make_tuple(m, r));
  out["models"] = models;
  out["rules"] = rules;
  out["compatible"] = compatible;
  // The forward model learned by EM, with its own rule (as `models --json`'s `forward`).
  py::dict f;
  f["name"] = forward::kModelName;
  f["title"] = forward::kTitle;
  f["rule"] = forward::kRuleName;
  f["parameters"] = parameterList(forward::forwardParameterSpecs());
  py::list forwardModels;
  forwardModels.append(f);
  out["forward"] = forwardModels;
  return out;
}

}  // namespace sg::python
