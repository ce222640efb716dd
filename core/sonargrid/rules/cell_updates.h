// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// One cell's update by each rule, from the model's single-precision values: what the rules' apply()
// (one CellEvidence at a time) and the run kernels' last cells (run_kernels.cpp, whose lanes repeat
// these operations in this order) both do, so that the two paths give the same bits. Always
// inlined, as they were written in apply()'s loops before.

#include <algorithm>

#include "sonargrid/rules/rule_classes.h"

namespace sg::cellrule {

// Cell k of `run` as a Footprint holds it (footprint.h, EvidenceRuns).
inline CellEvidence cellOfRun(const EvidenceRuns& runs, const EvidenceRuns::Run& run, int k) {
  const std::size_t v = run.first + static_cast<std::size_t>(k);
  CellEvidence c;
  c.cell = run.cell + static_cast<std::uint32_t>(k);
  c.empty = runs.empty[v];
  c.occupied = runs.occupied[v];
  c.probability = runs.probability[v];
  return c;
}

// Probability addition, paper 000 eq 8 (AdditionRule): the single-precision cell widened, the
// update in double, rounded once.
[[gnu::always_inline]] inline void additionEmpty(float empty, EmptyEvidence& cell) {
  if (empty > 0.0) {
    const double e = cell.emp;
    cell.emp = static_cast<float>(e + empty - e * empty);
  }
}
[[gnu::always_inline]] inline void additionOccupied(float occupied, double scale,
                                                    OccupiedEvidence& cell) {
  if (occupied > 0.0) {
    const double po = occupied * scale;
    const double o = cell.occ;
    cell.occ = static_cast<float>(o + po - o * po);
  }
}

// Bayes (BayesRule): paper 001 maps evidence to [0, 0.5] (empty) and [0.5, 1] (occupied).
[[gnu::always_inline]] inline double bayesEvidence(float empty, float occupied) {
  return 0.5 + 0.5 * (static_cast<double>(occupied) - static_cast<double>(empty));
}
// The least probability a Bayes cell keeps, 2⁻⁹⁶⁰ (about 10⁻²⁸⁹): each reading of empty evidence
// multiplies a cell's odds by p/(1 − p), and on the office log and long logs cells seen free often
// sank through the denormal range, where each multiplication takes a slow path on some CPUs (a
// million-reading re-map of hpf × bayes took 1.3 × the time it took with denormals flushed), to
// exactly 0, which no later evidence can move. Far above the denormals (p m stays normal for any
// p down to 2⁻⁶²), and far below anything a map shows (docs/models.md).
inline constexpr double kBayesFloor = 0x1p-960;
[[gnu::always_inline]] inline void bayes(double p, BayesCell& cell) {
  double& m = cell.p;
  const double num = p * m;
  const double den = num + (1.0 - p) * (1.0 - m);
  // den = 0 only when certain evidence meets a certain opposite cell; Bayes is undefined there
  // and the cell keeps its value.
  if (den > 0.0) m = std::max(num / den, kBayesFloor);
}
// The same on a vector of doubles (GCC's vector extensions, any width), operation for operation, a
// select for each `if`: the rules' run kernels (run_kernels.cpp) and the sweeps' batch maps
// (batch_evaluation.cpp) both call it.
template <class V>
[[gnu::always_inline]] inline V bayesLanes(V m, V p) {
  const V num = p * m;
  const V den = num + (1.0 - p) * (1.0 - m);
  const V q = num / den;
  const V floored = q < kBayesFloor ? V{} + kBayesFloor : q;
  return den > 0.0 ? floored : m;
}

// FastBayesRule's step (rule_classes.h, BayesFloatCell): the exact rule's on the cell's p, rounded
// once to the cell.
[[gnu::always_inline]] inline void floatBayes(double p, BayesFloatCell& cell) {
  BayesCell m{FastBayesRule::probabilityOf(cell)};
  bayes(p, m);
  cell = FastBayesRule::cellOf(m.p);
}

// The log update's product (LogRule), held within [kLogLow, kLogHigh].
inline constexpr double kLogLow = 1e-300, kLogHigh = 1e300;
[[gnu::always_inline]] inline void logProduct(float empty, float occupied, LogCell& cell) {
  double& m = cell.product;
  m *= (1.0 - static_cast<double>(empty)) * (1.0 + static_cast<double>(occupied));
  if (m > kLogHigh)
    m = kLogHigh;
  else if (m < kLogLow && m > 0.0)
    m = kLogLow;
}

// Clamped log-odds on the odds (LogOddsRule); the floor keeps a model's 0 or 1 from becoming an
// infinite step.
inline constexpr double kProbabilityFloor = 1e-6;
[[gnu::always_inline]] inline void logOdds(float probability, double invPrior, double minOdds,
                                           double maxOdds, LogOddsCell& cell) {
  const double p =
      std::clamp(static_cast<double>(probability), kProbabilityFloor, 1.0 - kProbabilityFloor);
  double& o = cell.odds;
  o = std::clamp(o * (p / (1.0 - p)) * invPrior, minOdds, maxOdds);
}

// Dempster's rule of combination (DempsterShaferRule), in single precision: the cell's masses, the
// rule, and the new masses stored as DempsterShaferCell::of() keeps them.
[[gnu::always_inline]] inline void dempsterShafer(float occupied, float empty,
                                                  DempsterShaferCell& cell) {
  float o = std::clamp(occupied, 0.0f, 1.0f);
  float e = std::clamp(empty, 0.0f, 1.0f);
  const DempsterShaferMasses m = cell.masses();
  // Every model gives a cell one kind of evidence; Dempster's rule then shortens to
  //   m(occ) = (m(occ) + m(unk) o) / (1 − m(emp) o),  m(emp) = m(emp) s,  m(unk) = m(unk) s,
  //   s = (1 − o) / (1 − m(emp) o)
  // (and symmetrically for e): the general form below with e = 0, in fewer operations. When the
  // mass o adds to is the one the cell leaves out, the largest, it stays the largest and stays left
  // out: the cell's two floats are scaled by s. The run kernels' lanes do the same, in this order.
  if (e == 0.0f || o == 0.0f) {
    const bool occupiedKind = e == 0.0f;  // x = o adds to m(occ); else x = e adds to m(emp)
    const float x = occupiedKind ? o : e;
    const float grow = occupiedKind ? m.occ : m.emp, shrink = occupiedKind ? m.emp : m.occ;
    const float denominator = 1.0f - shrink * x;
    if (denominator <= 0.0f) return;  // total conflict, see below
    const float inv = 1.0f / denominator;
    const float s = (1.0f - x) * inv;
    if (std::signbit(occupiedKind ? cell.a : cell.b)) {
      cell = {DempsterShaferCell::floored(cell.a * s), DempsterShaferCell::floored(cell.b * s)};
      return;
    }
    const float grown = (grow + m.unk * x) * inv, shrunk = shrink * s;
    cell = DempsterShaferCell::of(occupiedKind ? DempsterShaferMasses{grown, shrunk, m.unk * s}
                                               : DempsterShaferMasses{shrunk, grown, m.unk * s});
    return;
  }
  if (o + e > 1.0f) {  // masses must sum to at most one
    const float sum = o + e;
    o /= sum;
    e /= sum;
  }
  const float u = 1.0f - o - e;
  const float conflict = m.occ * e + m.emp * o;
  // Total conflict (a certain cell meets certain opposite evidence) leaves Dempster's rule
  // undefined; the cell keeps its masses.
  if (conflict >= 1.0f) return;
  const float norm = 1.0f / (1.0f - conflict);
  cell = DempsterShaferCell::of({(m.occ * o + m.occ * u + m.unk * o) * norm,
                                 (m.emp * e + m.emp * u + m.unk * e) * norm, m.unk * u * norm});
}

}  // namespace sg::cellrule
