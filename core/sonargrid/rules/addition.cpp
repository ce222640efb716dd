// SPDX-License-Identifier: BSD-3-Clause
#include <algorithm>

#include "sonargrid/models/lanes.h"
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
  runs::additionEmpty(runs, grid.cells<EmptyEvidence>(0));
  if (!normalise_) {
    runs::additionOccupied(runs, grid.cells<OccupiedEvidence>(1), 1.0);
    return;
  }
  // The occupied cells wait for the reading's total (applyDeferred). A cell of no occupied evidence
  // adds nothing to it (0 or −0 in fixed point is 0) and is left as it was by the update, so each
  // run is deferred from its first cell of other occupied evidence to its last: the arc's span of
  // the run, with the occupied values alone. Most of a cone is not on the arc: eight values at a
  // time are first tested for being all zero (the vector == holds for ±0 and not for NaN or
  // denormals, as the scalar == does; nothing in the program sets the CPU to treat denormals as
  // zero).
  std::size_t used = deferred->valuesEnd();
  auto zeros = [](const float* p) {
    const lanes::Floats lo = lanes::load(p), hi = lanes::load(p + 4);
    return lanes::all((lo == lanes::Floats{}) & (hi == lanes::Floats{}));
  };
  for (const EvidenceRuns::Run& run : runs.runs) {
    const float* const occupied = runs.occupied.data() + run.first;
    int lo = 0, hi = run.count;
    while (lo + 8 <= hi && zeros(occupied + lo)) lo += 8;
    while (lo < hi && occupied[lo] == 0.0f) ++lo;
    if (lo == hi) continue;
    while (hi - 8 >= lo && zeros(occupied + hi - 8)) hi -= 8;
    while (occupied[hi - 1] == 0.0f) --hi;  // stops at lo at the latest
    const auto count = static_cast<std::size_t>(hi - lo);
    // kRunPadding values of room past the span, zeros, which the lanes read from a short run's
    // start and throw away (footprint.h, run_kernels).
    const std::size_t room = used + count + kRunPadding;
    if (deferred->occupied.size() < room) deferred->occupied.resize(room);
    std::copy_n(occupied + lo, count, deferred->occupied.data() + used);
    std::fill_n(deferred->occupied.data() + used + count, kRunPadding, 0.0f);
    deferred->runs.push_back(
        {run.cell + static_cast<std::uint32_t>(lo), hi - lo, static_cast<std::uint32_t>(used)});
    used += count;
  }
}

void AdditionRule::applyDeferred(const EvidenceRuns& deferred, const FootprintTotals& totals,
                                 Grid& grid) const {
  // As applyPart() with the cells' empty evidence applied already.
  double scale = 1.0;
  if (normalise_ && totals.occupied > 0) scale = 1.0 / totals.occupiedSum();
  runs::additionOccupied(deferred, grid.cells<OccupiedEvidence>(1), scale);
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
