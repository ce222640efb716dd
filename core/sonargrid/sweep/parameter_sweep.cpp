// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/sweep/parameter_sweep.h"

#include <array>

#include "sonargrid/sweep/set_evaluation.h"

namespace sg {

std::vector<ParameterSet> paper002Table1Sets(const ParameterSet& base) {
  // Paper 002 Table 1: minimum, step and maximum of each parameter; P5's values are listed in the
  // table's footnote **. Written out rather than stepped so that every value is the double nearest
  // its decimal.
  static constexpr std::array<double, 15> kP5{6,  7,  8,  10, 13, 14, 15, 16,
                                              17, 18, 20, 25, 27, 35, 40};
  static constexpr std::array<double, 4> kP4{0.95, 0.96, 0.97, 0.98};
  static constexpr std::array<double, 6> kTwoP3{0.5, 1.0, 1.5, 2.0, 2.5, 3.0};
  static constexpr std::array<double, 4> kP2{0.05, 0.10, 0.15, 0.20};
  std::vector<ParameterSet> sets;
  sets.reserve(kP5.size() * kP4.size() * kTwoP3.size() * kP2.size());
  for (double p5 : kP5) {
    for (double p4 : kP4) {
      for (double twoP3 : kTwoP3) {
        for (double p2 : kP2) {
          ParameterSet s = base;
          s.set("p1", 1.0 - p4);  // footnote *: "P1 = 1 − P4 relation has been used"
          s.set("p2", p2);
          s.set("p3", twoP3 / 2.0);
          s.set("p4", p4);
          s.set("p5", p5);
          sets.push_back(std::move(s));
        }
      }
    }
  }
  return sets;
}

SweepOutcome runSweep(const Dataset& run, const Dataset* secondRun,
                      const std::vector<ParameterSet>& sets, const SweepSettings& settings,
                      const SweepProgress& progress, const std::atomic<bool>* cancel) {
  // The generic sweep's engine (set_evaluation.h), asked for paper 002's three goodness measures.
  SetEvaluationInput in;
  in.run = &run;
  in.secondRun = secondRun;
  in.settings = settings;
  in.measures.vsdns = true;
  in.measures.derivative = true;
  in.measures.twoRun = secondRun != nullptr;
  SweepOutcome out;
  out.rows.resize(sets.size());
  out.done.assign(sets.size(), false);
  std::vector<std::size_t> all(sets.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  std::size_t finished = 0;
  out.completed = evaluateSets(
      in, sets, all,
      [&](std::size_t i, const SetEvaluation& e) {
        SweepRow& row = out.rows[i];
        row.vsdns = e.vsdns->vsdns;
        row.cellsWithSpread = e.vsdns->cellsWithSpread;
        row.noise = *e.derivative;
        row.twoRuns = e.twoRun;
        out.done[i] = true;
        if (progress) progress(++finished, sets.size());
      },
      cancel);
  return out;
}

}  // namespace sg
