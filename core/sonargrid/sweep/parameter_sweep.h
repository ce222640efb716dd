// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A parameter sweep: one model × rule mapped once per parameter set over the same log, each map
// judged without a reference by the three goodness measures of paper 002 §5 (VSDNS, derivative
// noise and, given a second run over the same route, the two-run comparison). What paper 002 does
// with its 1440 maps (Table 1) and what `sonargrid-cli reproduce arafat` reruns.
//
// runSweep() is the generic sweep's engine (evaluateSets(), set_evaluation.h) asked for those three
// measures: batched where batch_evaluation.h serves the model and rule, one map per set otherwise,
// on the thread policy's threads (concurrency.h). Row i always holds set i, bit-identical to one
// map of set i, so the rows do not depend on the number of threads.

#include <atomic>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "sonargrid/data/dataset.h"
#include "sonargrid/engine/grid_spec.h"
#include "sonargrid/metrics/derivative_noise.h"
#include "sonargrid/metrics/two_run_comparison.h"
#include "sonargrid/params/parameters.h"

namespace sg {

// The grid of paper 002 Table 1 over the `parameterized` model's parameters p1..p5, each set
// starting from `base` (the other parameters: no_echo, the rule's prior...):
//   P2 ∈ {0.05, 0.10, 0.15, 0.20};  2·P3 ∈ {0.5, 1.0, ..., 3.0} (P3 in metres, docs/models.md);
//   P4 ∈ {0.95, 0.96, 0.97, 0.98};  P1 = 1 − P4 (the table's footnote *);
//   P5 ∈ {6, 7, 8, 10, 13, 14, 15, 16, 17, 18, 20, 25, 27, 35, 40} degrees (footnote **);
// 4 · 6 · 4 · 15 = 1440 sets, ordered with P5 outermost, then P4, 2·P3 and P2 innermost (the column
// order of paper 002 Table 2). Throws ParameterError when `base` lacks p1..p5.
std::vector<ParameterSet> paper002Table1Sets(const ParameterSet& base);

struct SweepSettings {
  std::string model = "parameterized";
  std::string rule = "bayes-recursive";
  PoseSource pose = PoseSource::Odometry;
  GridSpec grid;  // one grid for every map (and both runs), so maps compare cell for cell
};

struct SweepRow {
  std::optional<double> vsdns;  // empty when no cell's model values varied
  std::size_t cellsWithSpread = 0;
  DerivativeNoise noise;
  std::optional<TwoRunComparison> twoRuns;  // only with a second run
};

struct SweepOutcome {
  std::vector<SweepRow> rows;  // rows[i] belongs to sets[i]
  bool completed = true;       // false when cancelled: only rows with done[i] hold results
  std::vector<bool> done;
};

// Called after each finished set with the number finished so far and the total. Calls are
// serialised but may come from any of the sweep's threads.
using SweepProgress = std::function<void(std::size_t done, std::size_t total)>;

// Maps `run` (and `secondRun`, if given) with every set. The cancel flag is checked between scans;
// a cancelled sweep returns promptly with completed = false. Throws MapperError for an unknown or
// incompatible model/rule, a reading naming a sonar the ring lacks, or --pose truth without true
// poses; the first error of any thread (or std::system_error for a thread that could not be
// started) is rethrown once every thread has stopped.
SweepOutcome runSweep(const Dataset& run, const Dataset* secondRun,
                      const std::vector<ParameterSet>& sets, const SweepSettings& settings,
                      const SweepProgress& progress = {},
                      const std::atomic<bool>* cancel = nullptr);

}  // namespace sg
