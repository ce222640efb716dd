// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The re-map workloads of issue 2's benchmark target, shared by bench_mapper (wall-clock medians)
// and profile_remap (a single-threaded driver for instruction counts under callgrind).
// A Pioneer 3-DX 16-sonar ring drives a lawn-mower path over a 40 m × 30 m area; maximum range 5 m.
//   simulated  ranges ray-cast by the bundled simulator (core/sonargrid/sim) in a hall with a
//              pillar every 3 m between the lanes: what a robot would log there.
//   stress     ranges drawn uniformly from [0.3, 5) m, 15 % no-echo: more and longer cones than
//              any room gives, so an upper bound.
// Fewer readings spread the same path more thinly, so a small workload costs per reading what the
// full one does.

#include <cstdint>
#include <random>
#include <vector>

#include "sonargrid/dataset.h"
#include "sonargrid/grid_spec.h"
#include "sonargrid/mapper.h"
#include "sonargrid/sim/ray_sonar.h"

namespace bench {

constexpr int kReadings = 100000;
constexpr double kRowLength = 38.0;
constexpr int kRows = 15;

// The 40 m × 30 m area at 5 cm cells.
inline sg::GridSpec benchmarkGrid() {
  return sg::GridSpec::covering(sg::Position(0, 0), sg::Position(40, 30), 0.05, 0.0);
}

// The robot pose after `k` of `scans` scans along lawn-mower rows 2 m apart (y = 1, 3, …, 29).
inline sg::Pose2D lawnMower(int k, int scans) {
  const double s = kRows * kRowLength * k / scans;
  const int row = static_cast<int>(s / kRowLength);
  const double along = s - row * kRowLength;
  const bool east = row % 2 == 0;
  return sg::Pose2D(east ? 1.0 + along : 39.0 - along, 1.0 + 2.0 * row, east ? 0.0 : 3.14159265);
}

inline sg::Dataset simulatedWorkload(int readings) {
  std::vector<sg::Segment> world;
  auto box = [&world](double x0, double y0, double x1, double y1) {
    const std::vector<sg::Position> c{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    const auto s = sg::polygonSegments(c, true);
    world.insert(world.end(), s.begin(), s.end());
  };
  box(0.0, 0.0, 40.0, 30.0);
  // 0.6 m pillars halfway between lanes (y = 2, 4, …, 28), every 3 m.
  for (int j = 1; j < 15; ++j) {
    for (int i = 0; i < 13; ++i) box(1.7 + 3.0 * i, 2.0 * j - 0.3, 2.3 + 3.0 * i, 2.0 * j + 0.3);
  }
  const sg::SonarRing ring = sg::SonarRing::pioneer3dx();
  const int scans = readings / static_cast<int>(ring.size());
  std::vector<sg::TimedPose> route;
  for (int k = 0; k < scans; ++k) route.push_back(sg::TimedPose{0.1 * k, lawnMower(k, scans)});
  sg::SonarPhysics physics;
  physics.seed = 20261121;
  return sg::simulateRoute(world, route, ring, physics, "benchmark hall");
}

inline sg::Dataset stressWorkload(int readings) {
  sg::Dataset d;
  d.name = "benchmark workload";
  d.ring = sg::SonarRing::pioneer3dx();
  d.ring.maxRange = 5.0;
  std::mt19937_64 rng(20261121);
  // Uniform doubles from raw bits keep the workload identical on every standard library.
  auto uniform = [&rng]() { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  const int scans = readings / static_cast<int>(d.ring.size());
  for (int k = 0; k < scans; ++k) {
    sg::Scan scan;
    scan.time = 0.1 * k;
    scan.odometry = lawnMower(k, scans);
    scan.truth = scan.odometry;
    for (std::uint16_t i = 0; i < d.ring.size(); ++i) {
      const double range = uniform() < 0.15 ? sg::Reading::kNoEcho : 0.3 + 4.7 * uniform();
      scan.readings.push_back(sg::Reading{i, range, scan.time});
    }
    d.scans.push_back(std::move(scan));
  }
  return d;
}

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
