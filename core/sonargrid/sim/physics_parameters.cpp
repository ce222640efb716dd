// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/sim/physics_parameters.h"

#include <cmath>

namespace sg {
namespace {

namespace d = physics_default;

std::vector<ParameterSpec> makeSpecs() {
  const std::string polaroid =
      "Polaroid (SensComp) 6500 Series Sonar Ranging Module technical specifications";
  return {
      {"noise", "σ", "m", 0.0, 1.0, d::kNoise, polaroid + ": typical accuracy ±1 % of the reading",
       "standard deviation of the Gaussian range noise added to every echo"},
      {"specular_limit", "θs", "deg", 0.0, 90.0, d::kSpecularLimitDeg,
       "Kuc & Siegel 1987 (IEEE PAMI 9(6)): smooth surfaces reflect specularly; Cao & Borenstein "
       "2002 (SPIE 4715): Polaroid sonars hear flat walls up to ±42° off the normal",
       "per ray: a surface met further than this from its normal reflects the sound away"},
      {"multipath", "", "", 0.0, 1.0, d::kMultipath ? 1.0 : 0.0,
       "Kuc & Siegel 1987; Leonard & Durrant-Whyte 1992 ch. 2: specular walls give long readings",
       "1: a reflected ray is traced on and may echo from a later surface; 0: it is lost", true},
      {"max_bounces", "", "", 0.0, 10.0, static_cast<double>(d::kMaxBounces),
       "modelling choice, mild end: one reflection gives the corner echo",
       "multipath: reflections followed before a ray is given up", true},
      {"reflection_loss", "", "dB", 0.0, 60.0, d::kReflectionLossDb,
       "modelling choice, mild end: no measured loss per reflection is at hand",
       "multipath: decibels lost per reflection, against the spreading margin 20 log10(max/r)"},
      {"misread_rate", "", "", 0.0, 1.0, d::kMisreadRate,
       "modelling choice, mild end: no measured rate; Siegwart & Nourbakhsh 2004 §5.2.1 bound "
       "random inter-sonar errors at under 1 %",
       "probability that a reading is a phantom range, uniform over the range window"},
      {"crosstalk_rate", "", "", 0.0, 1.0, d::kCrosstalkRate,
       "modelling choice, mild end: Borenstein & Koren 1995 (IEEE T-RA 11(1)) describe ring "
       "crosstalk without a rate",
       "probability that a sonar also hears a ring neighbour's echo"},
      {"rays", "", "", 1.0, 1000.0, static_cast<double>(d::kRaysPerCone),
       "modelling choice: 3.125° apart in a 25° cone", "rays sampling each cone, edge to edge",
       true},
      {"min_range", "", "m", 0.0, 100.0, d::kMinRange, polaroid + ": from 6 inches",
       "readings below this read as this"},
      {"max_range", "", "m", 0.01, 100.0, d::kMaxRange, polaroid + ": to 35 ft, rounded down",
       "readings at or beyond this are no echo"},
      {"drift_wheel_scale", "", "", 0.0, 0.1, d::kDriftWheelScale,
       "modelling choice after UMBmark (Borenstein & Feng 1996, IEEE T-RA 12(6))",
       "with drift on: left wheel reads this much long, right wheel this much short"},
      {"drift_wheelbase_scale", "", "", 0.0, 0.1, d::kDriftWheelbaseScale,
       "modelling choice after UMBmark (Borenstein & Feng 1996)",
       "with drift on: relative error of the wheelbase odometry assumes"},
      {"drift_wheel_noise", "", "m/√m", 0.0, 0.1, d::kDriftWheelNoise,
       "modelling choice after UMBmark (Borenstein & Feng 1996)",
       "with drift on: random error of each wheel's distance, per square root of a metre"},
  };
}

ParameterSet withValues(std::initializer_list<std::pair<const char*, double>> values) {
  ParameterSet set = defaultPhysicsParameters();
  for (const auto& [name, value] : values) set.set(name, value);
  return set;
}

}  // namespace

const std::vector<ParameterSpec>& physicsParameterSpecs() {
  static const std::vector<ParameterSpec> specs = makeSpecs();
  return specs;
}

ParameterSet defaultPhysicsParameters() {
  return ParameterSet(physicsParameterSpecs());
}

const std::vector<std::string>& physicsPresetNames() {
  static const std::vector<std::string> names{"clean", "default", "harsh"};
  return names;
}

std::optional<ParameterSet> physicsPreset(const std::string& name) {
  if (name == "default") return defaultPhysicsParameters();
  // Every surface echoes, within the cone, and nothing else is heard; the sensor's noise stays.
  if (name == "clean")
    return withValues({{"specular_limit", 90.0},
                       {"multipath", 0.0},
                       {"misread_rate", 0.0},
                       {"crosstalk_rate", 0.0}});
  // `simulate`'s settings before the declaration (and so the bundled logs until issue 16).
  if (name == "harsh")
    return withValues({{"specular_limit", 20.0},
                       {"multipath", 1.0},
                       {"max_bounces", 3.0},
                       {"reflection_loss", 0.0},
                       {"misread_rate", 0.01},
                       {"crosstalk_rate", 0.0}});
  return std::nullopt;
}

void applyPhysics(const ParameterSet& values, SonarPhysics& physics, SonarRing& ring) {
  physics.rangeNoiseSd = values.get("noise");
  physics.maxIncidenceDeg = values.get("specular_limit");
  physics.specularEcho =
      values.get("multipath") != 0.0 ? SpecularEcho::Multipath : SpecularEcho::None;
  physics.maxBounces = static_cast<int>(values.get("max_bounces"));
  physics.reflectionLossDb = values.get("reflection_loss");
  physics.misreadRate = values.get("misread_rate");
  physics.crosstalkRate = values.get("crosstalk_rate");
  physics.raysPerCone = static_cast<int>(values.get("rays"));
  ring.minRange = values.get("min_range");
  ring.maxRange = values.get("max_range");
}

OdometryErrors driftErrors(const ParameterSet& values) {
  OdometryErrors e;
  e.leftScale = values.get("drift_wheel_scale");
  e.rightScale = -values.get("drift_wheel_scale");
  e.wheelbaseScale = values.get("drift_wheelbase_scale");
  e.wheelNoise = values.get("drift_wheel_noise");
  return e;
}

ParameterSet physicsParameters(const SonarPhysics& physics, const SonarRing& ring,
                               const OdometryErrors& drift) {
  ParameterSet set = defaultPhysicsParameters();
  set.set("noise", physics.rangeNoiseSd);
  set.set("specular_limit", physics.maxIncidenceDeg);
  set.set("multipath", physics.specularEcho == SpecularEcho::Multipath ? 1.0 : 0.0);
  set.set("max_bounces", physics.maxBounces);
  set.set("reflection_loss", physics.reflectionLossDb);
  set.set("misread_rate", physics.misreadRate);
  set.set("crosstalk_rate", physics.crosstalkRate);
  set.set("rays", physics.raysPerCone);
  set.set("min_range", ring.minRange);
  set.set("max_range", ring.maxRange);
  set.set("drift_wheel_scale", drift.leftScale);
  set.set("drift_wheelbase_scale", drift.wheelbaseScale);
  set.set("drift_wheel_noise", drift.wheelNoise);
  return set;
}

}  // namespace sg
