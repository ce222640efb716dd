// SPDX-License-Identifier: BSD-3-Clause
// Compiled with -ffp-contract=off (core/CMakeLists.txt): the clones for wider vectors must not fuse
// a multiply and an add that one map (built for baseline x86-64, which has no FMA) does apart.
#include "sonargrid/sweep/batch_evaluation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <mutex>
#include <new>
#include <numbers>
#include <stdexcept>
#include <tuple>

#include "sonargrid/base/concurrency.h"
#include "sonargrid/data/scan_poses.h"
#include "sonargrid/engine/mapper.h"
#include "sonargrid/models/cone_raster.h"
#include "sonargrid/models/parameterized_shape.h"
#include "sonargrid/rules/cell_updates.h"
#include "sonargrid/rules/rule_classes.h"

// The clones' resolver (an ifunc) runs while the dynamic loader relocates the program, before a
// sanitizer's runtime is set up; instrumented by ThreadSanitizer, it crashes every binary at start.
// Under a sanitizer (ThreadSanitizer, AddressSanitizer: the sanitizer and fuzz jobs) the kernel is
// therefore built once, for the baseline; the results are the same bits.
#if defined(__SANITIZE_THREAD__) || defined(__SANITIZE_ADDRESS__)
#define SG_BATCH_CLONES
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer) || __has_feature(address_sanitizer)
#define SG_BATCH_CLONES
#endif
#endif
#ifndef SG_BATCH_CLONES
#define SG_BATCH_CLONES __attribute__((target_clones("default", "avx2", "avx512f")))
#endif

namespace sg {
// Not in an anonymous namespace: batchRow() is cloned per instruction set, which needs a symbol
// with external linkage, and so do the types of its argument.
namespace batch {

constexpr int K = static_cast<int>(kBatchLanes);
// One value of each set of a batch (the vector extensions of GCC and Clang; 64 bytes).
using Doubles = double __attribute__((vector_size(8 * K)));
using Longs = std::int64_t __attribute__((vector_size(8 * K)));
using FloatsK = float __attribute__((vector_size(4 * K)));

// One set as the model and the rule read it (ParameterizedModel::configure, BayesRule::configure).
struct Lane {
  double p1 = 0, p2 = 0, p3 = 0, p4 = 0, p5 = 0;  // p5 in radians
  bool noEchoFree = false;
  double prior = 0.5;
  bool real = false;  // false: a lane that pads the last batch
};

Lane laneOf(const SweepSettings& settings, const ParameterSet& set) {
  // The set on the defaults, as the Mapper constructor completes it.
  ParameterSet p = defaultParameters(settings.model, settings.rule);
  for (const auto& [name, value] : set.values()) {
    if (p.has(name)) p.set(name, value);
  }
  Lane l;
  l.p1 = p.get("p1");
  l.p2 = p.get("p2");
  l.p3 = p.get("p3");
  l.p4 = p.get("p4");
  l.p5 = degToRad(p.get("p5"));
  l.noEchoFree = p.get("no_echo") != 0.0;
  l.prior = p.has("prior") ? p.get("prior") : 0.5;
  l.real = true;
  return l;
}

// Every reading of a run placed in the world once (Mapper::beamOf), in mapping order.
std::vector<Beam> beamsOf(const Dataset& run, PoseSource pose) {
  std::vector<Beam> beams;
  beams.reserve(run.readingCount());
  for (const Scan& scan : run.scans) {
    if (!hasPose(scan, pose)) continue;  // left out, as the mapper leaves it out (scan_poses.h)
    const Pose2D& robot = pose == PoseSource::Truth ? *scan.truth : scan.odometry;
    for (const Reading& r : scan.readings) {
      if (r.sonar >= run.ring.size()) {
        throw MapperError("reading names sonar " + std::to_string(r.sonar) + " but the ring has " +
                          std::to_string(run.ring.size()));
      }
      Beam b;
      b.sensor = robot.compose(run.ring.sonars[r.sonar].pose);
      b.range = r.range < run.ring.maxRange ? r.range : Reading::kNoEcho;
      b.maxRange = run.ring.maxRange;
      beams.push_back(b);
    }
  }
  return beams;
}

// K doubles per cell, each cell's on a cache line of its own. Read and written through
// load()/store(): the alignment a vector type has depends on the instruction set a clone is built
// for, so the storage does not rely on it.
class LanePlane {
 public:
  void assign(std::size_t cells, const double (&value)[K]) {
    if (cells > capacity_) {
      data_.reset(
          static_cast<double*>(::operator new[](cells * sizeof(double) * K, std::align_val_t{64})));
      capacity_ = cells;
    }
    cells_ = cells;
    for (std::size_t i = 0; i < cells; ++i) std::memcpy(data_.get() + i * K, value, sizeof value);
  }
  std::size_t cells() const { return cells_; }
  double* at(std::size_t cell) { return data_.get() + cell * K; }
  const double* at(std::size_t cell) const { return data_.get() + cell * K; }

 private:
  struct Delete {
    void operator()(double* p) const { ::operator delete[](p, std::align_val_t{64}); }
  };
  std::unique_ptr<double[], Delete> data_;
  std::size_t capacity_ = 0, cells_ = 0;
};

inline Doubles load(const double* p) {
  Doubles v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline void store(double* p, const Doubles& v) {
  std::memcpy(p, &v, sizeof v);
}

// A batch's state: per cell, one value of each lane of every quantity ([cell][lane]).
// A uniform batch (every lane the same cone) keeps one count per cell, the others one per lane.
struct LaneState {
  LanePlane count, mean, m2, posterior;
  std::vector<std::uint32_t> shared;  // a uniform batch's count per cell
  bool uniform = false;
  std::vector<float> values;  // one cone row's model values, [cell of the row][lane]
  void reset(std::size_t cells, bool isUniform, bool vsdns, bool map, const double (&prior)[K]) {
    static constexpr double kZero[K] = {};
    uniform = isUniform;
    count.assign(uniform ? 0 : cells, kZero);
    shared.assign(uniform ? cells : 0, 0);
    mean.assign(vsdns ? cells : 0, kZero);
    m2.assign(vsdns ? cells : 0, kZero);
    posterior.assign(map ? cells : 0, prior);
  }
};

using Shape = ParameterizedShape<float>;

// One cone row of one reading, for every lane of a batch.
struct RowJob {
  const ConeRow* row;
  const ConeBeam<Shape>* cones;  // K, one per lane
  const float* reachF;           // K: each lane's reach as forEachConeRow compares it
  bool vsdns, map;
  LaneState* state;
  // A uniform batch's lanes differ only in these of their shapes (the rest is cones[0]'s).
  FloatsK p1, p4, emptySlope, tentSlope;
};

// A row of a uniform batch: the row is every lane's own, and each cell's model value for the K
// sets is one vector of ParameterizedShape::value()'s float operations, in its order.
[[gnu::always_inline]] inline void uniformRow(const RowJob& job) {
  const ConeRow& row = *job.row;
  const BeamTables::Entry* const e = row.entries;
  LaneState& st = *job.state;
  const Shape& shape = job.cones[0].shape;
  const float hHi = static_cast<float>(row.heading);
  const float hLo = static_cast<float>(row.heading - static_cast<double>(hHi));
  std::uint32_t* const count = st.shared.data() + row.cell;
  double* const mean = job.vsdns ? st.mean.at(row.cell) : nullptr;
  double* const m2 = job.vsdns ? st.m2.at(row.cell) : nullptr;
  double* const post = job.map ? st.posterior.at(row.cell) : nullptr;
  for (int j = 0; j < row.count; ++j) {
    const float r = e[j].distance;
    const float a = std::abs((e[j].bearing - hHi) - hLo);
    const FloatsK axis = r < shape.emptyBelow ? job.p1 + job.emptySlope * r
                                              : job.p4 - job.tentSlope * std::abs(r - shape.s);
    const float w = (shape.halfAngle - a) * shape.invHalfAngle;
    const FloatsK pf = w * (axis - 0.5f) + 0.5f;
    const Doubles p = __builtin_convertvector(pf, Doubles);
    const std::size_t at = static_cast<std::size_t>(j) * kBatchLanes;
    const double n = static_cast<double>(++count[j]);
    if (mean) {  // VsdnsAccumulator::add
      const Doubles m = load(mean + at);
      const Doubles delta = p - m;
      const Doubles mNew = m + delta / n;
      store(mean + at, mNew);
      store(m2 + at, load(m2 + at) + delta * (p - mNew));
    }
    if (post) store(post + at, cellrule::bayesLanes(load(post + at), p));  // BayesRule, likelihood
  }
}

// In each row, each lane's own cells (the row trimmed by its own cone's test, which is what that
// lane's map would trim the same row of cell centres to), its model values in the float lanes of
// coneRow(), then per cell the Welford and Bayes steps of VsdnsAccumulator::add() and
// BayesRule::apply() across the lanes. Cloned for wider vectors (chosen when the program starts);
// every clone does the same operations per lane.
SG_BATCH_CLONES void batchRow(const RowJob& job) {
  if (job.state->uniform) {
    uniformRow(job);
    return;
  }
  const ConeRow& row = *job.row;
  const int n = row.count;
  const BeamTables::Entry* const e = row.entries;
  LaneState& st = *job.state;
  const std::size_t need = static_cast<std::size_t>(n + lanes::kWidth) * kBatchLanes;
  if (st.values.size() < need) st.values.resize(need);
  float* const values = st.values.data();
  const double h = row.axis;  // the sensor's heading as the row's bearings see it (ConeRow)
  Longs lo, hi;
  int first = n, last = -1;
  for (int k = 0; k < K; ++k) {
    lo[k] = n;
    hi[k] = -1;
    const ConeBeam<Shape>& cone = job.cones[k];
    if (!cone.active) continue;
    const double half = cone.halfAngle;
    const float rf = job.reachF[k];
    auto accepts = [&](const BeamTables::Entry& x) {
      return x.distance <= rf && std::abs(detail::offAxis(x.bearing, h)) <= half;
    };
    int a = 0, b = n - 1;
    while (a <= b && !accepts(e[a])) ++a;
    while (b > a && !accepts(e[b])) --b;
    if (a > b) continue;
    lo[k] = a;
    hi[k] = b;
    first = std::min(first, a);
    last = std::max(last, b);
    // The lane's own row heading, as forEachConeRow gives it to coneRow().
    const double rowHeading = h - detail::turn(static_cast<double>(e[a].bearing) - h);
    const float hHi = static_cast<float>(rowHeading);
    const float hLo = static_cast<float>(rowHeading - static_cast<double>(hHi));
    for (int j = a; j <= b; j += lanes::kWidth) {
      const lanes::Floats l0 = lanes::load(&e[j].distance);
      const lanes::Floats l1 = lanes::load(&e[j + 2].distance);
      const lanes::Floats delta = __builtin_shufflevector(l0, l1, 0, 2, 4, 6);
      const lanes::Floats bearing = __builtin_shufflevector(l0, l1, 1, 3, 5, 7);
      // Every cell of the parameterized cone is in Region I or II: none is dropped.
      const ConeValue<lanes::Floats> v = cone.shape.value(delta, lanes::abs((bearing - hHi) - hLo));
      float* const out =
          values + static_cast<std::size_t>(j) * kBatchLanes + static_cast<std::size_t>(k);
      out[0] = v.p[0];
      out[K] = v.p[1];
      out[2 * K] = v.p[2];
      out[3 * K] = v.p[3];
    }
  }
  if (first > last) return;
  double* const count = st.count.at(row.cell);
  double* const mean = job.vsdns ? st.mean.at(row.cell) : nullptr;
  double* const m2 = job.vsdns ? st.m2.at(row.cell) : nullptr;
  double* const post = job.map ? st.posterior.at(row.cell) : nullptr;
  for (int j = first; j <= last; ++j) {
    const std::size_t at = static_cast<std::size_t>(j) * kBatchLanes;
    FloatsK pf;
    std::memcpy(&pf, values + at, sizeof pf);
    const Doubles p = __builtin_convertvector(pf, Doubles);
    const Longs inside = (lo <= j) & (hi >= j);
    const Doubles c = load(count + at);
    const Doubles n1 = inside ? c + 1.0 : c;
    store(count + at, n1);
    if (mean) {  // VsdnsAccumulator::add
      const Doubles m = load(mean + at);
      const Doubles delta = p - m;
      const Doubles mNew = m + delta / n1;
      const Doubles s = load(m2 + at);
      const Doubles sNew = s + delta * (p - mNew);
      store(mean + at, inside ? mNew : m);
      store(m2 + at, inside ? sNew : s);
    }
    if (post) {  // BayesRule, likelihood input
      const Doubles m = load(post + at);
      const Doubles updated = cellrule::bayesLanes(m, p);
      store(post + at, inside ? updated : m);
    }
  }
}

}  // namespace batch

namespace {

using batch::batchRow;
using batch::beamsOf;
using batch::Doubles;
using batch::K;
using batch::Lane;
using batch::laneOf;
using batch::LaneState;
using batch::RowJob;
using batch::Shape;

// Rows of the grid a batch works through at a time: their cells' state for the batch (some
// 130 bytes per cell for VSDNS) stays in a core's own cache while every reading that reaches them
// is applied. Each cell still sees the readings in log order, so the order of the rows changes
// nothing of any result (the mapper's threads split a map into bands of rows the same way).
constexpr int kBandRows = 16;

// Each lane's cone for one reading, and the widest of them.
struct ReadingCones {
  ConeBeam<Shape> cones[K];
  float reachF[K] = {};
  double reach = 0.0, halfAngle = 0.0;
  bool any = false;
  void prepare(const Beam& beam, const Lane* lanes) {
    reach = halfAngle = 0.0;
    any = false;
    for (int k = 0; k < K; ++k) {
      const Lane& l = lanes[k];
      cones[k] = l.real ? prepareParameterized<float>(beam.range, beam.maxRange, l.p1, l.p2, l.p3,
                                                      l.p4, l.p5, l.noEchoFree)
                        : ConeBeam<Shape>{};
      if (!cones[k].active) continue;
      any = true;
      reach = std::max(reach, cones[k].reach);
      halfAngle = std::max(halfAngle, cones[k].halfAngle);
      reachF[k] = static_cast<float>(cones[k].reach);
    }
  }
};

// The grid rows a cone of `reach` and `halfAngle` can write, with a margin (forEachConeRow's
// extent in y: the apex, the arc's ends and, where the arc passes straight up or down, its top or
// bottom).
std::pair<int, int> rowsOf(const Pose2D& sensor, double reach, double halfAngle,
                           const GridSpec& grid) {
  const double h = wrapAngle(sensor.heading);
  const double R = reach / grid.cellSize;
  auto covers = [h, halfAngle](double direction) {
    const double raw = direction - h;
    return std::abs(raw + detail::turn(raw)) <= halfAngle;
  };
  constexpr double kHalfPi = std::numbers::pi / 2.0;
  const double d1y = std::sin(h - halfAngle), d2y = std::sin(h + halfAngle);
  const double top = covers(kHalfPi) ? R : std::max({0.0, R * d1y, R * d2y});
  const double bottom = covers(-kHalfPi) ? -R : std::min({0.0, R * d1y, R * d2y});
  const double v = (sensor.y() - grid.origin.y()) / grid.cellSize;
  return {static_cast<int>(std::floor(v + bottom)) - 3, static_cast<int>(std::ceil(v + top)) + 3};
}

// One run of one batch: band by band of grid rows, every reading that reaches the band, in log
// order, its cone rows in the band at the batch's widest cone, each row given to batchRow().
// Returns false when cancelled or stopped.
bool mapBatch(const std::vector<Beam>& beams, const GridSpec& grid, const BeamTables& tables,
              const Lane* lanes, bool vsdns, bool map, LaneState& st,
              const std::atomic<bool>* cancel, const std::atomic<bool>* stop) {
  // The readings of each band, in log order.
  const int bands = (grid.height + kBandRows - 1) / kBandRows;
  std::vector<std::vector<std::uint32_t>> inBand(static_cast<std::size_t>(bands));
  ReadingCones rc;
  for (std::size_t i = 0; i < beams.size(); ++i) {
    rc.prepare(beams[i], lanes);
    if (!rc.any) continue;
    const auto [lo, hi] = rowsOf(beams[i].sensor, rc.reach, rc.halfAngle, grid);
    const int b0 = std::max(0, lo) / kBandRows;
    const int b1 = std::min(grid.height - 1, hi) / kBandRows;
    for (int b = b0; b <= b1; ++b)
      inBand[static_cast<std::size_t>(b)].push_back(static_cast<std::uint32_t>(i));
  }
  for (int b = 0; b < bands; ++b) {
    if ((cancel && cancel->load(std::memory_order_relaxed)) ||
        (stop && stop->load(std::memory_order_relaxed)))
      return false;
    RowWindow window;
    window.begin = b * kBandRows;
    window.end = window.begin + kBandRows;
    for (const std::uint32_t i : inBand[static_cast<std::size_t>(b)]) {
      const Beam& beam = beams[i];
      rc.prepare(beam, lanes);
      RowJob job{nullptr, rc.cones, rc.reachF, vsdns, map, &st, {}, {}, {}, {}};
      if (st.uniform) {
        for (int k = 0; k < K; ++k) {
          job.p1[k] = rc.cones[k].shape.p1;
          job.p4[k] = rc.cones[k].shape.p4;
          job.emptySlope[k] = rc.cones[k].shape.emptySlope;
          job.tentSlope[k] = rc.cones[k].shape.tentSlope;
        }
      }
      forEachConeRow(
          beam.sensor, rc.reach, rc.halfAngle, grid, tables, [](std::size_t) {},
          [&](const ConeRow& row) {
            job.row = &row;
            batchRow(job);
          },
          window);
    }
  }
  return true;
}

// Lane k's VSDNS (VsdnsAccumulator::result: the same cells, sums and order).
VsdnsAccumulator::Result vsdnsOf(const LaneState& st, int k) {
  VsdnsAccumulator::Result r;
  double sum = 0.0;
  for (std::size_t i = 0; i < st.mean.cells(); ++i) {
    const double n = st.uniform ? st.shared[i] : st.count.at(i)[k];
    const double m2 = st.m2.at(i)[k];
    if (n < 2.0 || !(m2 > 0.0)) continue;
    const double s = std::sqrt(m2 / (n - 1.0));
    if (s == 0.0) continue;
    sum += s;
    ++r.cellsWithSpread;
  }
  if (r.cellsWithSpread > 0) r.vsdns = sum / static_cast<double>(r.cellsWithSpread);
  return r;
}

// Lane k's map, as Mapper::snapshot() gives it: the rule's layers of its posterior, observed where
// any of its readings wrote. Its layers are held as values: the set's measures read every cell
// several times, and the map lives only for them.
OccupancyMap mapOf(const LaneState& st, int k, const SweepSettings& settings,
                   const std::shared_ptr<const UpdateRule>& rule) {
  Grid grid(settings.grid, rule->layout());
  BayesCell* const cells = grid.cells<BayesCell>();
  Footprint seen;
  for (std::size_t i = 0; i < st.posterior.cells(); ++i) {
    cells[i].p = st.posterior.at(i)[k];
    if (st.uniform ? st.shared[i] > 0 : st.count.at(i)[k] > 0.0)
      seen.cells.push_back(CellEvidence(static_cast<std::uint32_t>(i), 0, 0, 0));
  }
  grid.markWritten(seen);
  OccupancyMap m = occupancyMapOf(grid, rule, settings.model, settings.rule);
  m.hold();
  return m;
}

}  // namespace

bool batchEvaluable(const SetEvaluationInput& in) {
  if (in.settings.model != "parameterized") return false;
  if (!mapsNeeded(in.measures)) return true;
  return in.settings.rule == "bayes-recursive";
}

bool evaluateSetsBatched(const SetEvaluationInput& in, const std::vector<ParameterSet>& sets,
                         const std::vector<std::size_t>& indices, const SetFinished& finished,
                         const std::atomic<bool>* cancel) {
  if (!batchEvaluable(in)) throw std::invalid_argument("these sets cannot be mapped in batches");
  for (std::size_t i : indices) {
    if (i >= sets.size()) throw std::invalid_argument("a sweep index beyond its sets");
  }
  checkSetEvaluationInput(in);
  if (indices.empty()) return true;
  const SweepSettings& settings = in.settings;
  const bool vsdns = in.measures.vsdns;
  const bool map = mapsNeeded(in.measures);

  // What one Mapper would refuse (a rule the model cannot take, an empty grid, too long a reach),
  // refused the same way before anything is mapped.
  std::vector<Lane> lanes(indices.size());
  double widest = 0.0;
  for (std::size_t k = 0; k < indices.size(); ++k) {
    lanes[k] = laneOf(settings, sets[indices[k]]);
    if (k == 0 || lanes[k].p3 > widest) {
      MapperSettings ms;
      ms.model = settings.model;
      ms.rule = settings.rule;
      ms.parameters = sets[indices[k]];
      ms.pose = settings.pose;
      for (const Dataset* d : {in.run, in.secondRun}) {
        if (d) Mapper check(d->ring, settings.grid, ms);
      }
      widest = lanes[k].p3;
    }
  }
  double maxRange = in.run->ring.maxRange;
  if (in.measures.twoRun) maxRange = std::max(maxRange, in.secondRun->ring.maxRange);
  const std::shared_ptr<const BeamTables> tables =
      BeamTables::shared(settings.grid.cellSize, maxRange + widest);

  // Sets of a similar cone side by side: by the no-echo switch, P5, P3, then their place in the
  // sweep. Sets of the very same cone fill uniform batches (a count per cell, one model value per
  // cell for all lanes); a group's last few, fewer than half a batch, go to mixed batches with the
  // like of other groups (each lane its own cells of the batch's widest cone), which cost more per
  // set than a uniform batch but less than one padded with many copies.
  std::vector<std::size_t> order(indices.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  auto cone = [&](std::size_t k) {
    return std::make_tuple(lanes[k].noEchoFree, lanes[k].p5, lanes[k].p3);
  };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::tuple_cat(cone(a), std::make_tuple(a)) <
           std::tuple_cat(cone(b), std::make_tuple(b));
  });
  std::vector<std::vector<std::size_t>> batchList, rest;
  for (std::size_t g = 0; g < order.size();) {
    std::size_t end = g;
    while (end < order.size() && cone(order[end]) == cone(order[g])) ++end;
    for (; g < end; g += std::min(kBatchLanes, end - g)) {
      const std::size_t n = std::min(kBatchLanes, end - g);
      std::vector<std::size_t> members(order.begin() + static_cast<std::ptrdiff_t>(g),
                                       order.begin() + static_cast<std::ptrdiff_t>(g + n));
      (2 * n >= kBatchLanes ? batchList : rest).push_back(std::move(members));
    }
  }
  std::vector<std::size_t> mixed;
  for (const auto& r : rest) mixed.insert(mixed.end(), r.begin(), r.end());
  for (std::size_t g = 0; g < mixed.size(); g += kBatchLanes) {
    batchList.emplace_back(
        mixed.begin() + static_cast<std::ptrdiff_t>(g),
        mixed.begin() + static_cast<std::ptrdiff_t>(std::min(mixed.size(), g + kBatchLanes)));
  }
  const std::size_t batches = batchList.size();

  const std::vector<Beam> beams1 = beamsOf(*in.run, settings.pose);
  const std::vector<Beam> beams2 =
      in.measures.twoRun ? beamsOf(*in.secondRun, settings.pose) : std::vector<Beam>{};
  const std::size_t cells = settings.grid.cellCount();

  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  std::atomic<std::size_t> done{0};
  std::mutex mutex;  // serialises `finished`
  auto work = [&](unsigned) {
    LaneState st;
    std::shared_ptr<UpdateRule> rules[K];
    while (!stop.load(std::memory_order_relaxed)) {
      const std::size_t b = next.fetch_add(1, std::memory_order_relaxed);
      if (b >= batches) return;
      Lane batch[K];
      std::size_t positions[K];
      int used = 0;
      for (std::size_t j : batchList[b]) {
        positions[used] = j;
        batch[used++] = lanes[j];
      }
      // Uniform: every lane the same cone (the no-echo switch, P3, P5); padding lanes then copy
      // the first lane, whose results they are not.
      bool uniform = true;
      for (int k = 1; k < used; ++k) {
        uniform = uniform && batch[k].noEchoFree == batch[0].noEchoFree &&
                  batch[k].p3 == batch[0].p3 && batch[k].p5 == batch[0].p5;
      }
      if (uniform) {
        for (int k = used; k < K; ++k) batch[k] = batch[0];
      }
      double prior[K];
      for (int k = 0; k < K; ++k) prior[k] = batch[k].prior;
      st.reset(cells, uniform, vsdns, map, prior);
      if (!mapBatch(beams1, settings.grid, *tables, batch, vsdns, map, st, cancel, &stop)) return;
      SetEvaluation results[K];
      std::optional<OccupancyMap> firsts[K];
      for (int k = 0; k < used; ++k) {
        std::optional<VsdnsAccumulator::Result> spread;
        if (vsdns) spread = vsdnsOf(st, k);
        if (!map) {
          results[k] = measureSet(in, spread, nullptr, nullptr);
          continue;
        }
        rules[k] = makeUpdateRule(settings.rule);
        ParameterSet p = defaultParameters(settings.model, settings.rule);
        for (const auto& [name, value] : sets[indices[positions[k]]].values()) {
          if (p.has(name)) p.set(name, value);
        }
        rules[k]->configure(p);
        firsts[k] = mapOf(st, k, settings, rules[k]);
        if (!in.measures.twoRun)
          results[k] = measureSet(in, spread, &*firsts[k], nullptr);
        else
          results[k].vsdns = spread;
      }
      if (in.measures.twoRun) {
        st.reset(cells, uniform, false, true, prior);
        if (!mapBatch(beams2, settings.grid, *tables, batch, false, true, st, cancel, &stop))
          return;
        for (int k = 0; k < used; ++k) {
          const OccupancyMap second = mapOf(st, k, settings, rules[k]);
          results[k] = measureSet(in, results[k].vsdns, &*firsts[k], &second);
        }
      }
      // A batch's sets finish together; a cancel between their calls leaves the rest unfinished.
      const std::lock_guard<std::mutex> lock(mutex);
      for (int k = 0; k < used; ++k) {
        if (cancel && cancel->load(std::memory_order_relaxed)) return;
        if (finished) finished(positions[k], results[k]);
        done.fetch_add(1);
      }
    }
  };
  const auto threads =
      static_cast<unsigned>(std::clamp<std::size_t>(batches, 1, parallelThreads()));
  runParallel(threads, work, [&] { stop.store(true); });
  return done.load() == indices.size();
}

}  // namespace sg
