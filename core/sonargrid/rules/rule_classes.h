// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The concrete update rules. Only the registry and tests need these names. Each names what it
// keeps per grid cell (its planes: grid.h, CellLayout).

#include <algorithm>
#include <array>
#include <cstdint>

#include "sonargrid/rules/update_rule.h"

namespace sg {

// Probability addition (paper 000 eqs 7–8, paper 001 §3.1). Emp and Occ in planes of their own: a
// cone writes one or the other to a cell. Each is kept in single precision (docs/models.md,
// "Single-precision cells"): an update widens it, computes in double and rounds once.
struct EmptyEvidence {
  float emp;
};
struct OccupiedEvidence {
  float occ;
};
class AdditionRule final : public RuleOnCells<AdditionRule, EmptyEvidence, OccupiedEvidence> {
 public:
  static const RuleInfo& staticInfo();
  const RuleInfo& info() const override { return staticInfo(); }
  void configure(const ParameterSet& params) override;
  CellLayout layout() const override {
    return CellLayout::of(EmptyEvidence{0.0f}, OccupiedEvidence{0.0f});
  }
  void apply(const Footprint& footprint, Grid& grid) const override;
  void applyRuns(const EvidenceRuns& runs, Grid& grid, Footprint* deferred) const override;
  bool needsTotals() const override { return normalise_; }
  void applyPart(const Footprint& part, const FootprintTotals& totals, Grid& grid) const override;

  double occupancyOf(const EmptyEvidence& e, const OccupiedEvidence& o) const;
  double nativeOf(const EmptyEvidence& e, const OccupiedEvidence& o) const;
  bool filledOf(const EmptyEvidence& e, const OccupiedEvidence& o) const { return o.occ > e.emp; }
  // Paper 000 eq 7: a filled cell's value is its Occ.
  double evidenceOf(const EmptyEvidence& /*e*/, const OccupiedEvidence& o) const { return o.occ; }

 private:
  bool paper001Combine_ = false;
  bool normalise_ = true;
};

// Bayes' rule on one p(occ) layer. `Input::Evidence` is paper 001 §3.2 (pE ↦ (1 − pE)/2,
// pO ↦ 0.5 + pO/2); `Input::Likelihood` is paper 002 eqs 5–6, fed the model's P(s|Occ).
struct BayesCell {
  double p;
};
class BayesRule final : public RuleOnCells<BayesRule, BayesCell> {
 public:
  enum class Input { Evidence, Likelihood };
  explicit BayesRule(Input input) : input_(input) {}
  static const RuleInfo& evidenceInfo();
  static const RuleInfo& likelihoodInfo();
  const RuleInfo& info() const override {
    return input_ == Input::Evidence ? evidenceInfo() : likelihoodInfo();
  }
  void configure(const ParameterSet& params) override;
  CellLayout layout() const override { return CellLayout::of(BayesCell{prior_}); }
  void apply(const Footprint& footprint, Grid& grid) const override;
  void applyRuns(const EvidenceRuns& runs, Grid& grid, Footprint* deferred) const override;
  bool applyUniform(const CellEvidence& evidence, std::span<const std::uint32_t> cells,
                    Grid& grid) const override;

  double occupancyOf(const BayesCell& c) const { return c.p; }
  double nativeOf(const BayesCell& c) const { return c.p; }
  bool filledOf(const BayesCell& c) const { return c.p > 0.5; }

 private:
  Input input_;
  double prior_ = 0.5;
};

// The log method of paper 001 §3.3 as a sum of logs, cut to [cut_min, cut_max].
struct LogCell {
  double product;  // Emp · Occ; the map value is its log10
};
class LogRule final : public RuleOnCells<LogRule, LogCell> {
 public:
  static const RuleInfo& staticInfo();
  const RuleInfo& info() const override { return staticInfo(); }
  void configure(const ParameterSet& params) override;
  CellLayout layout() const override { return CellLayout::of(LogCell{1.0}); }
  void apply(const Footprint& footprint, Grid& grid) const override;
  void applyRuns(const EvidenceRuns& runs, Grid& grid, Footprint* deferred) const override;
  bool applyUniform(const CellEvidence& evidence, std::span<const std::uint32_t> cells,
                    Grid& grid) const override;

  double occupancyOf(const LogCell& c) const;
  double nativeOf(const LogCell& c) const;
  bool filledOf(const LogCell& c) const { return nativeOf(c) > 0.0; }

 private:
  double cutMin_ = -2.0, cutMax_ = 2.0;
};

// Clamped log-odds (Thrun; OctoMap's AbstractOccupancyOcTree).
struct LogOddsCell {
  double odds;  // exp(L): clamping odds is clamping log-odds, without a log per cell
};
class LogOddsRule final : public RuleOnCells<LogOddsRule, LogOddsCell> {
 public:
  static const RuleInfo& staticInfo();
  const RuleInfo& info() const override { return staticInfo(); }
  void configure(const ParameterSet& params) override;
  CellLayout layout() const override { return CellLayout::of(LogOddsCell{priorOdds_}); }
  void apply(const Footprint& footprint, Grid& grid) const override;
  void applyRuns(const EvidenceRuns& runs, Grid& grid, Footprint* deferred) const override;
  bool applyUniform(const CellEvidence& evidence, std::span<const std::uint32_t> cells,
                    Grid& grid) const override;

  double occupancyOf(const LogOddsCell& c) const;
  double nativeOf(const LogOddsCell& c) const;
  bool filledOf(const LogOddsCell& c) const { return c.odds > 1.0; }

 private:
  double priorOdds_ = 1.0, minOdds_ = 0.0, maxOdds_ = 0.0;
};

// HIMM's histogram (paper 000 §2.2): integer certainty values.
struct HimmCell {
  std::uint8_t cv;
};
class HimmRule final : public RuleOnCells<HimmRule, HimmCell> {
 public:
  static const RuleInfo& staticInfo();
  const RuleInfo& info() const override { return staticInfo(); }
  void configure(const ParameterSet& params) override;
  CellLayout layout() const override { return CellLayout::of(HimmCell{0}); }
  void apply(const Footprint& footprint, Grid& grid) const override;
  bool byteTransition(const CellEvidence& evidence,
                      std::array<std::uint8_t, 256>& table) const override;

  double occupancyOf(const HimmCell& c) const { return c.cv / double(cvMax_); }
  double nativeOf(const HimmCell& c) const { return c.cv; }
  bool filledOf(const HimmCell& c) const { return c.cv > 0; }
  std::uint8_t levelOf(const HimmCell& c) const { return c.cv; }
  double evidenceOf(const HimmCell& c) const { return c.cv / double(cvMax_); }  // CV, paper 000

 private:
  // A cell's CV after one cell of a footprint: +I⁺ for occupied evidence, −I⁻ for free.
  std::uint8_t updated(std::uint8_t cv, const CellEvidence& c) const {
    if (c.occupied > c.empty) return static_cast<std::uint8_t>(std::min(cvMax_, cv + increment_));
    if (c.empty > c.occupied) return static_cast<std::uint8_t>(std::max(0, cv - decrement_));
    return cv;
  }

  int increment_ = 3, decrement_ = 1, cvMax_ = 15;
};

// Dempster–Shafer evidence combination over {occupied, empty} (Murphy 2000 §11.4).
struct DempsterShaferCell {
  double occ, emp;  // m(unknown) = 1 − both; side by side, as every update reads both
};
class DempsterShaferRule final : public RuleOnCells<DempsterShaferRule, DempsterShaferCell> {
 public:
  static const RuleInfo& staticInfo();
  const RuleInfo& info() const override { return staticInfo(); }
  void configure(const ParameterSet& params) override;
  CellLayout layout() const override { return CellLayout::of(DempsterShaferCell{0.0, 0.0}); }
  void apply(const Footprint& footprint, Grid& grid) const override;
  void applyRuns(const EvidenceRuns& runs, Grid& grid, Footprint* deferred) const override;
  bool applyUniform(const CellEvidence& evidence, std::span<const std::uint32_t> cells,
                    Grid& grid) const override;

  double occupancyOf(const DempsterShaferCell& c) const;
  double nativeOf(const DempsterShaferCell& c) const { return c.occ - c.emp; }
  bool filledOf(const DempsterShaferCell& c) const { return c.occ > c.emp; }
  double evidenceOf(const DempsterShaferCell& c) const { return c.occ; }  // m(occ)
};

}  // namespace sg
