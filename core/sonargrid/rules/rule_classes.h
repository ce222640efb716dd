// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The concrete update rules. Only the registry and tests need these names. Each names what it
// keeps per grid cell (its planes: grid.h, CellLayout).

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

#include "sonargrid/engine/update_rule.h"

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
  void applyRuns(const EvidenceRuns& runs, Grid& grid, EvidenceRuns* deferred) const override;
  bool needsTotals() const override { return normalise_; }
  void applyPart(const Footprint& part, const FootprintTotals& totals, Grid& grid) const override;
  using UpdateRule::applyDeferred;
  void applyDeferred(const EvidenceRuns& deferred, std::size_t firstRun, std::size_t endRun,
                     const FootprintTotals& totals, Grid& grid) const override;

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
  void applyRuns(const EvidenceRuns& runs, Grid& grid, EvidenceRuns* deferred) const override;
  bool applyUniform(const CellEvidence& evidence, std::span<const std::uint32_t> cells,
                    Grid& grid) const override;

  double occupancyOf(const BayesCell& c) const { return c.p; }
  double nativeOf(const BayesCell& c) const { return c.p; }
  bool filledOf(const BayesCell& c) const { return c.p > 0.5; }

 private:
  Input input_;
  double prior_ = 0.5;
};

// Bayes' rule under Precision::Fast (docs/models.md, "Exact and fast engines"): the cell keeps its
// p in four bytes, as the smaller of p and 1 − p, so that it holds p's distance from 0 or from 1
// however small (a float p would round to 1 after eight readings of 0.9 and stay there), in the
// upper half of that double's bits: its sign, its whole exponent (down to the exact cell's floor,
// 2⁻⁹⁶⁰) and 20 bits of its mantissa, rounded to nearest. A sign bit clear stands for p = v, set
// for p = 1 + v = 1 − |v| (−0: certain). A reading widens the cell to the double p, takes the exact
// rule's step (cell_updates.h, bayes), and rounds the new p once; within 2⁻³² of 1, where the
// exact cell's p is a whole number of 2⁻⁵³ below 1, the cell holds that number exactly, and it
// rounds to certainty by the exact rule's own arithmetic.
struct BayesFloatCell {
  std::uint32_t bits;  // the upper half of the double v
};
class FastBayesRule final : public RuleOnCells<FastBayesRule, BayesFloatCell> {
 public:
  explicit FastBayesRule(BayesRule::Input input) : input_(input) {}
  const RuleInfo& info() const override {
    return input_ == BayesRule::Input::Evidence ? BayesRule::evidenceInfo()
                                                : BayesRule::likelihoodInfo();
  }
  void configure(const ParameterSet& params) override;
  CellLayout layout() const override { return CellLayout::of(prior_); }
  void apply(const Footprint& footprint, Grid& grid) const override;
  void applyRuns(const EvidenceRuns& runs, Grid& grid, EvidenceRuns* deferred) const override;
  bool applyUniform(const CellEvidence& evidence, std::span<const std::uint32_t> cells,
                    Grid& grid) const override;

  // The p a cell stands for, and the cell of a p (rounded to nearest). A cell is never +0 (p is
  // at least the exact floor), so v ≤ 0 is its sign bit.
  static double probabilityOf(BayesFloatCell c) {
    const double v = std::bit_cast<double>(static_cast<std::uint64_t>(c.bits) << 32);
    return v <= 0.0 ? 1.0 + v : v;
  }
  static BayesFloatCell cellOf(double p) {
    const double v = p > 0.5 ? -(1.0 - p) : p;
    return {static_cast<std::uint32_t>((std::bit_cast<std::uint64_t>(v) + 0x80000000u) >> 32)};
  }
  // A cell at the prior's bits (every cell nobody has seen) reads as the prior itself, not as its
  // 21 significant bits: a prior on a level's boundary (0.3, 0.9) keeps the exact cell's level.
  double occupancyOf(const BayesFloatCell& c) const {
    return c.bits == prior_.bits ? priorP_ : probabilityOf(c);
  }
  double nativeOf(const BayesFloatCell& c) const { return occupancyOf(c); }
  bool filledOf(const BayesFloatCell& c) const { return occupancyOf(c) > 0.5; }

 private:
  // The reading's p at one cell, as BayesRule computes it.
  double readingProbability(const CellEvidence& c) const;
  BayesRule::Input input_;
  BayesFloatCell prior_ = cellOf(0.5);
  double priorP_ = 0.5;
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
  void applyRuns(const EvidenceRuns& runs, Grid& grid, EvidenceRuns* deferred) const override;
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
  void applyRuns(const EvidenceRuns& runs, Grid& grid, EvidenceRuns* deferred) const override;
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

// Dempster–Shafer evidence combination over {occupied, empty} (Murphy 2000 §11.4), in single
// precision (docs/models.md, "Single-precision cells").
template <class T>
struct DempsterShaferMassesOf {
  T occ, emp, unk;
};
using DempsterShaferMasses = DempsterShaferMassesOf<float>;
// A cell's three masses, which sum to one, in 8 bytes: the two smaller ones as floats, the largest
// left out and recomputed as one minus the other two. A float keeps a small mass to 24 bits however
// small it gets, down to 10⁻³⁸, so no mass is ever stored as a value near 1, which rounds to
// exactly 1 for good.
struct DempsterShaferCell {
  // `a` is m(occ), or −m(unk) when m(occ) is the one left out; `b` is m(emp), or −m(unk) when
  // m(emp) is. The sign bit says which: neither set, m(unk) is left out (a cell nobody has seen: 0,
  // 0). Side by side, as every update reads both.
  float a, b;

  // In float, as the rule computes; in double for what the map shows, so that the mass left out
  // keeps the small ones' digits (1 − 10⁻¹⁰ is a double, not a float) and near-certain cells keep
  // their order.
  template <class T = float>
  DempsterShaferMassesOf<T> masses() const {
    if (std::signbit(a)) {
      const T unk = -static_cast<T>(a), emp = b;
      return {T(1) - unk - emp, emp, unk};
    }
    if (std::signbit(b)) {
      const T unk = -static_cast<T>(b), occ = a;
      return {occ, T(1) - unk - occ, unk};
    }
    const T occ = a, emp = b;
    return {occ, emp, T(1) - occ - emp};
  }
  // The least magnitude of a stored float other than 0: a smaller one is stored as kTiny of its
  // sign. The repeated scaling of a cell's two small masses would otherwise take them into the
  // denormal range, where every multiplication by them is many times slower on some CPUs, and then
  // to 0, where the largest mass is exactly 1 and no evidence can ever turn the cell
  // (docs/models.md, "Single-precision cells"). A product of kTiny by a scale of at least 2^-26
  // (any evidence below 1 − 2^-24, a float's last step below 1) stays normal.
  static constexpr float kTiny = 0x1p-100f;
  static float floored(float v) {
    return v != 0.0f && std::fabs(v) < kTiny ? std::copysign(kTiny, v) : v;
  }
  // Leaves out the largest mass (m(unk) on a tie, then m(occ)); the sign bits are set exactly where
  // masses() looks for them, whatever the signs of the masses given. Both floats floored().
  static DempsterShaferCell of(const DempsterShaferMasses& m) {
    const float occ = floored(std::fabs(m.occ)), emp = floored(std::fabs(m.emp));
    const float unk = floored(-std::fabs(m.unk));
    if (m.unk >= m.occ && m.unk >= m.emp) return {occ, emp};
    if (m.occ >= m.emp) return {unk, emp};
    return {occ, unk};
  }
};
class DempsterShaferRule final : public RuleOnCells<DempsterShaferRule, DempsterShaferCell> {
 public:
  static const RuleInfo& staticInfo();
  const RuleInfo& info() const override { return staticInfo(); }
  void configure(const ParameterSet& params) override;
  CellLayout layout() const override { return CellLayout::of(DempsterShaferCell{0.0f, 0.0f}); }
  void apply(const Footprint& footprint, Grid& grid) const override;
  void applyRuns(const EvidenceRuns& runs, Grid& grid, EvidenceRuns* deferred) const override;
  bool applyUniform(const CellEvidence& evidence, std::span<const std::uint32_t> cells,
                    Grid& grid) const override;

  double occupancyOf(const DempsterShaferCell& c) const;
  double nativeOf(const DempsterShaferCell& c) const;
  bool filledOf(const DempsterShaferCell& c) const;
  double evidenceOf(const DempsterShaferCell& c) const { return c.masses<double>().occ; }  // m(occ)
};

}  // namespace sg
