// SPDX-License-Identifier: BSD-3-Clause
// The HIMM beam (paper 000 §2.2): only the acoustic axis. The cell holding the echo gets occupied
// evidence, the cells between the sensor and it free evidence; the HIMM rule turns these into +I⁺
// and −I⁻. For the probabilistic rules the two kinds carry OctoMap's hit and miss probabilities,
// which makes HIMM-with-log-odds the ray-casting update of OctoMap.

#include <cmath>
#include <limits>

#include "sonargrid/models/cone_model.h"
#include "sonargrid/models/model_classes.h"

namespace sg {
namespace {

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
  bool noEchoFree_ = false;
};

}  // namespace

const ModelInfo& HimmModel::staticInfo() {
  static const ModelInfo info{
      "himm",
      "HIMM acoustic-axis model",
      "paper 000 §2.2",
      {
          {"p_hit", "p_hit", "", 0.5, 1.0, 0.7,
           "OctoMap default (AbstractOccupancyOcTree: hit 0.7)",
           "P(occ | reading) of the echo cell for the probabilistic rules; the himm rule only "
           "needs it above 0.5."},
          {"p_miss", "p_miss", "", 0.0, 0.5, 0.4,
           "OctoMap default (AbstractOccupancyOcTree: miss 0.4)",
           "P(occ | reading) of the axis cells before the echo; the himm rule only needs it below "
           "0.5."},
          noEchoParameter("free evidence on every axis cell up to the maximum range"),
      },
      // Paper 000 §2.2: the histogram grid is HIMM's own update (I⁺ on the axis cell, I⁻ before).
      "himm",
      {"I⁺ cell", "I⁻ cells", ""}};
  return info;
}

void HimmModel::configure(const ParameterSet& p) {
  pHit_ = p.get("p_hit");
  pMiss_ = p.get("p_miss");
  noEchoFree_ = p.get("no_echo") != 0.0;
}

ModelValue HimmModel::evaluate(double delta, double theta, double range, double maxRange) const {
  // On a continuous plane the axis is a line of zero width: the view draws it as such.
  constexpr double kAxis = 1e-9;
  if (std::abs(theta) > kAxis || delta < 0.0) return {};
  const bool echo = std::isfinite(range);
  if (echo && std::abs(delta - range) <= kAxis) return fromProbability(pHit_);
  if ((echo && delta < range) || (!echo && noEchoFree_ && delta <= maxRange)) {
    ModelValue v = fromProbability(pMiss_);
    v.region = BeamRegion::Empty;
    return v;
  }
  return {};
}

double HimmModel::reach(double maxRange) const {
  return maxRange;
}

void HimmModel::footprint(const Beam& beam, const GridSpec& grid, const BeamTables& /*tables*/,
                          Footprint& out) const {
  const bool echo = beam.echo();
  if (!echo && !noEchoFree_) return;
  const double length = echo ? beam.range : beam.maxRange;
  const ModelValue hit = fromProbability(pHit_);
  ModelValue miss = fromProbability(pMiss_);

  // Grid traversal of the axis segment (Amanatides & Woo 1987) in cell units: every cell the
  // segment passes through, in order from the sensor, each once.
  const double c = grid.cellSize;
  const double u0 = (beam.sensor.x() - grid.origin.x()) / c;
  const double v0 = (beam.sensor.y() - grid.origin.y()) / c;
  const double du = std::cos(beam.sensor.heading) * length / c;
  const double dv = std::sin(beam.sensor.heading) * length / c;
  int ix = static_cast<int>(std::floor(u0));
  int iy = static_cast<int>(std::floor(v0));
  const int endX = static_cast<int>(std::floor(u0 + du));
  const int endY = static_cast<int>(std::floor(v0 + dv));
  const int stepX = du > 0 ? 1 : -1;
  const int stepY = dv > 0 ? 1 : -1;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const double tDeltaX = du != 0.0 ? 1.0 / std::abs(du) : kInf;
  const double tDeltaY = dv != 0.0 ? 1.0 / std::abs(dv) : kInf;
  double tMaxX = du != 0.0 ? (stepX > 0 ? ix + 1 - u0 : u0 - ix) * tDeltaX : kInf;
  double tMaxY = dv != 0.0 ? (stepY > 0 ? iy + 1 - v0 : v0 - iy) * tDeltaY : kInf;
  const int steps = std::abs(endX - ix) + std::abs(endY - iy);

  // The cells are written through a pointer, sized once: steps + 1 cells at most (those outside
  // the grid are skipped). The step is chosen without a branch, as it follows the slope's pattern,
  // which a branch predictor misses about once a cell; the arithmetic is that of Amanatides & Woo,
  // so the cells are the same.
  const std::size_t start = out.cells.size();
  out.cells.resize(start + static_cast<std::size_t>(steps) + 1);
  CellEvidence* dst = out.cells.data() + start;
  const auto width = static_cast<unsigned>(grid.width);
  const auto height = static_cast<unsigned>(grid.height);
  const CellEvidence free(0, miss.empty, miss.occupied, miss.probability);
  auto emit = [&](int x, int y, const CellEvidence& v) {
    *dst = v;
    dst->cell = static_cast<std::uint32_t>(y * grid.width + x);
    dst += static_cast<unsigned>(x) < width && static_cast<unsigned>(y) < height ? 1 : 0;
  };
  for (int k = 0; k < steps; ++k) {
    emit(ix, iy, free);
    const bool alongX = tMaxX < tMaxY;
    ix += alongX ? stepX : 0;
    iy += alongX ? 0 : stepY;
    const double nextX = tMaxX + tDeltaX, nextY = tMaxY + tDeltaY;
    tMaxX = alongX ? nextX : tMaxX;
    tMaxY = alongX ? tMaxY : nextY;
  }
  const ModelValue& last = echo ? hit : miss;
  emit(ix, iy, CellEvidence(0, last.empty, last.occupied, last.probability));
  out.cells.resize(static_cast<std::size_t>(dst - out.cells.data()));
}

std::unique_ptr<SensorModel> makeHimmModel() {
  return std::make_unique<HimmModel>();
}
const ModelInfo& himmModelInfo() {
  return HimmModel::staticInfo();
}

}  // namespace sg
