// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Every tunable number is declared once, here in the form of a ParameterSpec, by the model or rule
// that owns it. The CLI (`models --json`, `--set`), the GUI panel and docs/models.md all read the
// declarations; nothing else restates a range or a default.

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace sg {

struct ParameterSpec {
  std::string name;    // machine name used by --set and project files, e.g. "epsilon"
  std::string symbol;  // as the papers write it, e.g. "ε"
  std::string unit;    // "m", "deg", "1/m", "" for dimensionless
  double min = 0.0;
  double max = 1.0;
  double defaultValue = 0.0;
  std::string source;       // paper and equation, or the library the value comes from
  std::string description;  // one line for tooltips and docs
  bool integer = false;     // a whole number or a switch (0/1)
};

class ParameterError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Values keyed by name. Built from specs, so it always holds every declared parameter.
class ParameterSet {
 public:
  ParameterSet() = default;
  explicit ParameterSet(const std::vector<ParameterSpec>& specs);

  // Throws ParameterError naming the parameter and its allowed range when the name is unknown or
  // the value is out of range or not finite.
  void set(const std::string& name, double value);
  double get(const std::string& name) const;
  bool has(const std::string& name) const { return values_.count(name) != 0; }
  const std::map<std::string, double>& values() const { return values_; }
  const std::vector<ParameterSpec>& specs() const { return specs_; }

  // Merges another set's declarations and defaults (model + rule parameters in one set). Names
  // must not collide.
  void append(const ParameterSet& other);

  bool operator==(const ParameterSet& o) const { return values_ == o.values_; }

 private:
  std::vector<ParameterSpec> specs_;
  std::map<std::string, double> values_;
};

}  // namespace sg
