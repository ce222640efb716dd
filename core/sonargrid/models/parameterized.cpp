// SPDX-License-Identifier: BSD-3-Clause
// The parameterized sensor model P1–P5 (paper 002 §4, Figure 4 and eq 7). Along the acoustic axis,
// for a reading s:
//   Region II, 0 ≤ r < s − P3:  rises linearly from P1 at the sensor to 0.5 − P2
//   Region I,  |r − s| ≤ P3:    a tent from 0.5 + P2 at s ± P3 up to P4 at r = s
//   beyond s + P3:              0.5, no update
// Off the axis (eq 7, P5 the half-width): P(α) = (P5 − α)/P5 · (P(α = 0) − 0.5) + 0.5.
// P3 is in metres here (the paper's figures use the sensor's range units; notes).
// A no-echo reading is Region II all the way to the maximum range.

#include <algorithm>
#include <cmath>
#include <limits>

#include "sonargrid/models/model_classes.h"
#include "sonargrid/models/parameterized_shape.h"

namespace sg {
namespace {

class ParameterizedModel final : public ConeModel<ParameterizedModel> {
 public:
  static const ModelInfo& staticInfo();
  void configure(const ParameterSet& params) override;
  double reach(double maxRange) const override;
  template <class S>
  ConeBeam<ParameterizedShape<S>> prepare(double range, double maxRange) const {
    return prepareParameterized<S>(range, maxRange, p1_, p2_, p3_, p4_, p5_, noEchoFree_);
  }

 private:
  double p1_ = 0.02, p2_ = 0.15, p3_ = 0.1, p4_ = 0.98, p5_ = 0.2618;
  bool noEchoFree_ = false;
};

}  // namespace

const ModelInfo& ParameterizedModel::staticInfo() {
  static const ModelInfo info{
      "parameterized",
      "Parameterized sensor model (P1–P5)",
      "paper 002 §4, Figure 4, eq 7",
      {
          {"p1", "P1", "", 0.0, 0.5, 0.02, "paper 002 §4 (P1: minimum probability in Region II)",
           "Value at the transducer on the axis; the paper often ties P1 = 1 − P4."},
          {"p2", "P2", "", 0.0, 0.5, 0.15,
           "paper 002 §4 (P2: gap around 0.5 between Regions I and II)",
           "Region II ends at 0.5 − P2, Region I starts at 0.5 + P2."},
          {"p3", "P3", "m", 0.005, 3.0, 0.10, "paper 002 §4 (P3: tolerance of Region I)",
           "Half-width of Region I around the reading."},
          {"p4", "P4", "", 0.5, 1.0, 0.98, "paper 002 §4 (P4: maximum probability of occupancy)",
           "Peak of Region I at the reading."},
          {"p5", "P5", "deg", 1.0, 45.0, 15.0,
           "paper 002 eq 7 (P5: half-width of the view of focus)",
           "Half-width of the cone; values fall linearly to 0.5 at ±P5."},
          noEchoParameter(
              "Region II (P1 rising to 0.5 − P2) over the cone up to the maximum range"),
      },
      // Paper 002 §4: the parameterized model keeps Murphy's recursive Bayes (§3.3, eqs 5–6).
      "bayes-recursive",
      {"Region I", "Region II", "Region III"}};
  return info;
}

void ParameterizedModel::configure(const ParameterSet& p) {
  p1_ = p.get("p1");
  p2_ = p.get("p2");
  p3_ = p.get("p3");
  p4_ = p.get("p4");
  p5_ = degToRad(p.get("p5"));
  noEchoFree_ = p.get("no_echo") != 0.0;
}

double ParameterizedModel::reach(double maxRange) const {
  return maxRange + p3_;
}

std::unique_ptr<SensorModel> makeParameterizedModel() {
  return std::make_unique<ParameterizedModel>();
}
const ModelInfo& parameterizedModelInfo() {
  return ParameterizedModel::staticInfo();
}

}  // namespace sg
