// `sonargrid-cli models [--json]`: the parameter declarations of every model and rule, and which
// pairs may be combined. The GUI panel and docs/models.md read the same declarations.

#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "sonargrid/models/sensor_model.h"
#include "sonargrid/rules/update_rule.h"

namespace sg::cli {
namespace {

nlohmann::ordered_json parametersJson(const std::vector<ParameterSpec>& specs) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const ParameterSpec& s : specs) {
    list.push_back({{"name", s.name},
                    {"symbol", s.symbol},
                    {"unit", s.unit},
                    {"min", s.min},
                    {"max", s.max},
                    {"default", s.defaultValue},
                    {"source", s.source}});
  }
  return list;
}

void printParameters(const std::vector<ParameterSpec>& specs) {
  for (const ParameterSpec& s : specs) {
    std::cout << "    " << std::left << std::setw(18) << s.name << std::setw(10) << s.symbol << std::setw(6)
              << s.unit << "default " << s.defaultValue << "  [" << s.min << ", " << s.max << "]  " << s.source
              << '\n';
  }
}

}  // namespace

int runModels(Arguments& args) {
  const bool json = args.flag("--json");
  args.finish();
  if (json) {
    nlohmann::ordered_json out;
    out["models"] = nlohmann::ordered_json::array();
    for (const std::string& name : sensorModelNames()) {
      const ModelInfo& m = sensorModelInfo(name);
      out["models"].push_back({{"name", m.name}, {"title", m.title}, {"parameters", parametersJson(m.parameters)}});
    }
    out["rules"] = nlohmann::ordered_json::array();
    for (const std::string& name : updateRuleNames()) {
      const RuleInfo& r = updateRuleInfo(name);
      out["rules"].push_back({{"name", r.name}, {"title", r.title}, {"parameters", parametersJson(r.parameters)}});
    }
    out["compatible"] = nlohmann::ordered_json::array();
    for (const std::string& m : sensorModelNames()) {
      for (const std::string& r : updateRuleNames()) {
        if (compatibility(m, r).allowed) out["compatible"].push_back({m, r});
      }
    }
    std::cout << out.dump() << '\n';
    return 0;
  }
  std::cout << "Sensor models:\n";
  for (const std::string& name : sensorModelNames()) {
    const ModelInfo& m = sensorModelInfo(name);
    std::cout << "  " << m.name << " — " << m.title << " (" << m.source << ")\n";
    printParameters(m.parameters);
  }
  std::cout << "\nUpdate rules:\n";
  for (const std::string& name : updateRuleNames()) {
    const RuleInfo& r = updateRuleInfo(name);
    std::cout << "  " << r.name << " — " << r.title << " (" << r.source << ")\n";
    printParameters(r.parameters);
  }
  std::cout << "\nPairs that cannot be combined:\n";
  for (const std::string& m : sensorModelNames()) {
    for (const std::string& r : updateRuleNames()) {
      const Compatibility c = compatibility(m, r);
      if (!c.allowed) std::cout << "  " << m << " × " << r << ": " << c.reason << '\n';
    }
  }
  return 0;
}

}  // namespace sg::cli
