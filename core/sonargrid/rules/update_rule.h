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

// What a rule may need of a whole footprint when it is given the footprint in parts (the mapper
// maps bands of grid rows on separate threads, each band seeing only its rows of every footprint).
// `occupied` is the sum of the cells' occupied evidence in fixed point, units of 2^-40: integer
// sums are exact, so the total is the same however the footprint was cut.
struct FootprintTotals {
  std::int64_t occupied = 0;
  double occupiedSum() const { return static_cast<double>(occupied) * 0x1p-40; }
};
inline std::int64_t occupiedFixedPoint(const Footprint& footprint) {
  std::int64_t sum = 0;
  for (const CellEvidence& c : footprint.cells)
    sum += static_cast<std::int64_t>(static_cast<double>(c.occupied) * 0x1p40);
  return sum;
}

class UpdateRule {
 public:
  virtual ~UpdateRule() = default;

  virtual const RuleInfo& info() const = 0;
  virtual void configure(const ParameterSet& params) = 0;
  // Clears the layers to "nothing known" for a grid of `cells` cells.
  virtual void reset(std::size_t cells) = 0;
  // Folds one reading's footprint into the layers. A rule updates each cell of the footprint from
  // that cell's evidence alone (and from totals(), below): the mapper relies on it to give a rule
  // the rows of one footprint in parts, from several threads at once, never the same cell twice.
  virtual void apply(const Footprint& footprint) = 0;
  // Whether apply() uses FootprintTotals (then the mapper works them out before giving it parts).
  virtual bool needsTotals() const { return false; }
  // Folds part of a footprint (some of its rows), given the totals of the whole footprint.
  virtual void applyPart(const Footprint& part, const FootprintTotals& /*totals*/) { apply(part); }

  virtual double occupancy(std::size_t cell) const = 0;  // p(occupied) in [0, 1]
  virtual double native(std::size_t cell) const = 0;
  virtual bool filled(std::size_t cell) const = 0;  // occupied evidence beats free evidence
  virtual std::uint8_t level(std::size_t cell) const { return levelOfProbability(occupancy(cell)); }
  // Cells [begin, end) of the four layers of `map` (already sized to the grid), from the four
  // functions above. Each rule overrides it with writeLayersOf(*this, ...) so that the per-cell
  // calls are inlined: a re-map's snapshot is 4 × 200 000 virtual calls otherwise, several ms of a
  // slider's latency. Disjoint ranges may be written from several threads at once.
  virtual void writeLayers(OccupancyMap& map, std::size_t begin, std::size_t end) const;
};

// The body of every rule's writeLayers(): Rule is the final class, so the compiler makes its calls
// direct and inlines them.
template <class Rule>
void writeLayersOf(const Rule& rule, OccupancyMap& map, std::size_t begin, std::size_t end) {
  double* const probability = map.probability.data();
  double* const native = map.native.data();
  std::uint8_t* const level = map.level.data();
  std::uint8_t* const filled = map.filled.data();
  for (std::size_t i = begin; i < end; ++i) {
    probability[i] = rule.occupancy(i);
    native[i] = rule.native(i);
    level[i] = rule.level(i);
    filled[i] = rule.filled(i) ? 1 : 0;
  }
}

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
