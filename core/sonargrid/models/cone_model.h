#pragma once
// The shape every cone model shares: a per-reading `Prepared` beam (constants hoisted out of the
// cell loop) whose `at(delta, theta)` is the model. evaluate() and footprint() both go through it,
// so what the beam-model view shows is exactly what the mapper writes.

#include "sonargrid/models/cone_raster.h"
#include "sonargrid/models/sensor_model.h"

namespace sg {

// Prepared must provide: bool active; double reach; double halfAngle; ModelValue at(double, double)
// for any point, and inside(double, double) for points the rasteriser already placed within the
// reach and the half-angle (the same value without those two tests).
template <class Prepared>
void coneFootprint(const Prepared& pb, const Beam& beam, const GridSpec& grid,
                   const BeamTables& tables, Footprint& out) {
  if (!pb.active) return;
  const std::size_t start = out.cells.size();
  CellEvidence* dst = nullptr;
  forEachConeCell(
      beam.sensor, pb.reach, pb.halfAngle, grid, tables,
      [&](std::size_t bound) {
        out.cells.resize(start +
                         bound);  // leaves the new entries unwritten (UninitialisedAllocator)
        dst = out.cells.data() + start;
      },
      [&](std::uint32_t cell, double delta, double theta) {
        const ModelValue v = pb.inside(delta, theta);
        if (v.region != BeamRegion::Outside)
          *dst++ = CellEvidence{cell, v.empty, v.occupied, v.probability};
      });
  out.cells.resize(dst ? static_cast<std::size_t>(dst - out.cells.data()) : start);
}

// What every cone model shares: its declaration is staticInfo(), and evaluate() and footprint() are
// its per-reading prepare(range, maxRange) followed by at() or the rasteriser. A model supplies
// staticInfo(), configure(), reach() and prepare().
template <class Derived>
class ConeModel : public SensorModel {
 public:
  const ModelInfo& info() const final { return Derived::staticInfo(); }
  ModelValue evaluate(double delta, double theta, double range, double maxRange) const final {
    return self().prepare(range, maxRange).at(delta, theta);
  }
  void footprint(const Beam& beam, const GridSpec& grid, const BeamTables& tables,
                 Footprint& out) const final {
    coneFootprint(self().prepare(beam.range, beam.maxRange), beam, grid, tables, out);
  }

 private:
  const Derived& self() const { return static_cast<const Derived&>(*this); }
};

// p = 0.5 + (pO - pE) / 2 and back: the translation paper 001 §3.2 uses between evidence and a
// probability, shared by the models whose native output is one of the two.
inline ModelValue fromEvidence(BeamRegion region, double empty, double occupied) {
  return ModelValue{region, empty, occupied, 0.5 + 0.5 * (occupied - empty)};
}
inline ModelValue fromProbability(double p) {
  if (p > 0.5) return ModelValue{BeamRegion::Occupied, 0.0, 2.0 * p - 1.0, p};
  return ModelValue{BeamRegion::Empty, 1.0 - 2.0 * p, 0.0, p};
}

// The "no echo" switch every model declares (notes: a no-echo reading is free-space evidence only,
// or nothing — a documented choice per model).
ParameterSpec noEchoParameter(const std::string& freeMeaning);

}  // namespace sg
