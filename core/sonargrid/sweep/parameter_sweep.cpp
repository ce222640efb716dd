// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/sweep/parameter_sweep.h"

#include <algorithm>
#include <array>
#include <mutex>

#include "sonargrid/concurrency.h"
#include "sonargrid/mapper.h"
#include "sonargrid/metrics/vsdns.h"

namespace sg {

std::vector<ParameterSet> paper002Table1Sets(const ParameterSet& base) {
  // Paper 002 Table 1: minimum, step and maximum of each parameter; P5's values are listed in the
  // table's footnote **. Written out rather than stepped so that every value is the double nearest
  // its decimal.
  static constexpr std::array<double, 15> kP5{6,  7,  8,  10, 13, 14, 15, 16,
                                              17, 18, 20, 25, 27, 35, 40};
  static constexpr std::array<double, 4> kP4{0.95, 0.96, 0.97, 0.98};
  static constexpr std::array<double, 6> kTwoP3{0.5, 1.0, 1.5, 2.0, 2.5, 3.0};
  static constexpr std::array<double, 4> kP2{0.05, 0.10, 0.15, 0.20};
  std::vector<ParameterSet> sets;
  sets.reserve(kP5.size() * kP4.size() * kTwoP3.size() * kP2.size());
  for (double p5 : kP5) {
    for (double p4 : kP4) {
      for (double twoP3 : kTwoP3) {
        for (double p2 : kP2) {
          ParameterSet s = base;
          s.set("p1", 1.0 - p4);  // footnote *: "P1 = 1 − P4 relation has been used"
          s.set("p2", p2);
          s.set("p3", twoP3 / 2.0);
          s.set("p4", p4);
          s.set("p5", p5);
          sets.push_back(std::move(s));
        }
      }
    }
  }
  return sets;
}

namespace {

// One map of one run with one set, scan by scan on the calling thread. Returns false if cancelled
// or stopped (another thread failed).
bool mapRun(Mapper& mapper, const Dataset& data, const std::atomic<bool>* cancel,
            const std::atomic<bool>& stop) {
  mapper.reset();
  for (const Scan& scan : data.scans) {
    if ((cancel && cancel->load(std::memory_order_relaxed)) || stop.load(std::memory_order_relaxed))
      return false;
    mapper.integrate(scan);
  }
  return true;
}

}  // namespace

SweepOutcome runSweep(const Dataset& run, const Dataset* secondRun,
                      const std::vector<ParameterSet>& sets, const SweepSettings& settings,
                      const SweepProgress& progress, const std::atomic<bool>* cancel) {
  for (const Dataset* d : {&run, secondRun}) {
    if (d && settings.pose == PoseSource::Truth && !d->hasTruth())
      throw MapperError("the log has no true pose for every scan; map with odometry (--pose odom)");
  }
  SweepOutcome out;
  out.rows.resize(sets.size());
  out.done.assign(sets.size(), false);

  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  std::mutex mutex;  // guards finished, out.done and the progress calls
  std::size_t finished = 0;

  // Sets are handed out one at a time, so a thread that draws quick sets takes more of them. A
  // failure (an error in one set, a thread that cannot start) stops the others at their next set
  // or scan and reaches the caller from runParallel.
  auto work = [&](unsigned) {
    while (!stop.load(std::memory_order_relaxed)) {
      const std::size_t i = next.fetch_add(1, std::memory_order_relaxed);
      if (i >= sets.size()) return;
      MapperSettings ms;
      ms.model = settings.model;
      ms.rule = settings.rule;
      ms.parameters = sets[i];
      ms.pose = settings.pose;
      Mapper mapper(run.ring, settings.grid, ms);
      VsdnsAccumulator vsdns;
      mapper.setObserver(&vsdns);
      if (!mapRun(mapper, run, cancel, stop)) return;
      SweepRow row;
      const VsdnsAccumulator::Result spread = vsdns.result();
      row.vsdns = spread.vsdns;
      row.cellsWithSpread = spread.cellsWithSpread;
      const OccupancyMap first = mapper.snapshot();
      row.noise = derivativeNoise(first);
      if (secondRun) {
        Mapper again(secondRun->ring, settings.grid, ms);
        if (!mapRun(again, *secondRun, cancel, stop)) return;
        row.twoRuns = compareTwoRuns(first, again.snapshot());
      }
      out.rows[i] = row;
      const std::lock_guard<std::mutex> lock(mutex);
      out.done[i] = true;
      ++finished;
      if (progress) progress(finished, sets.size());
    }
  };
  const auto threads =
      static_cast<unsigned>(std::clamp<std::size_t>(sets.size(), 1, parallelThreads()));
  runParallel(threads, work, [&] { stop.store(true); });
  out.completed = std::all_of(out.done.begin(), out.done.end(), [](bool b) { return b; });
  return out;
}

}  // namespace sg
