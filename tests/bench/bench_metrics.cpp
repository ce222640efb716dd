// SPDX-License-Identifier: BSD-3-Clause
// Path comparison time on a large grid (moved out of tst_metrics, where no unit test may time
// anything): 800 x 600 cells of 5 cm (40 m x 30 m), a walled hall with 60 random wall segments,
// a map with every 7th wall cell missing and some noise, 100 start/goal pairs (docs/metrics.md).
//   build/tests/bench/bench_metrics --benchmark_repetitions=5
//   --benchmark_report_aggregates_only=true

#include <benchmark/benchmark.h>

#include <algorithm>
#include <string>

#include "sonargrid/engine/occupancy_map.h"
#include "sonargrid/metrics/ideal_map.h"
#include "sonargrid/metrics/path_comparison.h"
#include "sonargrid/metrics/seeded_random.h"
#include "sonargrid/reference/actual_position_grid.h"

namespace {

void pathComparisonLargeGrid(benchmark::State& state) {
  sg::GridSpec spec;
  spec.cellSize = 0.05;
  spec.width = 800;
  spec.height = 600;
  sg::ReferenceMap ref;
  ref.objects.push_back(sg::ReferenceObject{
      "walls", false, {{0.1, 0.1}, {39.9, 0.1}, {39.9, 29.9}, {0.1, 29.9}, {0.1, 0.1}}});
  sg::SeededRandom random(3);
  for (int k = 0; k < 60; ++k) {
    const double x = 1.0 + static_cast<double>(random.below(3800)) / 100.0;
    const double y = 1.0 + static_cast<double>(random.below(2800)) / 100.0;
    const double len = 1.0 + static_cast<double>(random.below(800)) / 100.0;
    const bool vertical = random.below(2) == 0;
    ref.objects.push_back(sg::ReferenceObject{
        "w" + std::to_string(k),
        false,
        {{x, y},
         {vertical ? x : std::min(39.0, x + len), vertical ? std::min(29.0, y + len) : y}}});
  }
  const sg::ActualPositionGrid apg = sg::ActualPositionGrid::rasterise(ref, spec);
  const sg::IdealMap ideal = sg::IdealMap::fromReference(ref, apg);
  sg::OccupancyMap map = sg::OccupancyMap::unobserved(spec);
  for (std::size_t i = 0; i < spec.cellCount(); ++i) {
    map.observed[i] = 1;
    map.probability[i] = apg.cells[i] && i % 7 != 0 ? 0.9 : (random.below(50) == 0 ? 0.8 : 0.1);
  }
  sg::PathComparison c;
  for (auto _ : state) {
    c = sg::comparePaths(map, ideal, 100, 1990);
    if (c.pairs != 100) state.SkipWithError("not 100 pairs");
    benchmark::DoNotOptimize(c.collisions);
  }
  state.counters["FP %"] = c.falsePositivePct.value_or(-1.0);
  state.counters["FN %"] = c.falseNegativePct.value_or(-1.0);
}

}  // namespace

BENCHMARK(pathComparisonLargeGrid)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
