// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What a generic sweep (docs/sweeps.md) measures for each parameter set: any of paper 002's
// goodness measures (VSDNS, derivative noise, two runs), map entropy and any reference metric of
// reference_score.h, from one map of the log (and one of the second log for the two-run
// comparison). And the runner that evaluates a list of sets on the thread policy's threads
// (concurrency.h), each set on one thread, so that every set's result is the same at any count.

#include <atomic>
#include <cstddef>
#include <functional>
#include <optional>
#include <set>
#include <vector>

#include "sonargrid/data/dataset.h"
#include "sonargrid/engine/grid_spec.h"
#include "sonargrid/metrics/derivative_noise.h"
#include "sonargrid/metrics/map_entropy.h"
#include "sonargrid/metrics/reference_score.h"
#include "sonargrid/metrics/two_run_comparison.h"
#include "sonargrid/metrics/vsdns.h"
#include "sonargrid/params/parameters.h"
#include "sonargrid/sweep/parameter_sweep.h"

namespace sg {

struct SetMeasures {
  bool vsdns = false;
  bool derivative = false;
  bool entropy = false;        // map entropy (Martin & Moravec 1996) of the first run's map
  bool twoRun = false;         // needs a second run
  std::set<Metric> reference;  // needs a reference map
  ScoreOptions score;          // pairs and seed of the path metrics; metrics = `reference`
};

struct SetEvaluation {
  std::optional<VsdnsAccumulator::Result> vsdns;
  std::optional<DerivativeNoise> derivative;
  std::optional<MapEntropy> entropy;
  std::optional<TwoRunComparison> twoRun;
  std::optional<ReferenceScore> reference;
};

struct SetEvaluationInput {
  const Dataset* run = nullptr;
  const Dataset* secondRun = nullptr;       // required by measures.twoRun
  const ReferenceMap* reference = nullptr;  // required by measures.reference
  SweepSettings settings;                   // model, rule, pose, grid (for both runs)
  SetMeasures measures;
};

// Maps and measures one set with the mapper's threads (the thread policy's count; bit-identical
// at any count). Returns empty when `cancel` was set before it finished. Throws MapperError (bad
// model/rule, --pose truth without true poses), MetricsError (nothing of the reference on the grid)
// and std::invalid_argument for a missing run or reference.
std::optional<SetEvaluation> evaluateSet(const SetEvaluationInput& input, const ParameterSet& set,
                                         const std::atomic<bool>* cancel = nullptr);

// Evaluates sets[indices[k]] for every k on the thread policy's threads (parallelThreads()): in
// batches of sets mapped together where batch_evaluation.h serves the model, rule and measures,
// otherwise each set on one thread, scan by scan (which Mapper guarantees bit-identical to its
// batch map). Either way every evaluation equals evaluateSet()'s, bit for bit. Each finished one is
// handed to `finished(k, evaluation)`, calls serialised (under one lock) but in any order and from
// any of the threads. Returns true when every index was evaluated, false when `cancel` stopped it.
// The first error of any thread (or of `finished`) stops the others and is rethrown once all have
// stopped.
using SetFinished = std::function<void(std::size_t k, const SetEvaluation& evaluation)>;
bool evaluateSets(const SetEvaluationInput& input, const std::vector<ParameterSet>& sets,
                  const std::vector<std::size_t>& indices, const SetFinished& finished,
                  const std::atomic<bool>* cancel = nullptr);

// What evaluateSet() and the batched path share. checkSetEvaluationInput() throws what
// evaluateSet() throws for a missing run, second run or reference and for --pose truth without true
// poses. mapsNeeded(): whether a measure reads the map (all but VSDNS). measureSet() gives the
// evaluation from VSDNS's result (when measured) and the set's map of each run (`first` when
// mapsNeeded(), `second` with the two-run comparison).
void checkSetEvaluationInput(const SetEvaluationInput& input);
bool mapsNeeded(const SetMeasures& measures);
SetEvaluation measureSet(const SetEvaluationInput& input,
                         const std::optional<VsdnsAccumulator::Result>& vsdns,
                         const OccupancyMap* first, const OccupancyMap* second);

}  // namespace sg
