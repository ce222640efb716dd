#pragma once
// The concrete sensor models. Only the registry and tests need these names; everything else goes
// through SensorModel.

#include <vector>

#include "sonargrid/models/sampled_function.h"
#include "sonargrid/models/sensor_model.h"

namespace sg {

class HpfModel final : public SensorModel {
 public:
  static const ModelInfo& staticInfo();
  const ModelInfo& info() const override { return staticInfo(); }
  void configure(const ParameterSet& params) override;
  ModelValue evaluate(double delta, double theta, double range, double maxRange) const override;
  double reach(double maxRange) const override;
  void footprint(const Beam& beam, const GridSpec& grid, const BeamTables& tables,
                 Footprint& out) const override;

 private:
  double epsilon_ = 0.1, omega_ = 0.436, rMin_ = 0.0;
  bool noEchoFree_ = true;
};

class KonoligeModel final : public SensorModel {
 public:
  KonoligeModel();
  static const ModelInfo& staticInfo();
  const ModelInfo& info() const override { return staticInfo(); }
  void configure(const ParameterSet& params) override;
  ModelValue evaluate(double delta, double theta, double range, double maxRange) const override;
  double reach(double maxRange) const override;
  void footprint(const Beam& beam, const GridSpec& grid, const BeamTables& tables,
                 Footprint& out) const override;

  struct Settings {
    double omega = 0.436;            // rad, full aperture
    double falseRate = 0.05;         // F, per metre
    double attenuation = 0.6;        // a0
    double attenuationSlope = 0.4;   // k, 1/m: a(r) = a0 (1 - min(1, k r))
    double sd0 = 0.01, sd1 = 0.015;  // d(r) = d0 + d1 r, metres
    bool noEchoFree = true;
  };

 private:
  Settings s_;
  SampledFunction lobe_;  // exp(-θ²/2σ²) over |θ| in [0, ω/2]
};

class MurphyModel final : public SensorModel {
 public:
  static const ModelInfo& staticInfo();
  const ModelInfo& info() const override { return staticInfo(); }
  void configure(const ParameterSet& params) override;
  ModelValue evaluate(double delta, double theta, double range, double maxRange) const override;
  double reach(double maxRange) const override;
  void footprint(const Beam& beam, const GridSpec& grid, const BeamTables& tables,
                 Footprint& out) const override;

 private:
  double maxRange_ = 5.0, beta_ = 0.2618, tolerance_ = 0.1, maxOccupied_ = 0.98;
  bool noEchoFree_ = true;
};

class ParameterizedModel final : public SensorModel {
 public:
  static const ModelInfo& staticInfo();
  const ModelInfo& info() const override { return staticInfo(); }
  void configure(const ParameterSet& params) override;
  ModelValue evaluate(double delta, double theta, double range, double maxRange) const override;
  double reach(double maxRange) const override;
  void footprint(const Beam& beam, const GridSpec& grid, const BeamTables& tables,
                 Footprint& out) const override;

 private:
  double p1_ = 0.02, p2_ = 0.15, p3_ = 0.1, p4_ = 0.98, p5_ = 0.2618;
  bool noEchoFree_ = true;
};

class HimmModel final : public SensorModel {
 public:
  static const ModelInfo& staticInfo();
  const ModelInfo& info() const override { return staticInfo(); }
  void configure(const ParameterSet& params) override;
  ModelValue evaluate(double delta, double theta, double range, double maxRange) const override;
  double reach(double maxRange) const override;
  void footprint(const Beam& beam, const GridSpec& grid, const BeamTables& tables,
                 Footprint& out) const override;

 private:
  double pHit_ = 0.7, pMiss_ = 0.4;
  bool noEchoFree_ = true;
};

}  // namespace sg
