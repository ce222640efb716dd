// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The re-map workloads of issue 2's benchmark target (core/sonargrid/sim/benchmark_workload.h,
// shared with `sonargrid-cli bench`), for bench_mapper (wall-clock medians), profile_remap (a
// single-threaded driver for instruction counts under callgrind) and bench_peer_mrpt.

#include "sonargrid/engine/mapper.h"
#include "sonargrid/sim/benchmark_workload.h"

namespace bench {

using sg::workload::benchmarkGrid;
using sg::workload::kReadings;
using sg::workload::simulatedWorkload;
using sg::workload::stressWorkload;

// Cells written per reading over one batch re-map (not timed): what the time is spent on.
inline double cellsPerReading(sg::Mapper& mapper, const sg::Dataset& d) {
  struct Counter final : sg::FootprintObserver {
    std::size_t cells = 0;
    void reset(std::size_t) override { cells = 0; }
    void observe(const sg::Footprint& f) override { cells += f.cells.size(); }
  } counter;
  mapper.setObserver(&counter);
  mapper.mapDataset(d);
  mapper.setObserver(nullptr);
  return static_cast<double>(counter.cells) / static_cast<double>(d.readingCount());
}

}  // namespace bench
