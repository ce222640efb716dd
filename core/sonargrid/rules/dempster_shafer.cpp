// SPDX-License-Identifier: BSD-3-Clause
// Dempster–Shafer combination over the frame {occupied, empty} (Murphy, Introduction to AI
// Robotics, 2000, §11.4; none of the three papers implements it). A reading's masses are
// m(occ) = pO, m(emp) = pE, m(unknown) = 1 − pO − pE. Dempster's rule:
//   K = m1(occ) m2(emp) + m1(emp) m2(occ)
//   m(occ) = (m1(occ) m2(occ) + m1(occ) m2(unk) + m1(unk) m2(occ)) / (1 − K)
//   m(emp) likewise, m(unk) = m1(unk) m2(unk) / (1 − K).
// p(occ) is the pignistic probability m(occ) + m(unk)/2.

#include <algorithm>

#include "sonargrid/rules/rule_classes.h"

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
  for (const CellEvidence& c : fp.cells) {
    double o = std::clamp(static_cast<double>(c.occupied), 0.0, 1.0);
    double e = std::clamp(static_cast<double>(c.empty), 0.0, 1.0);
    DempsterShaferCell& m = cells[c.cell];
    double& mo = m.occ;
    double& me = m.emp;
    // Every model gives a cell one kind of evidence; Dempster's rule then shortens to
    //   m(occ) = (m(occ) + m(unk) o) / (1 − m(emp) o),  m(emp) = m(emp)(1 − o) / (1 − m(emp) o)
    // (and symmetrically for e): the general form below with e = 0, in fewer operations.
    if (e == 0.0) {
      const double denominator = 1.0 - me * o;
      if (denominator <= 0.0) continue;  // total conflict, see below
      const double inv = 1.0 / denominator;
      const double mu = 1.0 - mo - me;
      mo = (mo + mu * o) * inv;
      me = me * (1.0 - o) * inv;
      continue;
    }
    if (o == 0.0) {
      const double denominator = 1.0 - mo * e;
      if (denominator <= 0.0) continue;
      const double inv = 1.0 / denominator;
      const double mu = 1.0 - mo - me;
      me = (me + mu * e) * inv;
      mo = mo * (1.0 - e) * inv;
      continue;
    }
    if (o + e > 1.0) {  // masses must sum to at most one
      const double s = o + e;
      o /= s;
      e /= s;
    }
    const double u = 1.0 - o - e;
    const double mu = 1.0 - mo - me;
    const double conflict = mo * e + me * o;
    // Total conflict (a certain cell meets certain opposite evidence) leaves Dempster's rule
    // undefined; the cell keeps its masses.
    if (conflict >= 1.0) continue;
    const double norm = 1.0 / (1.0 - conflict);
    const double newOcc = (mo * o + mo * u + mu * o) * norm;
    const double newEmp = (me * e + me * u + mu * e) * norm;
    mo = newOcc;
    me = newEmp;
  }
}

double DempsterShaferRule::occupancyOf(const DempsterShaferCell& c) const {
  const double mu = 1.0 - c.occ - c.emp;
  return c.occ + 0.5 * mu;
}

}  // namespace sg
