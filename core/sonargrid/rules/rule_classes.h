#pragma once
// The concrete update rules. Only the registry and tests need these names.

#include <vector>

#include "sonargrid/rules/update_rule.h"

namespace sg {

// Probability addition (paper 000 eqs 7–8, paper 001 §3.1).
class AdditionRule final : public UpdateRule {
 public:
  static const RuleInfo& staticInfo();
  const RuleInfo& info() const override { return staticInfo(); }
  void configure(const ParameterSet& params) override;
  void reset(std::size_t cells) override;
  void apply(const Footprint& footprint) override;
  bool needsTotals() const override { return normalise_; }
  void applyPart(const Footprint& part, const FootprintTotals& totals) override;
  double occupancy(std::size_t cell) const override;
  double native(std::size_t cell) const override;
  bool filled(std::size_t cell) const override { return occ_[cell] > emp_[cell]; }
  void writeLayers(OccupancyMap& map, std::size_t begin, std::size_t end) const override;

 private:
  bool paper001Combine_ = false;
  bool normalise_ = true;
  std::vector<double> emp_, occ_;
};

// Bayes' rule on one p(occ) layer. `Input::Evidence` is paper 001 §3.2 (pE ↦ (1 − pE)/2,
// pO ↦ 0.5 + pO/2); `Input::Likelihood` is paper 002 eqs 5–6, fed the model's P(s|Occ).
class BayesRule final : public UpdateRule {
 public:
  enum class Input { Evidence, Likelihood };
  explicit BayesRule(Input input) : input_(input) {}
  static const RuleInfo& evidenceInfo();
  static const RuleInfo& likelihoodInfo();
  const RuleInfo& info() const override {
    return input_ == Input::Evidence ? evidenceInfo() : likelihoodInfo();
  }
  void configure(const ParameterSet& params) override;
  void reset(std::size_t cells) override;
  void apply(const Footprint& footprint) override;
  double occupancy(std::size_t cell) const override { return map_[cell]; }
  double native(std::size_t cell) const override { return map_[cell]; }
  bool filled(std::size_t cell) const override { return map_[cell] > 0.5; }
  void writeLayers(OccupancyMap& map, std::size_t begin, std::size_t end) const override;

 private:
  Input input_;
  double prior_ = 0.5;
  std::vector<double> map_;
};

// The log method of paper 001 §3.3 as a sum of logs, cut to [cut_min, cut_max].
class LogRule final : public UpdateRule {
 public:
  static const RuleInfo& staticInfo();
  const RuleInfo& info() const override { return staticInfo(); }
  void configure(const ParameterSet& params) override;
  void reset(std::size_t cells) override;
  void apply(const Footprint& footprint) override;
  double occupancy(std::size_t cell) const override;
  double native(std::size_t cell) const override;
  bool filled(std::size_t cell) const override { return native(cell) > 0.0; }
  void writeLayers(OccupancyMap& map, std::size_t begin, std::size_t end) const override;

 private:
  double cutMin_ = -2.0, cutMax_ = 2.0;
  std::vector<double> product_;  // Emp · Occ; the map value is its log10
};

// Clamped log-odds (Thrun; OctoMap's AbstractOccupancyOcTree).
class LogOddsRule final : public UpdateRule {
 public:
  static const RuleInfo& staticInfo();
  const RuleInfo& info() const override { return staticInfo(); }
  void configure(const ParameterSet& params) override;
  void reset(std::size_t cells) override;
  void apply(const Footprint& footprint) override;
  double occupancy(std::size_t cell) const override;
  double native(std::size_t cell) const override;
  bool filled(std::size_t cell) const override { return odds_[cell] > 1.0; }
  void writeLayers(OccupancyMap& map, std::size_t begin, std::size_t end) const override;

 private:
  double priorOdds_ = 1.0, minOdds_ = 0.0, maxOdds_ = 0.0;
  std::vector<double> odds_;  // exp(L): clamping odds is clamping log-odds, without a log per cell
};

// HIMM's histogram (paper 000 §2.2): integer certainty values.
class HimmRule final : public UpdateRule {
 public:
  static const RuleInfo& staticInfo();
  const RuleInfo& info() const override { return staticInfo(); }
  void configure(const ParameterSet& params) override;
  void reset(std::size_t cells) override;
  void apply(const Footprint& footprint) override;
  double occupancy(std::size_t cell) const override { return cv_[cell] / double(cvMax_); }
  double native(std::size_t cell) const override { return cv_[cell]; }
  bool filled(std::size_t cell) const override { return cv_[cell] > 0; }
  void writeLayers(OccupancyMap& map, std::size_t begin, std::size_t end) const override;
  std::uint8_t level(std::size_t cell) const override { return cv_[cell]; }

 private:
  int increment_ = 3, decrement_ = 1, cvMax_ = 15;
  std::vector<std::uint8_t> cv_;
};

// Dempster–Shafer evidence combination over {occupied, empty} (Murphy 2000 §11.4).
class DempsterShaferRule final : public UpdateRule {
 public:
  static const RuleInfo& staticInfo();
  const RuleInfo& info() const override { return staticInfo(); }
  void configure(const ParameterSet& params) override;
  void reset(std::size_t cells) override;
  void apply(const Footprint& footprint) override;
  double occupancy(std::size_t cell) const override;
  double native(std::size_t cell) const override { return mass_[cell].occ - mass_[cell].emp; }
  bool filled(std::size_t cell) const override { return mass_[cell].occ > mass_[cell].emp; }
  void writeLayers(OccupancyMap& map, std::size_t begin, std::size_t end) const override;

 private:
  // m(unknown) = 1 − both. Side by side, so one cell's update touches one cache line.
  struct Masses {
    double occ = 0.0, emp = 0.0;
  };
  std::vector<Masses> mass_;
};

}  // namespace sg
