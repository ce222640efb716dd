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

#include "sonargrid/models/cone_model.h"
#include "sonargrid/models/model_classes.h"

namespace sg {
namespace {

struct ParameterizedBeam {
  bool active = false;
  double reach = 0.0;
  double halfAngle = 0.0;  // P5 in radians
  double invHalfAngle = 0.0;
  double emptyEnd = 0.0;    // s − P3, or the maximum range without an echo
  double emptySlope = 0.0;  // (0.5 − P2 − P1) / emptyEnd
  double s = 0.0, p1 = 0.0, p2 = 0.0, p3 = 0.0, p4 = 0.0;
  double tentSlope = 0.0;  // (P4 − 0.5 − P2) / P3
  bool echo = true;

  ModelValue at(double r, double alpha) const {
    if (std::abs(alpha) > halfAngle || r > reach) return {};
    return inside(r, alpha);
  }
  ModelValue inside(double r, double alpha) const {
    const double a = std::abs(alpha);
    double axis;
    BeamRegion region;
    if (r < emptyEnd || !echo) {
      axis = p1 + emptySlope * r;
      region = BeamRegion::Empty;
    } else {
      // Tent: 0.5 + P2 at |r − s| = P3, P4 at r = s.
      axis = p4 - tentSlope * std::abs(r - s);
      region = BeamRegion::Occupied;
    }
    const double p = (halfAngle - a) * invHalfAngle * (axis - 0.5) + 0.5;  // eq 7
    ModelValue v = fromProbability(p);
    v.region = region;
    return v;
  }
};

ParameterizedBeam prepareParameterized(double range, double maxRange, double p1, double p2,
                                       double p3, double p4, double p5, bool noEchoFree) {
  ParameterizedBeam b;
  b.echo = std::isfinite(range);
  if (!b.echo && !noEchoFree) return b;
  b.active = true;
  b.halfAngle = p5;
  b.invHalfAngle = 1.0 / p5;
  b.p1 = p1, b.p2 = p2, b.p3 = p3, b.p4 = p4;
  b.tentSlope = (p4 - 0.5 - p2) / p3;
  if (b.echo) {
    b.s = range;
    b.emptyEnd = range - p3;
    b.reach = range + p3;
  } else {
    b.s = maxRange;
    b.emptyEnd = maxRange;
    b.reach = maxRange;
  }
  b.emptySlope = b.emptyEnd > 0.0 ? (0.5 - p2 - p1) / b.emptyEnd : 0.0;
  return b;
}

class ParameterizedModel final : public ConeModel<ParameterizedModel> {
 public:
  static const ModelInfo& staticInfo();
  void configure(const ParameterSet& params) override;
  double reach(double maxRange) const override;
  ParameterizedBeam prepare(double range, double maxRange) const {
    return prepareParameterized(range, maxRange, p1_, p2_, p3_, p4_, p5_, noEchoFree_);
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
      }};
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
