// SPDX-License-Identifier: BSD-3-Clause
// Dempster–Shafer combination over the frame {occupied, empty} (Murphy, Introduction to AI
// Robotics, 2000, §11.4; none of the three papers implements it). A reading's masses are
// m(occ) = pO, m(emp) = pE, m(unknown) = 1 − pO − pE. Dempster's rule:
//   K = m1(occ) m2(emp) + m1(emp) m2(occ)
//   m(occ) = (m1(occ) m2(occ) + m1(occ) m2(unk) + m1(unk) m2(occ)) / (1 − K)
//   m(emp) likewise, m(unk) = m1(unk) m2(unk) / (1 − K).
// p(occ) is the pignistic probability m(occ) + m(unk)/2.

#include <algorithm>

#include "sonargrid/rules/cell_updates.h"
#include "sonargrid/rules/rule_classes.h"
#include "sonargrid/rules/run_kernels.h"

namespace sg {

const RuleInfo& DempsterShaferRule::staticInfo() {
  static const RuleInfo info{"dempster-shafer",
                             "Dempster–Shafer",
                             "Murphy 2000 §11.4 (Dempster's rule of combination)",
                             "m(occ) − m(emp)",
                             {}};
  return info;
}

void DempsterShaferRule::configure(const ParameterSet& /*params*/) {}

void DempsterShaferRule::apply(const Footprint& fp, Grid& grid) const {
  DempsterShaferCell* const cells = grid.cells<DempsterShaferCell>();
  for (const CellEvidence& c : fp.cells)
    cellrule::dempsterShafer(c.occupied, c.empty, cells[c.cell]);
}

bool DempsterShaferRule::applyUniform(const CellEvidence& evidence,
                                      std::span<const std::uint32_t> cells, Grid& grid) const {
  runs::dempsterShaferUniform(evidence.occupied, evidence.empty, cells,
                              grid.cells<DempsterShaferCell>());
  return true;
}

void DempsterShaferRule::applyRuns(const EvidenceRuns& runs, Grid& grid,
                                   EvidenceRuns* /*deferred*/) const {
  runs::dempsterShafer(runs, grid.cells<DempsterShaferCell>());
}

double DempsterShaferRule::occupancyOf(const DempsterShaferCell& c) const {
  const auto m = c.masses<double>();
  return m.occ + 0.5 * m.unk;
}

double DempsterShaferRule::nativeOf(const DempsterShaferCell& c) const {
  const auto m = c.masses<double>();
  return m.occ - m.emp;
}

bool DempsterShaferRule::filledOf(const DempsterShaferCell& c) const {
  const auto m = c.masses<double>();
  return m.occ > m.emp;
}

}  // namespace sg
