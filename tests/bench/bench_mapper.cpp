// SPDX-License-Identifier: BSD-3-Clause
// Full re-map time per model × rule (issue 2's benchmark target: ≤ 300 ms for every pair), on the
// two workloads of bench_workload.h (100 000 readings each, default parameters):
//   sim/…     the simulated hall, what a robot would log there;
//   stress/…  uniform random ranges, an upper bound.
// Run: build/tests/bench/bench_mapper --benchmark_filter=sim --benchmark_repetitions=7
// --benchmark_report_aggregates_only=true

#include <benchmark/benchmark.h>

#include "bench_workload.h"
#include "sonargrid/engine/mapper.h"

namespace {

const sg::Dataset& stressWorkload() {
  static const sg::Dataset d = bench::stressWorkload(bench::kReadings);
  return d;
}

const sg::Dataset& simulatedWorkload() {
  static const sg::Dataset d = bench::simulatedWorkload(bench::kReadings);
  return d;
}

void remap(benchmark::State& state, const sg::Dataset& d, const std::string& model,
           const std::string& rule) {
  const sg::GridSpec grid = bench::benchmarkGrid();
  sg::MapperSettings settings;
  settings.model = model;
  settings.rule = rule;
  sg::Mapper mapper(d.ring, grid, settings);
  for (auto _ : state) {
    mapper.mapDataset(d);
    benchmark::DoNotOptimize(mapper.readingsIntegrated());
  }
  state.counters["readings"] = static_cast<double>(d.readingCount());
  state.counters["cells/reading"] = bench::cellsPerReading(mapper, d);
}

int registerAll() {
  for (const sg::workload::Pair& p : sg::workload::allowedPairs()) {
    const std::string m = p.model, r = p.rule;
    benchmark::RegisterBenchmark(
        ("sim/" + m + "/" + r).c_str(),
        [m, r](benchmark::State& s) { remap(s, simulatedWorkload(), m, r); })
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1)
        ->UseRealTime();
    benchmark::RegisterBenchmark(("stress/" + m + "/" + r).c_str(),
                                 [m, r](benchmark::State& s) { remap(s, stressWorkload(), m, r); })
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1)
        ->UseRealTime();
  }
  return 0;
}
const int kRegistered = registerAll();

}  // namespace

BENCHMARK_MAIN();
