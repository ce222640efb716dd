// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The batched sweep (docs/sweeps.md, "Sweep time"): many parameter sets mapped in one pass over the
// log. Each reading's placement (the sensor's pose) is computed once per log; the cells of its cone
// once per batch of kBatchLanes sets, at the widest cone of the batch; every cell keeps the state
// of all the batch's sets side by side ([cell][set]: the Welford count, mean and M2 of VSDNS and
// the recursive Bayes posterior), so one cell's sets are updated together in vector lanes. Each
// set's values go through exactly the operations of one map (the model's formula in the same float
// lanes, the same Welford and Bayes steps in double, each set's own cells), so every result is
// bit-identical to evaluateSet() (tests/core/tst_batch_evaluation.cpp checks it field by field).
//
// It serves the `parameterized` model (paper 002 §4) with the `bayes-recursive` rule, and with any
// rule when VSDNS is the only measure (VSDNS reads the model's values, not the map). Any other
// model or rule goes through evaluateSet() set by set; evaluateSets() chooses.

#include <atomic>
#include <cstddef>
#include <vector>

#include "sonargrid/sweep/set_evaluation.h"

namespace sg {

// Sets per batch: a cell's state for all of them is one 64-byte vector per quantity.
inline constexpr std::size_t kBatchLanes = 8;

// Whether the batched path serves `input` (its model, rule and measures).
bool batchEvaluable(const SetEvaluationInput& input);

// evaluateSets() on the batched path (its contract, its callbacks). Sets of a similar cone (the
// same P5 and P3 first) share a batch; a set's row does not depend on the others of its batch, nor
// on the thread count. Throws std::invalid_argument when !batchEvaluable(input).
bool evaluateSetsBatched(const SetEvaluationInput& input, const std::vector<ParameterSet>& sets,
                         const std::vector<std::size_t>& indices, const SetFinished& finished,
                         const std::atomic<bool>* cancel = nullptr);

}  // namespace sg
