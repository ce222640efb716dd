// SPDX-License-Identifier: GPL-3.0-or-later
// `sonargrid-cli models [--json | --markdown]`: the parameter declarations of every model and rule,
// and which pairs may be combined. The GUI panel reads the same declarations, and `--markdown`
// prints the generated part of docs/models.md (the ctest docs_models_in_sync keeps the two equal).

#include <iomanip>
#include <iostream>
#include <locale>
#include <nlohmann/json.hpp>
#include <sstream>

#include "commands.h"
#include "sonargrid/engine/sensor_model.h"
#include "sonargrid/engine/update_rule.h"
#include "sonargrid/forward/catalog.h"
#include "sonargrid/forward/forward_em.h"

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
                    {"source", s.source},
                    {"integer", s.integer},
                    {"description", s.description}});
  }
  return list;
}

void printParameters(const std::vector<ParameterSpec>& specs) {
  for (const ParameterSpec& s : specs) {
    std::cout << "    " << std::left << std::setw(18) << s.name << std::setw(10) << s.symbol
              << std::setw(6) << s.unit << "default " << s.defaultValue << "  [" << s.min << ", "
              << s.max << "]  " << s.source << '\n';
  }
}

// Numbers as the plain listing prints them (6 significant digits), whatever the global locale.
std::string formatNumber(double v) {
  std::ostringstream out;
  out.imbue(std::locale::classic());
  out << v;
  return out.str();
}

// Text from a declaration, safe inside a Markdown table cell: '|' would end the cell, and '*', '`',
// '<' and '\\' could start emphasis, code, HTML or an escape.
std::string markdownText(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    if (c == '|' || c == '*' || c == '`' || c == '<' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

std::string markdownRange(const ParameterSpec& s) {
  if (!s.integer) return "[" + formatNumber(s.min) + ", " + formatNumber(s.max) + "]";
  if (s.min == 0.0 && s.max == 1.0) return "0 or 1";
  return "integer in [" + formatNumber(s.min) + ", " + formatNumber(s.max) + "]";
}

void printMarkdownParameters(const std::vector<ParameterSpec>& specs) {
  if (specs.empty()) {
    std::cout << "No parameters.\n";
    return;
  }
  std::cout << "| name | symbol | unit | default | range | source | description |\n"
            << "|---|---|---|---:|---|---|---|\n";
  for (const ParameterSpec& s : specs) {
    std::cout << "| `" << s.name << "` | " << markdownText(s.symbol) << " | "
              << (s.unit.empty() ? "—" : markdownText(s.unit)) << " | "
              << formatNumber(s.defaultValue) << " | " << markdownRange(s) << " | "
              << markdownText(s.source) << " | " << markdownText(s.description) << " |\n";
  }
}

// The generated block of docs/models.md: one section per model and rule, then the pair matrix.
void printMarkdown() {
  const std::vector<std::string> models = sensorModelNames();
  const std::vector<std::string> rules = updateRuleNames();
  std::cout << "## Sensor model parameters\n";
  for (const std::string& name : models) {
    const ModelInfo& m = sensorModelInfo(name);
    std::cout << "\n### `" << m.name << "` — " << markdownText(m.title) << "\n\n"
              << "Source: " << markdownText(m.source) << ".\n\n";
    printMarkdownParameters(m.parameters);
  }
  std::cout << "\n## Update rule parameters\n";
  for (const std::string& name : rules) {
    const RuleInfo& r = updateRuleInfo(name);
    std::cout << "\n### `" << r.name << "` — " << markdownText(r.title) << "\n\n"
              << "Source: " << markdownText(r.source) << ".  \n"
              << "Native value: " << markdownText(r.nativeName) << ".\n\n";
    printMarkdownParameters(r.parameters);
  }
  std::cout << "\n## Forward model parameters\n\n"
            << "### `" << forward::kModelName << "` — " << markdownText(forward::kTitle) << "\n\n"
            << "Source: " << markdownText(forward::mapModelSource(forward::kModelName)) << ".  \n"
            << "Rule: `" << forward::kRuleName
            << "` alone (EM over the whole log; docs/forward-model.md).\n\n";
  printMarkdownParameters(forward::forwardParameterSpecs());
  std::cout << "\n## Compatibility matrix\n\n"
            << "Rows are sensor models, columns update rules; ✓ = allowed, ✗ = refused.\n\n"
            << "| model |";
  for (const std::string& r : rules) std::cout << " `" << r << "` |";
  std::cout << "\n|---|";
  for (std::size_t i = 0; i < rules.size(); ++i) std::cout << ":-:|";
  std::cout << '\n';
  for (const std::string& m : models) {
    std::cout << "| `" << m << "` |";
    for (const std::string& r : rules) std::cout << (compatibility(m, r).allowed ? " ✓ |" : " ✗ |");
    std::cout << '\n';
  }
  std::cout << "\nRefused pairs:\n\n";
  for (const std::string& m : models) {
    for (const std::string& r : rules) {
      const Compatibility c = compatibility(m, r);
      if (!c.allowed)
        std::cout << "- `" << m << "` × `" << r << "`: " << markdownText(c.reason) << ".\n";
    }
  }
}

}  // namespace

int runModels(Arguments& args) {
  const bool json = args.flag("--json");
  const bool markdown = args.flag("--markdown");
  args.finish();
  if (json && markdown) throw UsageError("--json and --markdown cannot be combined");
  if (markdown) {
    printMarkdown();
    return 0;
  }
  if (json) {
    nlohmann::ordered_json out;
    out["models"] = nlohmann::ordered_json::array();
    for (const std::string& name : sensorModelNames()) {
      const ModelInfo& m = sensorModelInfo(name);
      out["models"].push_back(
          {{"name", m.name}, {"title", m.title}, {"parameters", parametersJson(m.parameters)}});
    }
    out["rules"] = nlohmann::ordered_json::array();
    for (const std::string& name : updateRuleNames()) {
      const RuleInfo& r = updateRuleInfo(name);
      out["rules"].push_back(
          {{"name", r.name}, {"title", r.title}, {"parameters", parametersJson(r.parameters)}});
    }
    out["compatible"] = nlohmann::ordered_json::array();
    for (const std::string& m : sensorModelNames()) {
      for (const std::string& r : updateRuleNames()) {
        if (compatibility(m, r).allowed) out["compatible"].push_back({m, r});
      }
    }
    // The forward model learned by EM, with EM as its own rule (docs/forward-model.md): beside the
    // inverse models, whose pairs `compatible` lists.
    out["forward"] = nlohmann::ordered_json::array();
    out["forward"].push_back({{"name", forward::kModelName},
                              {"title", forward::kTitle},
                              {"rule", forward::kRuleName},
                              {"parameters", parametersJson(forward::forwardParameterSpecs())}});
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
  std::cout << "\nForward model (its own rule, " << forward::kRuleName << "):\n"
            << "  " << forward::kModelName << " — " << forward::kTitle << " ("
            << forward::mapModelSource(forward::kModelName) << ")\n";
  printParameters(forward::forwardParameterSpecs());
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
