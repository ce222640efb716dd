// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The rules' updates of a reading's runs of consecutive cells (UpdateRule::applyRuns,
// footprint.h) and of a list of cells that take one value (UpdateRule::applyUniform), several
// cells at a time in double lanes: each cell gets the very operations, in the
// same order, that the rule's apply() gives it one CellEvidence at a time, so both paths give the
// same bits. Built for the baseline and, chosen when the program starts, for AVX2
// (run_kernels.cpp).

#include <cstdint>
#include <span>

#include "sonargrid/engine/footprint.h"
#include "sonargrid/rules/rule_classes.h"

namespace sg::runs {

// AdditionRule::applyPart's empty update of every cell of the runs with c.empty > 0; with
// `deferred`, also AdditionRule::applyRuns' deferral: appends to it, for each run with occupied
// evidence, its span from the first cell whose occupied value is not ±0 (NaN counts) to the last,
// with those values alone and kRunPadding zeros past them.
void additionEmpty(const EvidenceRuns& runs, EmptyEvidence* emp, EvidenceRuns* deferred = nullptr);
// Its occupied update with `scale` (1 without normalisation; positive) of every cell with
// c.occupied > 0 of runs [firstRun, endRun), reading the runs' occupied values alone (a reading's
// deferred runs, AdditionRule::applyRuns).
void additionOccupied(const EvidenceRuns& runs, std::size_t firstRun, std::size_t endRun,
                      OccupiedEvidence* occ, double scale);
// Every cell of the runs in `cells` (the grid's plane):
// BayesRule::apply, with p = 0.5 + (pO − pE)/2 (`likelihood` false) or the model's probability.
void bayes(const EvidenceRuns& runs, BayesCell* cells, bool likelihood);
// FastBayesRule::apply: BayesRule's lanes on the float cells widened to their p and rounded back
// (cellrule::floatBayes).
void floatBayes(const EvidenceRuns& runs, BayesFloatCell* cells, bool likelihood);
// LogRule::apply.
void logProduct(const EvidenceRuns& runs, LogCell* cells);
// LogOddsRule::apply, with its configured 1/prior odds and clamp.
void logOdds(const EvidenceRuns& runs, LogOddsCell* cells, double invPrior, double minOdds,
             double maxOdds);
// DempsterShaferRule::apply.
void dempsterShafer(const EvidenceRuns& runs, DempsterShaferCell* cells);
// The rules' applyUniform: one reading's value applied to each of `cells` (grid indices, distinct)
// of the grid's plane, several cells at a time, with the bits apply() gives each. (The log rule's
// stays a scalar loop, log_rule.cpp.)
// BayesRule's, `p` being the probability apply() computes for the evidence.
void bayesUniform(double p, std::span<const std::uint32_t> cells, BayesCell* plane);
// LogOddsRule's, with its configured 1/prior odds and clamp.
void logOddsUniform(float probability, std::span<const std::uint32_t> cells, LogOddsCell* plane,
                    double invPrior, double minOdds, double maxOdds);
// DempsterShaferRule's.
void dempsterShaferUniform(float occupied, float empty, std::span<const std::uint32_t> cells,
                           DempsterShaferCell* plane);

}  // namespace sg::runs
