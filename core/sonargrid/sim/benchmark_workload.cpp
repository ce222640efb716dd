// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/sim/benchmark_workload.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include "sonargrid/sim/ray_sonar.h"

namespace sg::workload {

GridSpec benchmarkGrid() {
  return GridSpec::covering(Position(0, 0), Position(40, 30), 0.05, 0.0);
}

Pose2D lawnMower(int k, int scans) {
  const double s = kRows * kRowLength * k / scans;
  const int row = static_cast<int>(s / kRowLength);
  const double along = s - row * kRowLength;
  const bool east = row % 2 == 0;
  return Pose2D(east ? 1.0 + along : 39.0 - along, 1.0 + 2.0 * row, east ? 0.0 : 3.14159265);
}

Dataset simulatedWorkload(int readings) {
  std::vector<Segment> world;
  auto box = [&world](double x0, double y0, double x1, double y1) {
    const std::vector<Position> c{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    const auto s = polygonSegments(c, true);
    world.insert(world.end(), s.begin(), s.end());
  };
  box(0.0, 0.0, 40.0, 30.0);
  // 0.6 m pillars halfway between lanes (y = 2, 4, …, 28), every 3 m.
  for (int j = 1; j < 15; ++j) {
    for (int i = 0; i < 13; ++i) box(1.7 + 3.0 * i, 2.0 * j - 0.3, 2.3 + 3.0 * i, 2.0 * j + 0.3);
  }
  const SonarRing ring = SonarRing::pioneer3dx();
  const int scans = readings / static_cast<int>(ring.size());
  std::vector<TimedPose> route;
  for (int k = 0; k < scans; ++k) route.push_back(TimedPose{0.1 * k, lawnMower(k, scans)});
  SonarPhysics physics;
  physics.seed = 20261121;
  return simulateRoute(world, route, ring, physics, "benchmark hall");
}

Dataset stressWorkload(int readings) {
  Dataset d;
  d.name = "benchmark workload";
  d.ring = SonarRing::pioneer3dx();
  d.ring.maxRange = 5.0;
  std::mt19937_64 rng(20261121);
  // Uniform doubles from raw bits keep the workload identical on every standard library.
  auto uniform = [&rng]() { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  const int scans = readings / static_cast<int>(d.ring.size());
  for (int k = 0; k < scans; ++k) {
    Scan scan;
    scan.time = 0.1 * k;
    scan.odometry = lawnMower(k, scans);
    scan.truth = scan.odometry;
    for (std::uint16_t i = 0; i < d.ring.size(); ++i) {
      const double range = uniform() < 0.15 ? Reading::kNoEcho : 0.3 + 4.7 * uniform();
      scan.readings.push_back(Reading{i, range, scan.time});
    }
    d.scans.push_back(std::move(scan));
  }
  return d;
}

namespace {

// Distance from p along its heading to the walls of the room [0, 10] × [0, 8].
double toWall(const Pose2D& p) {
  const double c = std::cos(p.heading), s = std::sin(p.heading);
  double t = 1e9;
  if (c > 1e-9) t = std::min(t, (10.0 - p.x()) / c);
  if (c < -1e-9) t = std::min(t, -p.x() / c);
  if (s > 1e-9) t = std::min(t, (8.0 - p.y()) / s);
  if (s < -1e-9) t = std::min(t, -p.y() / s);
  return t;
}

}  // namespace

Dataset roomLoopLog(std::size_t readings) {
  Dataset d;
  d.name = "bench_load";
  d.ring = SonarRing::pioneer3dx();
  const std::size_t sonars = d.ring.size();
  const std::size_t scans = readings / sonars;
  d.scans.reserve(scans);
  for (std::size_t k = 0; k < scans; ++k) {
    const double t = 0.1 * static_cast<double>(k);
    const double a = 2.0 * std::numbers::pi * static_cast<double>(k % 600) / 600.0;
    Scan& s = d.scans.emplace_back();
    s.time = t;
    s.odometry = Pose2D(5.0 + 3.0 * std::cos(a), 4.0 + 2.5 * std::sin(a),
                        wrapAngle(a + std::numbers::pi / 2));
    s.truth = s.odometry;
    s.readings.reserve(sonars);
    for (std::size_t i = 0; i < sonars; ++i) {
      const double r = toWall(s.odometry.compose(d.ring.sonars[i].pose));
      s.readings.push_back(
          Reading{static_cast<std::uint16_t>(i), r < d.ring.maxRange ? r : Reading::kNoEcho, t});
    }
  }
  return d;
}

MapperSettings Pair::settings() const {
  MapperSettings s;
  s.model = model;
  s.rule = rule;
  return s;
}

std::vector<Pair> allowedPairs() {
  std::vector<Pair> pairs;
  for (const std::string& m : sensorModelNames()) {
    for (const std::string& r : updateRuleNames()) {
      if (compatibility(m, r).allowed) pairs.push_back({m, r});
    }
  }
  return pairs;
}

std::vector<double> remapMilliseconds(Mapper& mapper, const Dataset& data, int repeats) {
  using Clock = std::chrono::steady_clock;
  std::vector<double> ms;
  for (int k = 0; k < repeats; ++k) {
    const Clock::time_point t0 = Clock::now();
    mapper.mapDataset(data);
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  }
  return ms;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace sg::workload
