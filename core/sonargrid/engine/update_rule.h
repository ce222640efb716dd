// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// An update rule says how a reading's evidence enters a cell (docs/models.md, "Update rules"): it
// declares what it keeps per cell and the value of a cell nobody has seen, and folds footprints
// into a Grid made with that layout; the grid owns the cells (grid.h). Every rule yields
// p(occupied), its own native value, the 16 levels and a "filled" flag, so views and metrics need
// not know which rule ran.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "sonargrid/engine/footprint.h"
#include "sonargrid/engine/grid.h"
#include "sonargrid/engine/occupancy_map.h"
#include "sonargrid/params/parameters.h"

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
  // Adds a share (a cell's, or a part's sum) modulo 2^64: no order of the shares changes the sum,
  // and it cannot overflow.
  void add(std::int64_t share) {
    occupied = static_cast<std::int64_t>(static_cast<std::uint64_t>(occupied) +
                                         static_cast<std::uint64_t>(share));
  }
};
// One cell's share, units of 2^-40 rounded toward zero. NaN counts 0, as the rules leave a cell of
// NaN evidence as it was, and a value beyond ±2^22 (no model gives more than 1) counts as ±2^22,
// so that the conversion is defined (a cast of NaN or of a value out of the integer's range is
// not).
inline std::int64_t occupiedFixedPoint(float occupied) {
  const double x = static_cast<double>(occupied);
  if (!(x == x)) return 0;
  return static_cast<std::int64_t>(std::clamp(x, -0x1p22, 0x1p22) * 0x1p40);
}
// The sum of a footprint's shares (FootprintTotals::add); a real footprint's sum (thousands of
// cells of at most 2^40) never comes near 2^63, so it is the exact sum.
inline std::int64_t occupiedFixedPoint(const Footprint& footprint) {
  FootprintTotals sum;
  for (const CellEvidence& c : footprint.cells) sum.add(occupiedFixedPoint(c.occupied));
  return sum.occupied;
}
// The same of the cells of the runs from `firstRun` on (a reading's deferred runs,
// UpdateRule::applyRuns, appended to those of the readings before), whose occupied values alone
// are read: eight at a time where the run kernels take masked lanes (run_kernels.cpp), the same
// sum.
std::int64_t occupiedFixedPoint(const EvidenceRuns& runs, std::size_t firstRun = 0);

class UpdateRule {
 public:
  virtual ~UpdateRule() = default;

  virtual const RuleInfo& info() const = 0;
  virtual void configure(const ParameterSet& params) = 0;
  // What the rule keeps per cell, and its value in a cell nobody has seen (as configured).
  virtual CellLayout layout() const = 0;
  // Folds one reading's footprint into the cells of `grid`, a grid made with layout(). A rule
  // updates each cell of the footprint from that cell's evidence alone (and from totals(), below):
  // the mapper relies on it to give a rule the rows of one footprint in parts, from several threads
  // at once, never the same cell twice.
  virtual void apply(const Footprint& footprint, Grid& grid) const = 0;
  // Whether apply() uses FootprintTotals (then the mapper works them out before giving it parts).
  virtual bool needsTotals() const { return false; }
  // Folds part of a footprint (some of its rows), given the totals of the whole footprint.
  virtual void applyPart(const Footprint& part, const FootprintTotals& /*totals*/,
                         Grid& grid) const {
    apply(part, grid);
  }

  // For a rule that keeps one byte per cell (HIMM): the value apply() leaves in a cell that held
  // v, for every v, when the cell is given `evidence`, as table[v]. Returns false, the table
  // untouched, for any other rule. A model whose footprint gives many cells the same evidence can
  // then map straight into the grid (SensorModel::applyDirect).
  virtual bool byteTransition(const CellEvidence& /*evidence*/,
                              std::array<std::uint8_t, 256>& /*table*/) const {
    return false;
  }

  // Applies `evidence` to each of `cells` (grid indices, each at most once), leaving the bits
  // apply() leaves for a footprint of those cells all carrying `evidence`; the grid's marks are
  // the caller's. Returns false, with nothing applied, for a rule that offers no such update: one
  // with totals (whose cells wait for the reading's total) or a one-byte rule (byteTransition() is
  // its way). A model whose footprint gives many cells one value (HIMM's axis: the free cells, then
  // the echo) can then map straight into the grid (SensorModel::applyDirect), with one call a value
  // rather than a Footprint.
  virtual bool applyUniform(const CellEvidence& /*evidence*/,
                            std::span<const std::uint32_t> /*cells*/, Grid& /*grid*/) const {
    return false;
  }

  // Folds a reading's cells given as runs (footprint.h; the mapper's batch path, where the model
  // hands its cells over as runs), each cell as apply() would. A rule without totals applies them
  // all. A rule with totals (needsTotals()) applies now what does not depend on them and appends to
  // `deferred` (cleared by the caller; its arrays sized by this call, as a writer of runs does) the
  // runs of the cells whose update does (they may take in cells that the deferred update leaves
  // as they are), such that applyDeferred(deferred, totals) later finishes the reading and
  // occupiedFixedPoint(deferred) is these cells' share of the totals; the two parts must touch
  // separate state of a cell (or all of it be deferred), since the deferred part of a reading may
  // be applied after the later readings' first parts (on several threads, after those of the whole
  // batch: Mapper::integrateBands). `deferred` may be null for a rule without
  // totals. A deferring rule may leave `deferred`'s empty and probability arrays as they were, if
  // its applyDeferred() reads only the occupied values: so a rule overrides both or neither. The
  // default converts the runs to CellEvidence and applies them, or defers them all with their
  // three values.
  virtual void applyRuns(const EvidenceRuns& runs, Grid& grid, EvidenceRuns* deferred) const;
  // Finishes a reading's runs that applyRuns() deferred, runs [firstRun, endRun) of `deferred`
  // (which may hold other readings' before and after them), given the totals of the whole reading.
  // The default converts them to CellEvidence and calls applyPart().
  virtual void applyDeferred(const EvidenceRuns& deferred, std::size_t firstRun, std::size_t endRun,
                             const FootprintTotals& totals, Grid& grid) const;
  // The same of all of its runs.
  void applyDeferred(const EvidenceRuns& deferred, const FootprintTotals& totals,
                     Grid& grid) const {
    applyDeferred(deferred, 0, deferred.runs.size(), totals, grid);
  }

  virtual double occupancy(const Grid& grid, std::size_t cell) const = 0;  // p(occupied), [0, 1]
  virtual double native(const Grid& grid, std::size_t cell) const = 0;
  virtual bool filled(const Grid& grid, std::size_t cell) const = 0;  // occupied beats free
  virtual std::uint8_t level(const Grid& grid, std::size_t cell) const = 0;
  // The rule's certainty that the cell is occupied (OccupancyMap::evidence).
  virtual double evidence(const Grid& grid, std::size_t cell) const = 0;
  // level() of cells [begin, end) into level[begin, end), with the per-cell calls inlined
  // (RuleOnCells): a re-map's snapshot is 200 000 virtual calls otherwise, on the path from a
  // slider to the picture. Disjoint ranges may be written from several threads at once.
  virtual void writeLevels(const Grid& grid, std::uint8_t* level, std::size_t begin,
                           std::size_t end) const = 0;
  // One derived layer of cells [begin, end) into out[0, end − begin) (doubles, or bytes for
  // DerivedLayer::Filled), inlined likewise: what holding a snapshot's layers costs.
  virtual void writeLayer(const Grid& grid, DerivedLayer layer, std::size_t begin, std::size_t end,
                          void* out) const = 0;
};

// A rule's layers of the cell values a snapshot shares (Grid::sharedCells()): what a mapped
// OccupancyMap reads its p(occupied), native value, evidence and filled flag from. It keeps the
// rule (which nothing configures again) and the shared cells alive.
class RuleCells final : public DerivedCells {
 public:
  RuleCells(std::shared_ptr<const UpdateRule> rule, Grid cells)
      : rule_(std::move(rule)), cells_(std::move(cells)) {}
  double value(DerivedLayer layer, std::size_t cell) const override {
    switch (layer) {
      case DerivedLayer::Probability:
        return rule_->occupancy(cells_, cell);
      case DerivedLayer::Native:
        return rule_->native(cells_, cell);
      case DerivedLayer::Evidence:
        return rule_->evidence(cells_, cell);
      case DerivedLayer::Filled:
        break;
    }
    return rule_->filled(cells_, cell) ? 1.0 : 0.0;
  }
  void fill(DerivedLayer layer, std::size_t begin, std::size_t end, void* out) const override {
    rule_->writeLayer(cells_, layer, begin, end, out);
  }

 private:
  std::shared_ptr<const UpdateRule> rule_;
  Grid cells_;
};

// The base of every rule: `Rule` (the final class) keeps one value of each of `Cells` per cell,
// plane by plane in that order (CellLayout), and says what a cell means through occupancyOf(),
// nativeOf() and filledOf() (and levelOf(), which defaults to the level of the probability), each
// given the cell's value in every plane. This class gives UpdateRule's per-cell reads and
// writeLevels() and writeLayer() from them, with direct, inlined calls.
template <class Rule, class... Cells>
class RuleOnCells : public UpdateRule {
 public:
  double occupancy(const Grid& grid, std::size_t cell) const final {
    return at(grid, cell, [this](const Cells&... c) { return self().occupancyOf(c...); });
  }
  double native(const Grid& grid, std::size_t cell) const final {
    return at(grid, cell, [this](const Cells&... c) { return self().nativeOf(c...); });
  }
  bool filled(const Grid& grid, std::size_t cell) const final {
    return at(grid, cell, [this](const Cells&... c) { return self().filledOf(c...); });
  }
  std::uint8_t level(const Grid& grid, std::size_t cell) const final {
    return at(grid, cell, [this](const Cells&... c) { return self().levelOf(c...); });
  }
  double evidence(const Grid& grid, std::size_t cell) const final {
    return at(grid, cell, [this](const Cells&... c) { return self().evidenceOf(c...); });
  }
  std::uint8_t levelOf(const Cells&... c) const {
    return levelOfProbability(self().occupancyOf(c...));
  }
  // The rule's certainty of occupancy in [0, 1] (OccupancyMap::evidence): by default that of a
  // probabilistic rule, 2p − 1 above p = 0.5 and 0 below. Rules that keep occupied evidence of
  // their own (HIMM, addition, Dempster–Shafer) say so.
  double evidenceOf(const Cells&... c) const {
    const double e = 2.0 * self().occupancyOf(c...) - 1.0;
    return e > 0.0 ? e : 0.0;
  }

  void writeLevels(const Grid& grid, std::uint8_t* level, std::size_t begin,
                   std::size_t end) const final {
    forCells(grid, begin, end,
             [&](std::size_t i, const Cells&... c) { level[i] = self().levelOf(c...); });
  }
  void writeLayer(const Grid& grid, DerivedLayer layer, std::size_t begin, std::size_t end,
                  void* out) const final {
    const Rule& rule = self();
    auto* const values = static_cast<double*>(out);
    switch (layer) {
      case DerivedLayer::Probability:
        forCells(grid, begin, end, [&](std::size_t i, const Cells&... c) {
          values[i - begin] = rule.occupancyOf(c...);
        });
        return;
      case DerivedLayer::Native:
        forCells(grid, begin, end, [&](std::size_t i, const Cells&... c) {
          values[i - begin] = rule.nativeOf(c...);
        });
        return;
      case DerivedLayer::Evidence:
        forCells(grid, begin, end, [&](std::size_t i, const Cells&... c) {
          values[i - begin] = rule.evidenceOf(c...);
        });
        return;
      case DerivedLayer::Filled:
        break;
    }
    auto* const flags = static_cast<std::uint8_t*>(out);
    forCells(grid, begin, end, [&](std::size_t i, const Cells&... c) {
      flags[i - begin] = rule.filledOf(c...) ? 1 : 0;
    });
  }

 private:
  const Rule& self() const { return static_cast<const Rule&>(*this); }

  template <class Fn, std::size_t... Plane>
  static auto atPlanes(const Grid& grid, std::size_t cell, Fn&& fn, std::index_sequence<Plane...>) {
    return fn(grid.cells<Cells>(Plane)[cell]...);
  }
  template <class Fn>
  static auto at(const Grid& grid, std::size_t cell, Fn&& fn) {
    return atPlanes(grid, cell, fn, std::index_sequence_for<Cells...>{});
  }

  // fn(i, cell values) for every cell i of [begin, end), each plane's pointer taken once.
  template <class Fn>
  static void forCells(const Grid& grid, std::size_t begin, std::size_t end, Fn&& fn) {
    forCellsOf(grid, begin, end, fn, std::index_sequence_for<Cells...>{});
  }
  template <class Fn, std::size_t... Plane>
  static void forCellsOf(const Grid& grid, std::size_t begin, std::size_t end, Fn&& fn,
                         std::index_sequence<Plane...>) {
    const std::tuple<const Cells*...> planes{grid.cells<Cells>(Plane)...};
    for (std::size_t i = begin; i < end; ++i) fn(i, std::get<Plane>(planes)[i]...);
  }
};

// Which arithmetic a rule's cells use (docs/models.md, "Exact and fast engines"). Exact is the
// double arithmetic every rule was written and tested in, the oracle; Fast may keep a cell in
// another form (a cone model's Bayes cells: four bytes, rule_classes.h, BayesFloatCell) within
// the tolerance that tests/core/tst_precision.cpp holds it to against Exact. Both are
// deterministic: the same bits at any thread count and in batch, incremental and live mapping.
enum class Precision { Exact, Fast };
// The precision named "exact" or "fast"; throws std::invalid_argument for another name.
Precision precisionFromName(const std::string& name);
// Whether `model` × `rule` has cells of its own under Fast: a cone model with the Bayes family.
// Every other pair keeps its exact cells under both. HIMM's axis model gives a few discrete
// values, and its cells sit on the 16 levels' boundaries (p_hit = 0.7 is the boundary of levels 10
// and 11), where the exact cell's side is decided by the last bits of a double, which a cell of
// 21 significant bits cannot follow; it keeps exact cells (docs/models.md).
bool hasFastCells(const std::string& model, const std::string& rule);

std::vector<std::string> updateRuleNames();
// nullptr when unknown.
// With Precision::Fast, the fast cells of `name` where it has any (hasFastCells(): a caller
// mapping with a non-cone model passes Exact).
std::unique_ptr<UpdateRule> makeUpdateRule(const std::string& name,
                                           Precision precision = Precision::Exact);
const RuleInfo& updateRuleInfo(const std::string& name);  // throws when unknown

// Whether a model and a rule may be combined, and why not (docs/models.md has the table).
struct Compatibility {
  bool allowed = true;
  std::string reason;
};
Compatibility compatibility(const std::string& model, const std::string& rule);

// Why `rule` makes no use of `model`'s parameter `parameter` (the parameter panel disables its
// control and shows this as the reason), or an empty string when the pair uses it. For now one
// pair has such parameters: HIMM × HIMM, whose increments alone set the cells, so p_hit and
// p_miss only decide on which side of 0.5 a cell's evidence lies, which their ranges fix.
std::string unusedParameterReason(const std::string& model, const std::string& rule,
                                  const std::string& parameter);

}  // namespace sg
