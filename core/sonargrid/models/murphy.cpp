// SPDX-License-Identifier: BSD-3-Clause
// Murphy's standard sonar model (paper 002 §3.1, eqs 1–4, after Murphy 2000). For a cell at range r
// and angle α inside the cone (|α| ≤ β):
//   v = ((R − r)/R + (β − α)/β) / 2
//   Region I  (|r − s| ≤ tolerance):  P(s|Occ) = v · Max_occ           (eq 1)
//   Region II (r < s − tolerance):    P(s|Emp) = v, P(s|Occ) = 1 − v   (eqs 3–4)
//   Region III (beyond):              no update.
// P(s|Occ) is clamped to [1 − Max_occ, Max_occ] so no cell becomes absorbing (notes). Kept as
// printed, including what paper 002 §3.2 criticises: Region I values below 0.5 at the cone's
// corners and Region II values above 0.5 near r = R, α = β.
// As evidence (for addition, log and Dempster–Shafer) the model gives Murphy's own belief masses:
// m(occ) = P(s|Occ) in Region I, m(emp) = P(s|Emp) in Region II.

#include <algorithm>
#include <cmath>
#include <limits>

#include "sonargrid/models/cone_model.h"
#include "sonargrid/models/model_classes.h"

namespace sg {
namespace {

// Per reading; S is double for evaluate() and float for the footprint (cone_model.h).
template <class S>
struct MurphyShape {
  S occupiedLo, occupiedHi;  // Region I: |r − s| <= tolerance; empty without an echo
  S emptyBelow;              // Region II: r < s − tolerance; everywhere without an echo
  S R, beta, maxOcc, minOcc;
  S halfInvR, halfInvBeta;  // 1/(2R), 1/(2β): no division per cell

  template <class T>
  [[gnu::always_inline]] ConeValue<T> value(T r, T a) const {
    // v <= 1 as r, a >= 0, so only its lower clamp can bind (and v · Max_occ <= Max_occ).
    const T v = lanes::max(T{}, (R - r) * halfInvR + (beta - a) * halfInvBeta);
    const auto occupied = r >= occupiedLo && r <= occupiedHi;
    const T pOcc = lanes::max(v * maxOcc, T{} + minOcc);
    const T pE = occupied ? T{} : lanes::min(v, T{} + maxOcc);
    const T pO = occupied ? pOcc : T{};
    const T p = occupied ? pOcc : lanes::clamp(S(1) - v, T{} + minOcc, T{} + maxOcc);
    return {occupied, r < emptyBelow, pE, pO, p};
  }
};

template <class S>
ConeBeam<MurphyShape<S>> prepareMurphy(double range, double maxRange, double R, double beta,
                                       double tolerance, double maxOcc, bool noEchoFree) {
  ConeBeam<MurphyShape<S>> b;
  const bool echo = std::isfinite(range);
  if (!echo && !noEchoFree) return b;
  b.active = true;
  b.halfAngle = beta;
  b.reach = echo ? range + tolerance : std::min(maxRange, R);
  constexpr double kInf = std::numeric_limits<double>::infinity();
  MurphyShape<S>& m = b.shape;
  m.occupiedLo = roundUp<S>(echo ? range - tolerance : kInf);
  m.occupiedHi = roundDown<S>(echo ? range + tolerance : -kInf);
  // r < x is r < the float x rounds up to, for a float r.
  m.emptyBelow = roundUp<S>(echo ? range - tolerance : kInf);
  m.R = S(R);
  m.beta = S(beta);
  m.maxOcc = S(maxOcc);
  m.minOcc = S(1.0 - maxOcc);
  m.halfInvR = S(0.5 / R);
  m.halfInvBeta = S(0.5 / beta);
  return b;
}

class MurphyModel final : public ConeModel<MurphyModel> {
 public:
  static const ModelInfo& staticInfo();
  void configure(const ParameterSet& params) override;
  double reach(double maxRange) const override;
  template <class S>
  ConeBeam<MurphyShape<S>> prepare(double range, double maxRange) const {
    return prepareMurphy<S>(range, maxRange, maxRange_, beta_, tolerance_, maxOccupied_,
                            noEchoFree_);
  }

 private:
  double maxRange_ = 5.0, beta_ = 0.2618, tolerance_ = 0.1, maxOccupied_ = 0.98;
  bool noEchoFree_ = false;
};

}  // namespace

const ModelInfo& MurphyModel::staticInfo() {
  static const ModelInfo info{
      "murphy",
      "Murphy standard sonar model",
      "paper 002 §3.1 eqs 1–4 (after Murphy 2000)",
      {
          {"max_range", "R", "m", 0.5, 20.0, 5.0, "paper 002 eqs 1, 4 (R: maximum sensing range)",
           "R in eqs 1 and 4: the distance term (R − r)/R falls to 0 here; separate from the log's "
           "range."},
          {"beta", "β", "deg", 1.0, 45.0, 15.0, "paper 002 eqs 1, 4 (β: half the cone width)",
           "Half-width of the cone."},
          {"tolerance", "tol", "m", 0.005, 2.0, 0.10, "paper 002 §3.1 (thickness of Region I)",
           "Half-width of Region I around the reading."},
          {"max_occupied", "Max_occ", "", 0.5, 0.999, 0.98, "paper 002 eq 1 (Max_occupied = 0.98)",
           "Ceiling of P(s|Occ); also the clamp that keeps cells from becoming absorbing."},
          noEchoParameter("Region II (free) over the cone up to min(R, maximum range)"),
      },
      // Paper 002 §3.3: Murphy's model is combined by recursive Bayesian updating (eqs 5–6).
      "bayes-recursive",
      {"Region I", "Region II", "Region III"}};
  return info;
}

void MurphyModel::configure(const ParameterSet& p) {
  maxRange_ = p.get("max_range");
  beta_ = degToRad(p.get("beta"));
  tolerance_ = p.get("tolerance");
  maxOccupied_ = p.get("max_occupied");
  noEchoFree_ = p.get("no_echo") != 0.0;
}

double MurphyModel::reach(double maxRange) const {
  // An echo is nearer than the transducer's maximum and writes to range + tolerance; no echo clears
  // to min(maxRange, R). The model's R never takes a beam further (it only shapes eq 1), so a 20 m
  // R must not size the tables for 20 m.
  return maxRange + tolerance_;
}

std::unique_ptr<SensorModel> makeMurphyModel() {
  return std::make_unique<MurphyModel>();
}
const ModelInfo& murphyModelInfo() {
  return MurphyModel::staticInfo();
}

}  // namespace sg
