// SPDX-License-Identifier: BSD-3-Clause
// Moravec–Elfes heuristic probability functions, as paper 000 §2.1 (eqs 1–6) and paper 001 §2.1
// print them.

#include <algorithm>
#include <cmath>
#include <limits>

#include "sonargrid/models/cone_model.h"
#include "sonargrid/models/model_classes.h"

namespace sg {
namespace {

// Per reading; S is double for evaluate() and float for the footprint (cone_model.h).
template <class S>
struct HpfShape {
  S occupiedLo, occupiedHi;  // [R − ε, R + ε]; empty without an echo
  S emptyLo, emptyHi;        // [R_min, R − ε]; empty when R − ε <= R_min
  S range, invEpsilon, rMin;
  S invEmptySpan;  // 1 / (R − ε − R_min)
  S invHalfAngle;  // 2 / ω

  template <class T>
  [[gnu::always_inline]] ConeValue<T> value(T delta, T absTheta) const {
    const T t = absTheta * invHalfAngle;
    const T angular = S(1) - t * t;  // Ea = Oa = 1 − (2θ/ω)², eqs 3 and 6
    const T dOcc = (delta - range) * invEpsilon;
    const T dEmp = (delta - rMin) * invEmptySpan;
    const auto occupied = delta >= occupiedLo && delta <= occupiedHi;
    const auto empty = delta >= emptyLo && delta <= emptyHi;
    const T pO = occupied ? (S(1) - dOcc * dOcc) * angular : T{};   // eq 5 × eq 6
    const T pE = occupied ? T{} : (S(1) - dEmp * dEmp) * angular;   // eq 2 × eq 3
    return {occupied, empty, pE, pO, S(0.5) + S(0.5) * (pO - pE)};  // fromEvidence
  }
};

class HpfModel final : public ConeModel<HpfModel> {
 public:
  static const ModelInfo& staticInfo();
  void configure(const ParameterSet& params) override;
  double reach(double maxRange) const override;
  template <class S>
  ConeBeam<HpfShape<S>> prepare(double range, double maxRange) const;

 private:
  double epsilon_ = 0.1, omega_ = 0.436, rMin_ = 0.0;
  bool noEchoFree_ = false;
};

}  // namespace

const ModelInfo& HpfModel::staticInfo() {
  static const ModelInfo info{
      "hpf",
      "Moravec–Elfes heuristic probability functions (HPF, 2-D Gaussian)",
      "paper 000 §2.1 eqs 1–6; paper 001 §2.1",
      {
          {"epsilon", "ε", "m", 0.005, 1.0, 0.10,
           "paper 000 eqs 2, 5 (ε: mean sonar deviation error)",
           "Half-width of the occupied arc; the empty region ends at R − ε."},
          {"omega", "ω", "deg", 5.0, 90.0, 25.0, "paper 000 eqs 3, 6 (ω: beam aperture)",
           "Full cone angle; Ea = Oa = 1 − (2θ/ω)²."},
          {"r_min", "R_min", "m", 0.0, 1.0, 0.0, "paper 000 eq 2 (R_min)",
           "Distance from the transducer where the empty region starts."},
          noEchoParameter(
              "free space along the cone up to the maximum range (Er with R − ε = R_max)"),
      },
      // Paper 000 §2.1 eqs 7–8: the HPF certainty grid combines readings by probability addition.
      "addition",
      {"occupied arc", "empty arc", ""}};
  return info;
}

void HpfModel::configure(const ParameterSet& p) {
  epsilon_ = p.get("epsilon");
  omega_ = degToRad(p.get("omega"));
  rMin_ = p.get("r_min");
  noEchoFree_ = p.get("no_echo") != 0.0;
}

template <class S>
ConeBeam<HpfShape<S>> HpfModel::prepare(double range, double maxRange) const {
  ConeBeam<HpfShape<S>> b;
  const bool echo = std::isfinite(range);
  if (!echo && !noEchoFree_) return b;
  b.active = true;
  b.halfAngle = omega_ / 2.0;
  // No echo: nothing within the maximum range, so the empty region runs to it and there is no
  // occupied arc.
  const double r = echo ? range : maxRange;
  const double emptyEnd = echo ? range - epsilon_ : maxRange;
  b.reach = echo ? range + epsilon_ : maxRange;
  const double span = emptyEnd - rMin_;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  HpfShape<S>& h = b.shape;
  h.occupiedLo = roundUp<S>(echo ? range - epsilon_ : kInf);
  h.occupiedHi = roundDown<S>(echo ? range + epsilon_ : -kInf);
  h.emptyLo = roundUp<S>(span > 0.0 ? rMin_ : kInf);
  h.emptyHi = roundDown<S>(span > 0.0 ? emptyEnd : -kInf);
  h.range = S(r);
  h.invEpsilon = S(1.0 / epsilon_);
  h.rMin = S(rMin_);
  h.invEmptySpan = S(span > 0.0 ? 1.0 / span : 0.0);
  h.invHalfAngle = S(2.0 / omega_);
  return b;
}

double HpfModel::reach(double maxRange) const {
  return maxRange + epsilon_;
}

std::unique_ptr<SensorModel> makeHpfModel() {
  return std::make_unique<HpfModel>();
}
const ModelInfo& hpfModelInfo() {
  return HpfModel::staticInfo();
}

}  // namespace sg
