// SPDX-License-Identifier: BSD-3-Clause
// The HIMM beam (paper 000 §2.2): only the acoustic axis. The cell holding the echo gets occupied
// evidence, the cells between the sensor and it free evidence; the HIMM rule turns these into +I⁺
// and −I⁻. For the probabilistic rules the two kinds carry OctoMap's hit and miss probabilities,
// which makes HIMM-with-log-odds the ray-casting update of OctoMap.

#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include "sonargrid/engine/grid.h"
#include "sonargrid/engine/update_rule.h"
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
  bool listDirect(const Beam* beams, std::size_t count, const GridSpec& grid,
                  DirectCells& out) const override;
  bool applyDirect(const DirectCells& cells, const UpdateRule& rule, Grid& grid) const override;
  bool integrateDirect(const Beam* beams, std::size_t count, const UpdateRule& rule,
                       Grid& grid) const override;

 private:
  // What footprint() gives the axis cells before the echo, and the echo's cell.
  CellEvidence freeEvidence() const {
    const ModelValue v = fromProbability(pMiss_);
    return CellEvidence(0, v.empty, v.occupied, v.probability);
  }
  CellEvidence hitEvidence() const {
    const ModelValue v = fromProbability(pHit_);
    return CellEvidence(0, v.empty, v.occupied, v.probability);
  }

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

namespace {

// Whether cell (x, y) of traceAxis() lies in `grid`: one unsigned comparison per axis, as a
// negative index wraps past the grid's size.
inline bool inGrid(int x, int y, const GridSpec& grid) {
  return static_cast<unsigned>(x) < static_cast<unsigned>(grid.width) &&
         static_cast<unsigned>(y) < static_cast<unsigned>(grid.height);
}

// Calls emit(x, y, last) for every cell the axis segment of `beam` passes through, `length`
// metres long, in order from the sensor, each once (Amanatides & Woo 1987, in cell units), with
// last = true for the final cell only; x and y may lie outside the grid. The step is written as a
// select, and GCC 12 at -O2 compiles it to a branch on the comparison (perf annotate,
// 2026-11-27). That is the faster of the two: the same step as bit masks, with no branch, made
// the walk twice as slow (one-thread CPU time of himm × himm 12.6 → 26.8 ms, `profile_remap`), as
// each cell's comparison then waits for the previous cell's sum, where the predicted branch lets
// the walk run ahead. The arithmetic is that of Amanatides & Woo, so the cells are the same.
template <class Emit>
void traceAxis(const Beam& beam, double length, const GridSpec& grid, Emit&& emit) {
  const double c = grid.cellSize;
  // Counted from the grid's base (GridSpec::base): the same cells however the grid grew; the
  // walk runs in those counts, and each cell is shifted into the grid as it is emitted.
  const GridSpec::Counted at = grid.counted(beam.sensor.position);
  const double u0 = at.u;
  const double v0 = at.v;
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
  emit.reserve(static_cast<std::size_t>(steps) + 1);
  for (int k = 0; k < steps; ++k) {
    emit(ix + at.shiftX, iy + at.shiftY, false);
    const bool alongX = tMaxX < tMaxY;
    ix += alongX ? stepX : 0;
    iy += alongX ? 0 : stepY;
    const double nextX = tMaxX + tDeltaX, nextY = tMaxY + tDeltaY;
    tMaxX = alongX ? nextX : tMaxX;
    tMaxY = alongX ? tMaxY : nextY;
  }
  emit(ix + at.shiftX, iy + at.shiftY, true);
}

}  // namespace

void HimmModel::footprint(const Beam& beam, const GridSpec& grid, const BeamTables& /*tables*/,
                          Footprint& out) const {
  const bool echo = beam.echo();
  if (!echo && !noEchoFree_) return;
  const CellEvidence free = freeEvidence(), last = echo ? hitEvidence() : free;
  // The cells are written through a pointer, sized once: steps + 1 cells at most (those outside
  // the grid are skipped, without a branch).
  struct Writer {
    Footprint& out;
    const GridSpec& grid;
    const CellEvidence &free, &last;
    std::size_t start = out.cells.size();
    CellEvidence* dst = nullptr;
    void reserve(std::size_t cells) {
      out.cells.resize(start + cells);
      dst = out.cells.data() + start;
    }
    void operator()(int x, int y, bool isLast) {
      *dst = isLast ? last : free;
      dst->cell = static_cast<std::uint32_t>(y * grid.width + x);
      dst += inGrid(x, y, grid) ? 1 : 0;
    }
  } writer{out, grid, free, last};
  traceAxis(beam, echo ? beam.range : beam.maxRange, grid, writer);
  out.cells.resize(static_cast<std::size_t>(writer.dst - out.cells.data()));
}

bool HimmModel::listDirect(const Beam* beams, std::size_t count, const GridSpec& grid,
                           DirectCells& out) const {
  // Each reading's axis cells in the grid, as footprint() lists them (the echo's last).
  struct Collector {
    const GridSpec& grid;
    std::vector<std::uint32_t>& cells;
    std::size_t start = cells.size();
    std::uint32_t* dst = nullptr;
    bool lastInside = false;
    void reserve(std::size_t n) {
      cells.resize(start + n);
      dst = cells.data() + start;
    }
    void operator()(int x, int y, bool isLast) {
      const bool inside = inGrid(x, y, grid);
      *dst = static_cast<std::uint32_t>(y * grid.width + x);
      dst += inside ? 1 : 0;
      lastInside = isLast && inside;
    }
  };
  for (std::size_t i = 0; i < count; ++i) {
    const Beam& beam = beams[i];
    const bool echo = beam.echo();
    if (!echo && !noEchoFree_) continue;
    Collector collect{grid, out.cells};
    traceAxis(beam, echo ? beam.range : beam.maxRange, grid, collect);
    const auto end = static_cast<std::uint32_t>(collect.dst - out.cells.data());
    out.cells.resize(end);
    out.ends.push_back(end);
    out.frees.push_back(end - static_cast<std::uint32_t>(collect.start) -
                        (echo && collect.lastInside ? 1u : 0u));
  }
  return true;
}

bool HimmModel::applyDirect(const DirectCells& list, const UpdateRule& rule, Grid& grid) const {
  // The marks are the caller's (SensorModel::applyDirect). A one-byte rule says what each kind of
  // cell does to every value a cell can hold: the axis cells then take a table look-up each. Any
  // other rule that takes one value for many cells (UpdateRule::applyUniform) gets a reading's free
  // cells in one call and its echo's cell in another. The cells of one reading are distinct, so
  // their order within it does not matter.
  const CellEvidence free = freeEvidence(), hit = hitEvidence();
  std::array<std::uint8_t, 256> freeStep{}, hitStep{};
  const bool bytes = rule.byteTransition(free, freeStep) && rule.byteTransition(hit, hitStep);
  if (!bytes && !rule.applyUniform(free, {}, grid)) return false;
  std::uint8_t* const cv = bytes ? grid.bytes(0) : nullptr;
  const std::span<const std::uint32_t> all(list.cells);
  std::size_t begin = 0;
  for (std::size_t k = 0; k < list.ends.size(); ++k) {
    const std::span<const std::uint32_t> cells = all.subspan(begin, list.ends[k] - begin);
    const std::size_t frees = list.frees[k];
    if (bytes) {
      for (std::size_t j = 0; j < cells.size(); ++j) {
        const std::uint32_t c = cells[j];
        cv[c] = (j < frees ? freeStep : hitStep)[cv[c]];
      }
    } else {
      rule.applyUniform(free, cells.first(frees), grid);
      if (frees < cells.size()) rule.applyUniform(hit, cells.subspan(frees), grid);
    }
    begin = list.ends[k];
  }
  return true;
}

bool HimmModel::integrateDirect(const Beam* beams, std::size_t count, const UpdateRule& rule,
                                Grid& grid) const {
  // A one-byte rule: each axis cell takes its table look-up as it is traced, with no list between
  // (a third faster on one thread than listing first).
  std::array<std::uint8_t, 256> freeStep{}, hitStep{};
  if (!rule.byteTransition(freeEvidence(), freeStep) ||
      !rule.byteTransition(hitEvidence(), hitStep)) {
    return false;
  }
  struct Updater {
    Grid& grid;
    std::uint8_t* cv;
    const std::uint8_t *free, *last;
    void reserve(std::size_t /*cells*/) {}
    void operator()(int x, int y, bool isLast) {
      const GridSpec& spec = grid.spec();
      if (!inGrid(x, y, spec)) return;
      const auto cell = static_cast<std::uint32_t>(y * spec.width + x);
      cv[cell] = (isLast ? last : free)[cv[cell]];
      grid.markWritten(cell);
    }
  };
  for (std::size_t i = 0; i < count; ++i) {
    const Beam& beam = beams[i];
    const bool echo = beam.echo();
    if (!echo && !noEchoFree_) continue;
    Updater updater{grid, grid.bytes(0), freeStep.data(), echo ? hitStep.data() : freeStep.data()};
    traceAxis(beam, echo ? beam.range : beam.maxRange, grid.spec(), updater);
  }
  return true;
}

std::unique_ptr<SensorModel> makeHimmModel() {
  return std::make_unique<HimmModel>();
}
const ModelInfo& himmModelInfo() {
  return HimmModel::staticInfo();
}

}  // namespace sg
