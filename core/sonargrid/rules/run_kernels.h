// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The rules' updates of one run of consecutive cells (UpdateRule::applyRun, footprint.h), several
// cells at a time in double lanes: each cell gets the very operations, in the same order, that the
// rule's apply() gives it one CellEvidence at a time, so both paths give the same bits. Built for
// the baseline and, chosen when the program starts, for AVX2 (run_kernels.cpp).

#include "sonargrid/footprint.h"
#include "sonargrid/rules/rule_classes.h"

namespace sg::runs {

// AdditionRule::applyPart's empty update of every cell of the run with c.empty > 0.
void additionEmpty(const EvidenceRun& run, EmptyEvidence* emp);
// Its occupied update with scale 1 (no normalisation) of every cell with c.occupied > 0.
void additionOccupied(const EvidenceRun& run, OccupiedEvidence* occ);
// BayesRule::apply, with p = 0.5 + (pO − pE)/2 (`likelihood` false) or the model's probability.
void bayes(const EvidenceRun& run, BayesCell* cells, bool likelihood);
// LogRule::apply.
void logProduct(const EvidenceRun& run, LogCell* cells);
// LogOddsRule::apply, with its configured 1/prior odds and clamp.
void logOdds(const EvidenceRun& run, LogOddsCell* cells, double invPrior, double minOdds,
             double maxOdds);
// DempsterShaferRule::apply.
void dempsterShafer(const EvidenceRun& run, DempsterShaferCell* cells);

}  // namespace sg::runs
