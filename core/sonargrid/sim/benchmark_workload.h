// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The standard re-map workloads (issue 2's benchmark target, issue 15's `sonargrid-cli bench`),
// shared by `sonargrid-cli bench`, tests/bench/bench_mapper, profile_remap, bench_load and
// bench_peer_mrpt, so that every timing is of the same readings.
// A Pioneer 3-DX 16-sonar ring drives a lawn-mower path over a 40 m × 30 m area; maximum range 5 m.
//   simulated  ranges ray-cast by the bundled simulator in a hall with a pillar every 3 m between
//              the lanes: what a robot would log there.
//   stress     ranges drawn uniformly from [0.3, 5) m, 15 % no-echo: more and longer cones than
//              any room gives, so an upper bound.
// Fewer readings spread the same path more thinly, so a small workload costs per reading what the
// full one does.

#include <cstddef>
#include <string>
#include <vector>

#include "sonargrid/data/dataset.h"
#include "sonargrid/data/pose.h"
#include "sonargrid/engine/grid_spec.h"
#include "sonargrid/engine/mapper.h"

namespace sg::workload {

inline constexpr int kReadings = 100000;
inline constexpr double kRowLength = 38.0;
inline constexpr int kRows = 15;

// The 40 m × 30 m area at 5 cm cells.
GridSpec benchmarkGrid();

// The robot pose after `k` of `scans` scans along lawn-mower rows 2 m apart (y = 1, 3, …, 29).
Pose2D lawnMower(int k, int scans);

Dataset simulatedWorkload(int readings);
Dataset stressWorkload(int readings);

// A large log for load timing (issue 6, "Large logs"): `readings` readings (62 500 scans of a
// 16-sonar Pioneer ring for a million) driving loops in a 10 m × 8 m room, each range the distance
// to the room's walls (no echo past the ring's maximum range).
Dataset roomLoopLog(std::size_t readings);

// What every re-map benchmark times (`sonargrid-cli bench`, bench_peer_mrpt): each model × rule
// pair the registry allows, keyed "model/rule", models then rules in registry order.
struct Pair {
  std::string model, rule;
  std::string key() const { return model + "/" + rule; }
  MapperSettings settings() const;  // the pair at its default parameters
};
std::vector<Pair> allowedPairs();

// Wall-clock milliseconds of `repeats` full re-maps (Mapper::mapDataset) of `data` by `mapper`, one
// each; the mapper (and its cone tables) is made before, as it is once per cell size in a session.
std::vector<double> remapMilliseconds(Mapper& mapper, const Dataset& data, int repeats);
// The median of timings (the mean of the middle two for an even count); 0 for none.
double median(std::vector<double> values);

}  // namespace sg::workload
