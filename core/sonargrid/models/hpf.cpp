// Moravec–Elfes heuristic probability functions, as paper 000 §2.1 (eqs 1–6) and paper 001 §2.1
// print them.

#include <algorithm>
#include <cmath>

#include "sonargrid/models/cone_model.h"
#include "sonargrid/models/model_classes.h"

namespace sg {
namespace {

struct HpfBeam {
  bool active = false;
  double reach = 0.0;
  double halfAngle = 0.0;
  double range = 0.0;  // R, or the maximum range for a no-echo reading
  bool echo = true;
  double epsilon = 0.0;
  double invEpsilon = 0.0;
  double rMin = 0.0;
  double invEmptySpan = 0.0;  // 1 / (R - ε - R_min); 0 when the empty region is empty
  double emptyEnd = 0.0;      // R - ε
  double invHalfAngle = 0.0;  // 2 / ω

  ModelValue at(double delta, double theta) const {
    if (std::abs(theta) > halfAngle || delta > reach) return {};
    return inside(delta, theta);
  }
  ModelValue inside(double delta, double theta) const {
    const double t = theta * invHalfAngle;
    const double angular = 1.0 - t * t;  // Ea = Oa = 1 - (2θ/ω)², eqs 3 and 6
    if (echo && delta >= range - epsilon && delta <= range + epsilon) {
      const double d = (delta - range) * invEpsilon;
      return fromEvidence(BeamRegion::Occupied, 0.0, (1.0 - d * d) * angular);  // eq 5 × eq 6
    }
    if (invEmptySpan > 0.0 && delta >= rMin && delta <= emptyEnd) {
      const double d = (delta - rMin) * invEmptySpan;
      return fromEvidence(BeamRegion::Empty, (1.0 - d * d) * angular, 0.0);  // eq 2 × eq 3
    }
    return {};
  }
};

class HpfModel final : public ConeModel<HpfModel> {
 public:
  static const ModelInfo& staticInfo();
  void configure(const ParameterSet& params) override;
  double reach(double maxRange) const override;
  HpfBeam prepare(double range, double maxRange) const;

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
      }};
  return info;
}

void HpfModel::configure(const ParameterSet& p) {
  epsilon_ = p.get("epsilon");
  omega_ = degToRad(p.get("omega"));
  rMin_ = p.get("r_min");
  noEchoFree_ = p.get("no_echo") != 0.0;
}

namespace {
HpfBeam prepareHpf(double range, double maxRange, double epsilon, double omega, double rMin,
                   bool noEchoFree) {
  HpfBeam b;
  b.echo = std::isfinite(range);
  if (!b.echo && !noEchoFree) return b;
  b.active = true;
  b.halfAngle = omega / 2.0;
  b.invHalfAngle = 2.0 / omega;
  b.epsilon = epsilon;
  b.invEpsilon = 1.0 / epsilon;
  b.rMin = rMin;
  if (b.echo) {
    b.range = range;
    b.emptyEnd = range - epsilon;
    b.reach = range + epsilon;
  } else {
    // No echo: nothing within the maximum range, so the empty region runs to it and there is no
    // occupied arc.
    b.range = maxRange;
    b.emptyEnd = maxRange;
    b.reach = maxRange;
  }
  const double span = b.emptyEnd - rMin;
  b.invEmptySpan = span > 0.0 ? 1.0 / span : 0.0;
  return b;
}
}  // namespace

HpfBeam HpfModel::prepare(double range, double maxRange) const {
  return prepareHpf(range, maxRange, epsilon_, omega_, rMin_, noEchoFree_);
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
