#include "sonargrid/rules/rule_classes.h"

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

void AdditionRule::reset(std::size_t cells) {
  emp_.assign(cells, 0.0);
  occ_.assign(cells, 0.0);
}

void AdditionRule::apply(const Footprint& fp) {
  FootprintTotals totals;
  if (normalise_) totals.occupied = occupiedFixedPoint(fp);
  applyPart(fp, totals);
}

void AdditionRule::applyPart(const Footprint& fp, const FootprintTotals& totals) {
  // The echo came from one cell of the arc, so the arc's occupied evidence shares a total of one.
  double scale = 1.0;
  if (normalise_ && totals.occupied > 0) scale = 1.0 / totals.occupiedSum();
  for (const CellEvidence& c : fp.cells) {
    if (c.empty > 0.0) {
      double& e = emp_[c.cell];
      e = e + c.empty - e * c.empty;
    }
    if (c.occupied > 0.0) {
      const double po = c.occupied * scale;
      double& o = occ_[c.cell];
      o = o + po - o * po;
    }
  }
}

double AdditionRule::native(std::size_t i) const {
  const double o = occ_[i], e = emp_[i];
  if (paper001Combine_) {
    // Paper 001 leaves Occ = Emp undefined; "no evidence either way" is 0.5.
    if (o > e) return o;
    if (e > o) return 1.0 - e;
    return 0.5;
  }
  return o >= e ? o : -e;
}

double AdditionRule::occupancy(std::size_t i) const {
  const double v = native(i);
  return paper001Combine_ ? v : 0.5 * (1.0 + v);
}

void AdditionRule::writeLayers(OccupancyMap& map, std::size_t begin, std::size_t end) const {
  writeLayersOf(*this, map, begin, end);
}

}  // namespace sg
