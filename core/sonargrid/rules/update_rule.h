#pragma once
// An update rule owns the grid's storage and says how a reading's evidence enters a cell
// (notes/models-and-metrics.md, "Update rules"). Every rule yields p(occupied), its own native
// value, the 16 levels and a "filled" flag, so views and metrics need not know which rule ran.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "sonargrid/footprint.h"
#include "sonargrid/occupancy_map.h"
#include "sonargrid/parameters.h"

namespace sg {

struct RuleInfo {
  std::string name;  // registry and CLI name, e.g. "bayes"
  std::string title;
  std::string source;
  std::string nativeName;  // what native() holds, e.g. "log-odds"
  std::vector<ParameterSpec> parameters;
};

class UpdateRule {
 public:
  virtual ~UpdateRule() = default;

  virtual const RuleInfo& info() const = 0;
  virtual void configure(const ParameterSet& params) = 0;
  // Clears the layers to "nothing known" for a grid of `cells` cells.
  virtual void reset(std::size_t cells) = 0;
  // Folds one reading's footprint into the layers.
  virtual void apply(const Footprint& footprint) = 0;

  virtual double occupancy(std::size_t cell) const = 0;  // p(occupied) in [0, 1]
  virtual double native(std::size_t cell) const = 0;
  virtual bool filled(std::size_t cell) const = 0;  // occupied evidence beats free evidence
  virtual std::uint8_t level(std::size_t cell) const { return levelOfProbability(occupancy(cell)); }
};

std::vector<std::string> updateRuleNames();
std::unique_ptr<UpdateRule> makeUpdateRule(const std::string& name);  // nullptr when unknown
const RuleInfo& updateRuleInfo(const std::string& name);              // throws when unknown

// Whether a model and a rule may be combined, and why not (docs/models.md has the table).
struct Compatibility {
  bool allowed = true;
  std::string reason;
};
Compatibility compatibility(const std::string& model, const std::string& rule);

}  // namespace sg
