// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The settings the three papers used, as data: a model, a rule and the parameter values each paper
// prints, every value with the place it is printed. A parameter a paper does not state keeps the
// default of its declaration (parameters.h), so a preset names only what it can cite. Lengths
// paper 002 prints in the sensor's range units (P3, tolerance) are taken as metres, as the
// parameterized model declares.

#include <string>
#include <vector>

#include "sonargrid/engine/mapper.h"

namespace sg {

struct PresetValue {
  std::string parameter;  // a declared parameter name, e.g. "p3"
  double value = 0.0;
  std::string citation;  // paper and section, figure or table that prints the value
};

struct Preset {
  std::string name;   // stable key, e.g. "paper002-table1-mean-vsdns"
  std::string title;  // for menus, by authors: "Arafat et al. Table 1: optimum by mean VSDNS"
  std::string model;  // registry names
  std::string rule;
  std::string source;  // why this model and rule: the paper and section
  std::vector<PresetValue> values;
  std::string companion;  // the preset the paper sets beside this one (side-by-side views), or ""
};

// Every paper preset, in paper order.
const std::vector<Preset>& paperPresets();

// The preset called `name`, or nullptr.
const Preset* findPreset(const std::string& name);

// The preset's model and rule with every declared parameter at its default, then the preset's
// values. Throws MapperError or ParameterError (naming the preset) when a value is not declared or
// out of its declared range.
MapperSettings applyPreset(const Preset& preset);

}  // namespace sg
