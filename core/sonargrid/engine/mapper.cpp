// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/engine/mapper.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <thread>
#include <utility>

#include "sonargrid/base/concurrency.h"
#include "sonargrid/data/scan_poses.h"
#include "sonargrid/engine/row_bands.h"

namespace sg {

ParameterSet defaultParameters(const std::string& model, const std::string& rule) {
  try {
    ParameterSet p(sensorModelInfo(model).parameters);
    p.append(ParameterSet(updateRuleInfo(rule).parameters));
    return p;
  } catch (const std::invalid_argument& e) {
    throw MapperError(e.what());
  }
}

Mapper::Mapper(const SonarRing& ring, const GridSpec& grid, const MapperSettings& settings)
    : ring_(ring), settings_(settings) {
  model_ = makeSensorModel(settings.model);
  if (!model_) throw MapperError("unknown sensor model '" + settings.model + "'");
  rule_ =
      makeUpdateRule(settings.rule, hasFastCells(settings.model, settings.rule) ? settings.precision
                                                                                : Precision::Exact);
  if (!rule_) throw MapperError("unknown update rule '" + settings.rule + "'");
  const Compatibility c = compatibility(settings.model, settings.rule);
  if (!c.allowed) {
    throw MapperError("model '" + settings.model + "' cannot be used with rule '" + settings.rule +
                      "': " + c.reason);
  }
  if (grid.width <= 0 || grid.height <= 0 || !(grid.cellSize > 0.0))
    throw MapperError("the grid is empty");
  // Parameters the caller did not give stay at their defaults.
  ParameterSet params = defaultParameters(settings.model, settings.rule);
  for (const auto& [name, value] : settings.parameters.values()) {
    if (params.has(name)) params.set(name, value);
  }
  settings_.parameters = params;
  model_->configure(params);
  rule_->configure(params);
  grid_ = Grid(grid, rule_->layout());  // unknown and unobserved
  // A log may declare any finite max_range; the cone tables hold 16 × (2r + 1)² entries for a
  // reach of r cells, so a reach of 1e12 m would be an undefined cast and no memory at all.
  const double reach = model_->reach(ring_.maxRange);
  const double reachCells = std::ceil(reach / grid.cellSize);
  if (!std::isfinite(reachCells) || reachCells > kMaxReachCells) {
    std::ostringstream msg;
    msg << "the sonar reaches " << reach << " m (max_range " << ring_.maxRange << " m), "
        << reachCells << " cells of " << grid.cellSize << " m; the limit is " << kMaxReachCells
        << " cells: check the log's max_range or map with larger cells";
    throw MapperError(msg.str());
  }
  tables_ = BeamTables::shared(grid.cellSize, reach);
}

namespace {

// How often batch mapping looks at the cancel flag, in readings.
constexpr std::size_t kCancelStride = 256;
// Below this many readings a thread costs more than it saves.
constexpr std::size_t kParallelMinimum = 4096;
// Footprints computed ahead of the one being applied: enough to keep the workers busy, few enough
// that their buffers stay in cache.
constexpr std::size_t kSlots = 64;
constexpr std::int64_t kEmptySlot = -1;
constexpr std::int64_t kHaltedSlot = -2;
// Set in the pipeline's count of applied items when the run stops.
constexpr std::size_t kHalted = std::size_t{1} << (std::numeric_limits<std::size_t>::digits - 1);
// The direct path's work item (Mapper::integrateDirect): readings whose cells one thread lists
// for another to fold in, some 30 µs of work against about a µs of hand-over; and the lists
// held at once, some 25 kB each on the 100k workload, so that they stay in cache.
constexpr std::size_t kDirectChunk = 128;
constexpr std::size_t kDirectSlots = 8;
// A snapshot's layers are filled on one more thread per this many cells.
constexpr std::size_t kSnapshotCellsPerThread = 32768;
// Rows of the grid per thread at the least (integrateBands): a thread with none would read
// every beam for nothing.
constexpr int kBandRows = 8;

}  // namespace

void Mapper::reset() {
  live_.derive(nullptr);
  grid_.clear();  // replaces, rather than writes, the planes a snapshot shares
  readings_ = 0;
  if (observer_) observer_->reset(grid_.cellCount());
}

void Mapper::setObserver(FootprintObserver* observer) {
  observer_ = observer;
  if (observer_) observer_->reset(grid_.cellCount());
}

Beam Mapper::beamOf(const Pose2D& robot, const Eigen::Matrix2d& rotation,
                    const Reading& reading) const {
  if (reading.sonar >= ring_.size()) {
    throw MapperError("reading names sonar " + std::to_string(reading.sonar) +
                      " but the ring has " + std::to_string(ring_.size()));
  }
  Beam beam;
  beam.sensor = robot.compose(ring_.sonars[reading.sonar].pose, rotation);
  // A range at or beyond the transducer's maximum is no echo (notes, Conventions).
  beam.range = reading.range < ring_.maxRange ? reading.range : Reading::kNoEcho;
  beam.maxRange = ring_.maxRange;
  return beam;
}

Footprint Mapper::footprintOf(const Pose2D& robot, const Reading& reading) const {
  Footprint fp;
  model_->footprint(beamOf(robot, robot.rotation(), reading), grid_.spec(), *tables_, fp);
  return fp;
}

void Mapper::applyRuns(const EvidenceRuns& runs, EvidenceRuns* deferred) {
  rule_->applyRuns(runs, grid_, deferred);
  for (const EvidenceRuns::Run& run : runs.runs) grid_.markWritten(run.cell, run.count);
}

void Mapper::applyFootprint(const Footprint& footprint) {
  rule_->apply(footprint, grid_);
  if (observer_) observer_->observe(footprint);
  markObserved(footprint);
  ++readings_;
}

void Mapper::beginWriting() {
  live_.derive(nullptr);
  grid_.unshare();
}

void Mapper::integrate(const Scan& scan, double until) {
  if (!hasPose(scan, settings_.pose)) return;  // left out (scan_poses.h)
  const Pose2D& robot = settings_.pose == PoseSource::Truth ? *scan.truth : scan.odometry;
  bool writing = false;  // a scan with nothing up to `until` leaves shared cells shared
  const Eigen::Matrix2d rotation = robot.rotation();
  for (const Reading& r : scan.readings) {
    if (r.time > until) continue;
    if (!writing) {
      beginWriting();
      writing = true;
    }
    scratch_.clear();
    model_->footprint(beamOf(robot, rotation, r), grid_.spec(), *tables_, scratch_);
    applyFootprint(scratch_);
  }
}

bool Mapper::mapDataset(const Dataset& dataset, double until, const std::atomic<bool>* cancel) {
  if (settings_.pose == PoseSource::Truth && !anyScanHasPose(dataset, PoseSource::Truth)) {
    throw MapperError(std::string(kNoTruePose) + "; map with odometry (--pose odom)");
  }
  reset();
  // Where each scan's beams start: the readings up to `until` of the scans before it.
  const std::vector<Scan>& scans = dataset.scans;
  std::vector<std::size_t> first(scans.size() + 1, 0);
  for (std::size_t k = 0; k < scans.size(); ++k) {
    std::size_t kept = 0;
    if (hasPose(scans[k], settings_.pose))  // else left out (scan_poses.h)
      for (const Reading& r : scans[k].readings) kept += r.time <= until ? 1 : 0;
    first[k + 1] = first[k] + kept;
  }
  // Each beam is its reading's own (a sine and a cosine of the robot's heading): a large log's
  // are placed on the policy's threads, each taking a run of scans.
  std::vector<Beam> beams(first.back());
  const unsigned parts =
      beams.size() < kParallelMinimum ? 1u : std::min<unsigned>(parallelThreads(), 8u);
  runParallel(parts, [&](unsigned part) {
    const std::size_t begin = scans.size() * part / parts;
    const std::size_t end = scans.size() * (part + 1) / parts;
    for (std::size_t k = begin; k < end; ++k) {
      if (!hasPose(scans[k], settings_.pose)) continue;
      const Pose2D& robot = dataset.pose(scans[k], settings_.pose);
      const Eigen::Matrix2d rotation = robot.rotation();
      Beam* out = beams.data() + first[k];
      for (const Reading& r : scans[k].readings) {
        if (r.time <= until) *out++ = beamOf(robot, rotation, r);
      }
    }
  });
  return integrateBeams(beams, cancel);
}

namespace {

// Waits until `value` differs from `old`. A footprint takes some 10 µs (a chunk of HIMM's axis
// cells some 30 µs), so the wait is usually over within a short spin; sleeping at once would cost
// a futex call and a wake-up per item on each side. After a short spin the thread yields before it
// sleeps: on a machine with more threads than free CPUs (a shared machine, a batch node, more
// --threads than CPUs) the thread we wait for is often waiting for a CPU, and a yield gives it ours
// at once where a long spin burnt it and a sleep added two context switches. Measured on the office
// log at 2 threads on a 2-CPU machine under a load of 7: himm × himm 247 → 110 ms, hpf × addition
// 1551 → 1339 ms (medians of 7; 512 pauses and no yield before).
template <class T>
void waitForChange(const std::atomic<T>& value, T old) {
  for (int k = 0; k < 64; ++k) {
    if (value.load(std::memory_order_acquire) != old) return;
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
  }
  for (int k = 0; k < 256; ++k) {
    if (value.load(std::memory_order_acquire) != old) return;
    std::this_thread::yield();
  }
  value.wait(old, std::memory_order_acquire);
}

// An ordered pipeline over items 0 .. n − 1 on `threads` threads: any thread may compute item i
// (compute(i, payload)) once its slot (i mod `slots`) is free; only the calling thread's share,
// thread 0, applies them (apply(i, payload)), strictly in order 0, 1, 2, ... It looks at `cancel`
// before every `cancelStride`-th item it applies, and returns false when it stopped there.
template <class Payload, class Compute, class Apply>
bool orderedPipeline(std::size_t n, unsigned threads, std::size_t slots, std::size_t cancelStride,
                     const std::atomic<bool>* cancel, Compute&& computeItem, Apply&& applyItem) {
  struct Slot {
    Payload payload;
    std::atomic<std::int64_t> holds{kEmptySlot};  // index of the item in it, once complete
  };
  std::vector<Slot> ring(slots);
  std::atomic<std::size_t> next{0};     // next item nobody has claimed
  std::atomic<std::size_t> applied{0};  // items applied so far; kHalted once stopped
  std::atomic<bool> stop{false};
  auto compute = [&](std::size_t i) {
    Slot& slot = ring[i % slots];
    computeItem(i, slot.payload);
    slot.holds.store(static_cast<std::int64_t>(i), std::memory_order_release);
    slot.holds.notify_one();
  };
  // Stops the run and wakes every thread waiting in it: workers waiting for a slot to be applied
  // see kHalted in `applied` (it is not advanced, so no worker may overwrite an item the applying
  // thread is reading), and the applying thread waiting for an item whose worker failed sees its
  // slot change.
  auto halt = [&] {
    stop.store(true);
    applied.fetch_or(kHalted);
    applied.notify_all();
    for (Slot& slot : ring) {
      slot.holds.store(kHaltedSlot);
      slot.holds.notify_all();
    }
  };
  auto help = [&] {
    while (!stop.load(std::memory_order_relaxed)) {
      const std::size_t i = next.fetch_add(1, std::memory_order_relaxed);
      if (i >= n) return;
      // Slot i mod slots still holds item i − slots until that one is applied.
      for (std::size_t a = applied.load(std::memory_order_acquire);;
           a = applied.load(std::memory_order_acquire)) {
        if (a & kHalted) return;
        if (i < a + slots) break;
        waitForChange(applied, a);
      }
      compute(i);
    }
  };
  bool completed = true;
  auto apply = [&] {
    for (std::size_t i = 0; i < n; ++i) {
      if (cancel && i % cancelStride == 0 && cancel->load(std::memory_order_relaxed)) {
        completed = false;
        break;
      }
      Slot& slot = ring[i % slots];
      for (std::int64_t held = slot.holds.load(std::memory_order_acquire);
           held != static_cast<std::int64_t>(i);
           held = slot.holds.load(std::memory_order_acquire)) {
        if (stop.load(std::memory_order_relaxed)) break;
        // Rather than wait, compute the next unclaimed item if its slot is free.
        std::size_t j = next.load(std::memory_order_relaxed);
        if (j < n && j < i + slots &&
            next.compare_exchange_weak(j, j + 1, std::memory_order_relaxed)) {
          compute(j);
          continue;
        }
        waitForChange(slot.holds, held);
      }
      if (stop.load(std::memory_order_relaxed)) break;
      applyItem(i, slot.payload);
      applied.fetch_add(1, std::memory_order_release);  // keeps kHalted
      applied.notify_all();
    }
    halt();  // workers still waiting for a slot (a cancelled run) return
  };
  // This thread applies, in order; the others compute items ahead of it.
  runParallel(
      threads, [&](unsigned k) { k == 0 ? apply() : help(); }, halt);
  return completed;
}

}  // namespace

bool Mapper::integrateBeams(const std::vector<Beam>& beams, const std::atomic<bool>* cancel) {
  beginWriting();
  const std::size_t n = beams.size();
  // Straight into the grid without footprints when the model and rule can (HIMM's axis: its
  // cells listed on any thread, folded in in order; SensorModel::listDirect).
  DirectCells probe;
  const bool direct = !observer_ && model_->listDirect(beams.data(), 0, grid_.spec(), probe) &&
                      model_->applyDirect(probe, *rule_, grid_);
  // A model that neither rasterises by rows nor lists its cells maps on one thread: split by
  // stripes, every thread would trace every whole line and then sort its cells into rows, which
  // cost more than the second thread saved (himm × himm on the 100k workload, same process,
  // loaded machine: 142–196 ms at 2 threads against 29–49 ms at 1); through the pipeline, the
  // hand-over of each footprint costs more than tracing it.
  // So does normalising addition with a model that gives no runs, which its threads would have to
  // keep whole for the totals (integrateBands; no model of the registry is one).
  EvidenceRuns probeRuns;
  const bool keepable =
      !rule_->needsTotals() ||
      (n > 0 && model_->evidenceRuns(beams[0], grid_.spec(), *tables_, RowWindow{0, 0}, probeRuns));
  const unsigned threads =
      n < kParallelMinimum || !(model_->rasterisesRows() || direct) || !keepable
          ? 1u
          : parallelThreads();
  if (direct) return integrateDirect(beams, cancel, threads);
  if (threads == 1) {
    const bool totals = rule_->needsTotals();
    EvidenceRuns runs, deferred;
    for (std::size_t i = 0; i < n; ++i) {
      if (cancel && i % kCancelStride == 0 && cancel->load(std::memory_order_relaxed)) return false;
      scratch_.clear();
      // Without an observer, the model's runs go straight to the rule; the runs that wait for the
      // totals (addition's occupied arc) are applied once the reading's runs are all in.
      runs.clear();
      if (!observer_ && model_->evidenceRuns(beams[i], grid_.spec(), *tables_, RowWindow{}, runs)) {
        deferred.clear();
        applyRuns(runs, &deferred);
        if (totals)
          rule_->applyDeferred(deferred, FootprintTotals{occupiedFixedPoint(deferred)}, grid_);
        ++readings_;
        continue;
      }
      model_->footprint(beams[i], grid_.spec(), *tables_, scratch_);
      applyFootprint(scratch_);
    }
    return true;
  }
  // Bands of rows per thread, unless an observer must see whole footprints in order: then the
  // pipeline.
  if (!observer_) {
    const auto bands = static_cast<unsigned>(grid_.spec().height / kBandRows);
    return integrateBands(beams, cancel, std::max(1u, std::min(threads, bands)));
  }

  // An observer sees whole footprints in order: computed ahead on the other threads, applied on
  // this one.
  return orderedPipeline<Footprint>(
      n, threads, kSlots, kCancelStride, cancel,
      [&](std::size_t i, Footprint& fp) {
        fp.clear();
        model_->footprint(beams[i], grid_.spec(), *tables_, fp);
      },
      [&](std::size_t, const Footprint& fp) { applyFootprint(fp); });
}

bool Mapper::integrateDirect(const std::vector<Beam>& beams, const std::atomic<bool>* cancel,
                             unsigned threads) {
  // Chunks of kDirectChunk readings: listed (SensorModel::listDirect) on any thread, folded in
  // (applyDirect) strictly in order on this one, so every cell sees the readings in log order and
  // the grid has the bits of the footprint path at any thread count.
  const std::size_t n = beams.size();
  const std::size_t chunks = (n + kDirectChunk - 1) / kDirectChunk;
  // The lister marks its cells written too (the marks are one value, so in any order), which
  // takes that share of the work off the one thread that folds in (himm × dempster-shafer, whose
  // folding in is the slower side). A cancelled or failed run may so leave marks on cells of
  // chunks listed but not folded in: its grid is unfinished anyway (mapDataset()). On one thread
  // each cell's mark is simply stored: reading it first, as threads that share the marks must
  // (Grid::markWrittenShared), cost a mispredicted branch wherever the robot reached new cells
  // (himm × dempster-shafer's one-thread re-map 1.11–1.17 × the time; docs/performance.md).
  auto list = [&](std::size_t c, DirectCells& cells, bool shared = true) {
    cells.clear();
    const std::size_t begin = c * kDirectChunk;
    model_->listDirect(beams.data() + begin, std::min(kDirectChunk, n - begin), grid_.spec(),
                       cells);
    if (shared)
      grid_.markWrittenShared(cells.cells);
    else
      grid_.markWritten(std::span<const std::uint32_t>(cells.cells));
  };
  auto apply = [&](std::size_t c, const DirectCells& cells) {
    model_->applyDirect(cells, *rule_, grid_);
    readings_ += std::min(kDirectChunk, n - c * kDirectChunk);
  };
  if (threads == 1) {
    // Traced and folded in at once where the model can (HIMM's axis with its one-byte rule), else
    // listed and folded, a chunk at a time between looks at the cancel flag.
    const bool fused = model_->integrateDirect(beams.data(), 0, *rule_, grid_);
    DirectCells cells;
    for (std::size_t c = 0; c < chunks; ++c) {
      if (cancel && cancel->load(std::memory_order_relaxed)) return false;
      if (fused) {
        const std::size_t begin = c * kDirectChunk;
        const std::size_t count = std::min(kDirectChunk, n - begin);
        model_->integrateDirect(beams.data() + begin, count, *rule_, grid_);
        readings_ += count;
      } else {
        list(c, cells, false);
        apply(c, cells);
      }
    }
    return true;
  }
  return orderedPipeline<DirectCells>(chunks, threads, kDirectSlots, 1, cancel, list, apply);
}

bool Mapper::integrateBands(const std::vector<Beam>& beams, const std::atomic<bool>* cancel,
                            unsigned threads) {
  // Each thread has its own band of consecutive grid rows, the bands of about equal work over the
  // whole batch (row_bands.h). It reads every beam but rasterises only its own rows, and applies
  // them to cells no other thread has: each cell still sees the readings in log order, so the grid
  // is bit-identical to the serial one, and no footprint is handed from one core to another (that
  // traffic, 16 bytes a cell, cost the ordered pipeline most of its second core). A cone inside
  // one band costs the other threads nothing, where interleaved stripes of rows made every thread
  // set up nearly every reading (hpf × bayes-recursive on 2 threads: 0.95–0.98 of the wall-clock
  // time on the 100k workload and 0.95–0.97 on the office log; docs/performance.md).
  // Rules with totals (normalising addition) take two passes a chunk of readings, so that there
  // too no thread waits for another reading by reading (below).
  const std::size_t n = beams.size();
  const bool totals = rule_->needsTotals();
  const double reach = model_->reach(ring_.maxRange);  // for any range (the grid's growth too)
  // Whether no-echo readings write (and so weigh): the model's value half-way out on the axis of
  // one. A wrong guess would only unbalance the bands, never change a cell.
  const double maxRange = ring_.maxRange;
  const bool noEchoWrites =
      model_->evaluate(maxRange / 2.0, 0.0, Reading::kNoEcho, maxRange).region !=
      BeamRegion::Outside;
  std::atomic<bool> stop{false};
  std::atomic<std::size_t> done{n};  // the fewest readings any thread has applied
  auto halt = [&](std::size_t applied) {
    for (std::size_t d = done.load(); applied < d && !done.compare_exchange_weak(d, applied);) {
    }
    stop.store(true);
  };
  auto stopping = [&](std::size_t i) {
    return stop.load(std::memory_order_relaxed) ||
           (cancel && i % kCancelStride == 0 && cancel->load(std::memory_order_relaxed));
  };
  // A thread that fails (or cannot start) halts the others; runParallel rethrows its error here.
  auto runThreads = [&](auto work) {
    runParallel(
        threads, [&](unsigned k) { work(k); }, [&] { halt(0); });
  };
  // The rows a beam can write lie within the model's reach (for any range) of its sensor's row, and
  // a few rows more for the cell the sensor is in and the spans' margins (cone_raster.h): a beam
  // whose sensor is further than that from a thread's band is passed over before the model sets it
  // up (its constants, the cone's edges), which the band's rows would then cut to nothing.
  const GridSpec& spec = grid_.spec();
  const double reachRows = reach / spec.cellSize + 4.0;
  auto farFrom = [&](const RowWindow& band, const Beam& beam) {
    const GridSpec::Counted at = spec.counted(beam.sensor.position);
    const double row = at.v + at.shiftY;
    // (a NaN row goes on, as on one thread)
    return row < band.begin - reachRows || row > band.end + reachRows;
  };

  if (!totals) {
    const std::vector<RowWindow> rows =
        balancedBands(estimatedRowWork(beams, spec, reach, noEchoWrites), threads);
    runThreads([&](unsigned k) {
      Footprint fp;
      EvidenceRuns runs;
      for (std::size_t i = 0; i < n; ++i) {
        if (stopping(i)) return halt(i);
        if (farFrom(rows[k], beams[i])) continue;
        runs.clear();
        if (model_->evidenceRuns(beams[i], spec, *tables_, rows[k], runs)) {
          applyRuns(runs, nullptr);
          continue;
        }
        fp.clear();
        model_->footprintRows(beams[i], spec, *tables_, rows[k], fp);
        rule_->apply(fp, grid_);
        markObserved(fp);
      }
    });
  } else {
    // Normalising addition needs each reading's total over its whole occupied arc, which may lie
    // in several bands. So, a chunk of kTotalsChunk readings at a time, each thread first applies
    // to its band what does not wait for the totals (the empty evidence; UpdateRule::applyRuns)
    // and keeps what does (the arc's runs) with its band's share of each total; then, once every
    // thread has done so, it applies the kept runs in log order with the whole totals. The two
    // parts touch separate state of a cell, and a chunk is finished before the next begins, so
    // each cell still sees each part's readings in log order; the bands may so be drawn afresh
    // for each chunk, about equal for its readings. No thread waits for another reading by reading:
    // stripes of rows with the threads in step, reading by reading, had hpf × addition take as long
    // on 2 threads as on 1 on one machine (docs/performance.md).
    // A thread's store, on a cache line of its own: its vectors' ends move as it fills (side by
    // side, the two threads' stores made each take 1.5× as long a cell as one thread).
    struct alignas(64) Kept {
      EvidenceRuns runs;                 // the arc's runs of the chunk's readings, in log order
      std::vector<std::uint32_t> ends;   // one past reading i's last run in `runs`
      std::vector<std::int64_t> shares;  // reading i's share of its total (fixed point)
    };
    std::vector<Kept> kept(threads);
    for (std::size_t begin = 0; begin < n && !stop.load(); begin += kTotalsChunk) {
      const std::size_t count = std::min(kTotalsChunk, n - begin);
      const std::span<const Beam> chunk(beams.data() + begin, count);
      const std::vector<RowWindow> rows =
          balancedBands(estimatedRowWork(chunk, spec, reach, noEchoWrites), threads);
      runThreads([&](unsigned k) {
        Kept& mine = kept[k];
        mine.runs.clear();
        mine.ends.resize(count);
        mine.shares.resize(count);
        EvidenceRuns runs;
        for (std::size_t j = 0; j < count; ++j) {
          if (stopping(begin + j)) return halt(begin);
          const auto from = static_cast<std::uint32_t>(mine.runs.runs.size());
          mine.shares[j] = 0;
          if (!farFrom(rows[k], chunk[j])) {
            runs.clear();
            // (integrateBeams() maps on one thread with a model that gives no runs.)
            model_->evidenceRuns(chunk[j], spec, *tables_, rows[k], runs);
            applyRuns(runs, &mine.runs);
            mine.shares[j] = occupiedFixedPoint(mine.runs, from);
          }
          mine.ends[j] = static_cast<std::uint32_t>(mine.runs.runs.size());
        }
      });
      if (stop.load()) break;
      runThreads([&](unsigned k) {
        const Kept& mine = kept[k];
        std::uint32_t from = 0;
        for (std::size_t j = 0; j < count; ++j) {
          if (stopping(begin + j)) return halt(begin + j);
          if (mine.ends[j] == from) continue;  // nothing of it kept in this band
          FootprintTotals sum;
          for (const Kept& band : kept) sum.add(band.shares[j]);
          rule_->applyDeferred(mine.runs, from, mine.ends[j], sum, grid_);
          from = mine.ends[j];
        }
      });
    }
  }
  readings_ += done;
  return done == n;
}

OccupancyMap Mapper::snapshot() const {
  return occupancyMapOf(grid_, rule_, settings_.model, settings_.rule);
}

OccupancyMap occupancyMapOf(const Grid& grid, std::shared_ptr<const UpdateRule> rule,
                            const std::string& model, const std::string& ruleName) {
  OccupancyMap m;
  m.spec = grid.spec();
  m.model = model;
  m.rule = ruleName;
  const std::size_t n = grid.cellCount();
  m.level.resize(n);
  m.observed.resize(n);
  grid.copyObserved(0, n, m.observed.data());
  // Split between threads for large grids: a 5 cm grid of a room and its ghosts is 200 000 cells
  // and this is on the path from a slider to the picture.
  const auto parts = static_cast<unsigned>(
      std::clamp<std::size_t>(n / kSnapshotCellsPerThread, 1, parallelThreads()));
  std::uint8_t* const level = m.level.data();
  runParallel(parts, [&](unsigned k) {
    rule->writeLevels(grid, level, n * k / parts, n * (k + 1) / parts);
  });
  m.derive(std::make_shared<const RuleCells>(std::move(rule), grid.sharedCells()));
  return m;
}

bool Mapper::grow(const Position& lo, const Position& hi) {
  const GridSpec before = grid_.spec();
  if (grid_.covers(lo, hi)) return false;
  if (observer_) {
    throw MapperError(
        "the grid must grow to hold the new readings, and a footprint observer "
        "counts the cells of its present limits; map the log in one batch instead");
  }
  try {
    grid_.growToCover(lo, hi);
  } catch (const GridLimitError& e) {
    throw MapperError(e.what());
  }
  return grid_.spec() != before;
}

bool Mapper::reserve(const Position& lo, const Position& hi) {
  return grow(lo, hi);
}

bool Mapper::append(std::span<const Scan> scans, double until, const std::atomic<bool>* cancel) {
  std::vector<Beam> beams;
  for (const Scan& scan : scans) {
    if (!hasPose(scan, settings_.pose)) continue;  // left out, as mapDataset() leaves it out
    const Pose2D& robot = settings_.pose == PoseSource::Truth ? *scan.truth : scan.odometry;
    if (!robot.position.allFinite() || !std::isfinite(robot.heading)) {
      throw MapperError("the scan at t = " + std::to_string(scan.time) +
                        " s has a pose that is not a finite number");
    }
    const Eigen::Matrix2d rotation = robot.rotation();
    for (const Reading& r : scan.readings)
      if (r.time <= until) beams.push_back(beamOf(robot, rotation, r));
  }
  if (beams.empty()) return true;
  // The model writes no further than its reach from the sensor (cell centres within it); two cells
  // more hold the cells those centres lie in, whatever the rounding. The grid grows once for the
  // whole batch: growth keeps every cell, so it is the same as growing before each reading.
  const double reach = model_->reach(ring_.maxRange) + 2.0 * grid_.spec().cellSize;
  Position lo = beams.front().sensor.position, hi = lo;
  for (const Beam& b : beams) {
    lo = lo.cwiseMin(b.sensor.position);
    hi = hi.cwiseMax(b.sensor.position);
  }
  grow(Position(lo.x() - reach, lo.y() - reach), Position(hi.x() + reach, hi.y() + reach));
  return integrateBeams(beams, cancel);
}

const OccupancyMap& Mapper::liveMap(RowBand* rewritten) {
  const GridSpec& spec = grid_.spec();
  const std::vector<RowBand> runs = grid_.takeDirtyRuns();
  if (live_.spec != spec || live_.level.size() != grid_.cellCount()) {
    live_ = snapshot();
    if (rewritten) *rewritten = RowBand{0, spec.height};
    return live_;
  }
  const auto width = static_cast<std::size_t>(spec.width);
  for (const RowBand& run : runs) {
    const std::size_t begin = static_cast<std::size_t>(run.begin) * width;
    const std::size_t end = static_cast<std::size_t>(run.end) * width;
    rule_->writeLevels(grid_, live_.level.data(), begin, end);
    grid_.copyObserved(begin, end, live_.observed.data());
  }
  live_.derive(std::make_shared<const RuleCells>(rule_, grid_.sharedCells()));
  if (rewritten)
    *rewritten = runs.empty() ? RowBand{} : RowBand{runs.front().begin, runs.back().end};
  return live_;
}

}  // namespace sg
