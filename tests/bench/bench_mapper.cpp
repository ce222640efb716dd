// Full re-map time per model × rule (issue 2's benchmark target: ≤ 300 ms for every pair).
// Workload: a Pioneer-style 16-sonar ring driving a lawn-mower path over a 40 m × 30 m area,
// 100 000 readings, maximum range 5 m, 5 cm cells. Ranges are drawn uniformly from [0.3, 5) m with
// 15 % no-echo readings (fixed seed): more cells per reading than a real room gives, so the
// numbers are an upper bound. Run: build/tests/bench/bench_mapper --benchmark_repetitions=5
//   --benchmark_report_aggregates_only=true

#include <benchmark/benchmark.h>

#include <cstdint>
#include <random>

#include "sonargrid/mapper.h"

namespace {

sg::Dataset makeWorkload() {
  sg::Dataset d;
  d.name = "benchmark workload";
  d.ring = sg::SonarRing::pioneer3dx();
  d.ring.maxRange = 5.0;
  std::mt19937_64 rng(20261121);
  // Uniform doubles from raw bits keep the workload identical on every standard library.
  auto uniform = [&rng]() { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  constexpr int kReadings = 100000;
  const int scans = kReadings / static_cast<int>(d.ring.size());
  // Lawn-mower rows 2 m apart across 38 m × 28 m.
  const double rowLength = 38.0;
  const int rows = 15;
  const double pathLength = rows * rowLength;
  for (int k = 0; k < scans; ++k) {
    const double s = pathLength * k / scans;
    const int row = static_cast<int>(s / rowLength);
    const double along = s - row * rowLength;
    const bool east = row % 2 == 0;
    sg::Scan scan;
    scan.time = 0.1 * k;
    scan.odometry = sg::Pose2D(east ? 1.0 + along : 39.0 - along, 1.0 + 2.0 * row, east ? 0.0 : 3.14159265);
    scan.truth = scan.odometry;
    for (std::uint16_t i = 0; i < d.ring.size(); ++i) {
      const double range = uniform() < 0.15 ? sg::Reading::kNoEcho : 0.3 + 4.7 * uniform();
      scan.readings.push_back(sg::Reading{i, range, scan.time});
    }
    d.scans.push_back(std::move(scan));
  }
  return d;
}

const sg::Dataset& workload() {
  static const sg::Dataset d = makeWorkload();
  return d;
}

void remap(benchmark::State& state, const std::string& model, const std::string& rule) {
  const sg::Dataset& d = workload();
  sg::GridSpec grid = sg::GridSpec::covering(sg::Position(0, 0), sg::Position(40, 30), 0.05, 0.0);
  sg::MapperSettings settings;
  settings.model = model;
  settings.rule = rule;
  sg::Mapper mapper(d.ring, grid, settings);
  for (auto _ : state) {
    mapper.mapDataset(d);
    benchmark::DoNotOptimize(mapper.readingsIntegrated());
  }
  state.counters["readings"] = static_cast<double>(d.readingCount());
}

int registerAll() {
  for (const std::string& m : sg::sensorModelNames()) {
    for (const std::string& r : sg::updateRuleNames()) {
      if (!sg::compatibility(m, r).allowed) continue;
      benchmark::RegisterBenchmark(("remap/" + m + "/" + r).c_str(),
                                   [m, r](benchmark::State& s) { remap(s, m, r); })
          ->Unit(benchmark::kMillisecond)
          ->Iterations(1);
    }
  }
  return 0;
}
const int kRegistered = registerAll();

}  // namespace

BENCHMARK_MAIN();
