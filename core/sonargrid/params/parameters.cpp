// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/params/parameters.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace sg {

ParameterSet::ParameterSet(const std::vector<ParameterSpec>& specs) : specs_(specs) {
  for (const ParameterSpec& s : specs_) values_[s.name] = s.defaultValue;
}

void ParameterSet::set(const std::string& name, double value) {
  const auto it = std::find_if(specs_.begin(), specs_.end(),
                               [&](const ParameterSpec& s) { return s.name == name; });
  if (it == specs_.end()) {
    std::ostringstream msg;
    msg << "unknown parameter '" << name << "'; this model and rule take:";
    for (const ParameterSpec& s : specs_) msg << ' ' << s.name;
    if (specs_.empty()) msg << " none";
    throw ParameterError(msg.str());
  }
  if (!std::isfinite(value) || value < it->min || value > it->max) {
    std::ostringstream msg;
    msg << "parameter '" << name << "' = " << value << " is outside [" << it->min << ", " << it->max
        << "]";
    if (!it->unit.empty()) msg << ' ' << it->unit;
    throw ParameterError(msg.str());
  }
  if (it->integer && value != std::round(value)) {
    throw ParameterError("parameter '" + name + "' takes a whole number");
  }
  values_[name] = value;
}

double ParameterSet::get(const std::string& name) const {
  const auto it = values_.find(name);
  if (it == values_.end()) throw ParameterError("no parameter '" + name + "'");
  return it->second;
}

void ParameterSet::append(const ParameterSet& other) {
  for (const ParameterSpec& s : other.specs_) {
    if (has(s.name)) throw ParameterError("parameter '" + s.name + "' is declared twice");
  }
  for (const ParameterSpec& s : other.specs_) {
    specs_.push_back(s);
    values_[s.name] = other.get(s.name);
  }
}

}  // namespace sg
