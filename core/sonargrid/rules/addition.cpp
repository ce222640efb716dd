// SPDX-License-Identifier: BSD-3-Clause

#include "sonargrid/rules/cell_updates.h"
#include "sonargrid/rules/rule_classes.h"
#include "sonargrid/rules/run_kernels.h"

namespace sg {

const RuleInfo& AdditionRule::staticInfo() {
  static const RuleInfo info{
      "addition",
      "Probability addition (simple update)",
      "paper 000 eqs 7–8; paper 001 §3.1",
      "combined Occ/Emp value (−1..1 for paper 000, 0..1 for paper 001)",
      {
          {"combine", "combine", "", 0.0, 1.0, 0.0, "paper 000 eqs 7–8 (0) or paper 001 §3.1 (1)",
           "0: Occ if Occ ≥ Emp else −Emp (range −1..1); 1: Occ if Occ > Emp, 1 − Emp if Emp > "
           "Occ, 0.5 on a tie.",
           true},
          {"normalise", "norm", "", 0.0, 1.0, 1.0, "paper 001 §3.1 (Po ← Po / ΣPo)",
           "1: each reading's occupied evidence is scaled to sum to 1 over its arc.", true},
      }};
  return info;
}

void AdditionRule::configure(const ParameterSet& p) {
  paper001Combine_ = p.get("combine") != 0.0;
  normalise_ = p.get("normalise") != 0.0;
}

void AdditionRule::apply(const Footprint& fp, Grid& grid) const {
  FootprintTotals totals;
  if (normalise_) totals.occupied = occupiedFixedPoint(fp);
  applyPart(fp, totals, grid);
}

void AdditionRule::applyPart(const Footprint& fp, const FootprintTotals& totals, Grid& grid) const {
  // The echo came from one cell of the arc, so the arc's occupied evidence shares a total of one.
  double scale = 1.0;
  if (normalise_ && totals.occupied > 0) scale = 1.0 / totals.occupiedSum();
  EmptyEvidence* const emp = grid.cells<EmptyEvidence>(0);
  OccupiedEvidence* const occ = grid.cells<OccupiedEvidence>(1);
  for (const CellEvidence& c : fp.cells) {
    cellrule::additionEmpty(c.empty, emp[c.cell]);
    cellrule::additionOccupied(c.occupied, scale, occ[c.cell]);
  }
}

void AdditionRule::applyRuns(const EvidenceRuns& runs, Grid& grid, EvidenceRuns* deferred) const {
  if (!normalise_) {
    runs::additionEmpty(runs, grid.cells<EmptyEvidence>(0));
    runs::additionOccupied(runs, 0, runs.runs.size(), grid.cells<OccupiedEvidence>(1), 1.0);
    return;
  }
  // The occupied cells wait for the reading's total (applyDeferred). A cell of no occupied evidence
  // adds nothing to it (0 or −0 in fixed point is 0) and is left as it was by the update, so each
  // run is deferred from its first cell of other occupied evidence to its last: the arc's span of
  // the run, with the occupied values alone (found eight values at a time, in the empty update's
  // pass over the runs, run_kernels.cpp).
  runs::additionEmpty(runs, grid.cells<EmptyEvidence>(0), deferred);
}

void AdditionRule::applyDeferred(const EvidenceRuns& deferred, std::size_t firstRun,
                                 std::size_t endRun, const FootprintTotals& totals,
                                 Grid& grid) const {
  // As applyPart() with the cells' empty evidence applied already.
  double scale = 1.0;
  if (normalise_ && totals.occupied > 0) scale = 1.0 / totals.occupiedSum();
  runs::additionOccupied(deferred, firstRun, endRun, grid.cells<OccupiedEvidence>(1), scale);
}

double AdditionRule::nativeOf(const EmptyEvidence& emp, const OccupiedEvidence& occ) const {
  const double o = occ.occ, e = emp.emp;
  if (paper001Combine_) {
    // Paper 001 leaves Occ = Emp undefined; "no evidence either way" is 0.5.
    if (o > e) return o;
    if (e > o) return 1.0 - e;
    return 0.5;
  }
  return o >= e ? o : -e;
}

double AdditionRule::occupancyOf(const EmptyEvidence& emp, const OccupiedEvidence& occ) const {
  const double v = nativeOf(emp, occ);
  return paper001Combine_ ? v : 0.5 * (1.0 + v);
}

}  // namespace sg
