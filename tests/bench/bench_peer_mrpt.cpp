// SPDX-License-Identifier: BSD-3-Clause
// Peer benchmark (issue 15): the same 100 000-reading workload (core/sonargrid/sim/
// benchmark_workload.h) mapped by MRPT 2.5's COccupancyGridMap2D sonar insertion and by SonarGrid,
// in one process, alternating, and the ratio MRPT / SonarGrid per model × rule pair (above 1:
// SonarGrid is faster). Built only when Debian's libmrpt-dev is installed (README, "Benchmark").
//
// Fair, as issue 15 asks:
//   - one CObservationRange per reading (MRPT's sonar observation), with the ring's aperture and
//     maximum range, the sensor's pose on the robot and the robot's odometry pose;
//   - readings without an echo are skipped by both (SonarGrid's models skip them by default,
//     no_echo = 0);
//   - MRPT's grid is the workload's 40 m × 30 m at 5 cm plus a margin of the maximum range and a
//     metre on every side, so no cone leaves it (and it never resizes during insertion);
//   - the observations are built before the clock starts, as SonarGrid's log is loaded before.
// MRPT runs on one thread (its insertion is serial); SonarGrid on the thread policy's threads,
// --threads N (issue 15's target is at 2).
//
//   bench_peer_mrpt [--threads N] [--repeat K] [--stress] [--only TEXT]
//
// Prints the median of K (default 5) timed runs of each, per pair (with --only, the pairs whose
// model/rule name contains TEXT).

#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/obs/CObservationRange.h>
#include <mrpt/poses/CPose3D.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "bench_workload.h"
#include "sonargrid/base/concurrency.h"
#include "sonargrid/engine/mapper.h"

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

struct Observation {
  mrpt::poses::CPose3D robot;
  mrpt::obs::CObservationRange range;
};

// One CObservationRange per reading with an echo.
std::vector<Observation> observations(const sg::Dataset& d) {
  std::vector<Observation> out;
  for (const sg::Scan& scan : d.scans) {
    const sg::Pose2D& p = scan.odometry;
    for (const sg::Reading& r : scan.readings) {
      if (!r.echo() || r.range >= d.ring.maxRange) continue;
      Observation& o = out.emplace_back();
      o.robot = mrpt::poses::CPose3D(p.x(), p.y(), 0.0, p.heading, 0.0, 0.0);
      o.range.minSensorDistance = static_cast<float>(d.ring.minRange);
      o.range.maxSensorDistance = static_cast<float>(d.ring.maxRange);
      o.range.sensorConeApperture = static_cast<float>(d.ring.apertureRad);
      const sg::Pose2D& mount = d.ring.sonars[r.sonar].pose;
      mrpt::obs::CObservationRange::TMeasurement m;
      m.sensorID = r.sonar;
      m.sensorPose = mrpt::math::TPose3D(mount.x(), mount.y(), 0.0, mount.heading, 0.0, 0.0);
      m.sensedDistance = static_cast<float>(r.range);
      o.range.sensedData.push_back(m);
    }
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  unsigned threads = 2;
  int repeat = 5;
  bool stress = false;
  std::string only;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--threads") == 0 && i + 1 < argc) {
      threads = static_cast<unsigned>(std::atoi(argv[++i]));
    } else if (std::strcmp(argv[i], "--repeat") == 0 && i + 1 < argc) {
      repeat = std::max(1, std::atoi(argv[++i]));
    } else if (std::strcmp(argv[i], "--stress") == 0) {
      stress = true;
    } else if (std::strcmp(argv[i], "--only") == 0 && i + 1 < argc) {
      only = argv[++i];
    } else {
      std::fprintf(stderr,
                   "usage: bench_peer_mrpt [--threads N] [--repeat K] [--stress] [--only TEXT]\n");
      return 2;
    }
  }
  if (threads < 1 || threads > sg::kMaxThreads) {
    std::fprintf(stderr, "bench_peer_mrpt: --threads must be 1 to %u\n", sg::kMaxThreads);
    return 2;
  }
  sg::ScopedThreadCount policy(threads);

  const sg::Dataset d =
      stress ? bench::stressWorkload(bench::kReadings) : bench::simulatedWorkload(bench::kReadings);
  const sg::GridSpec grid = bench::benchmarkGrid();
  const std::vector<Observation> obs = observations(d);
  const double margin = d.ring.maxRange + 1.0;
  const auto cell = static_cast<float>(grid.cellSize);
  const float x0 = static_cast<float>(grid.origin.x() - margin);
  const float y0 = static_cast<float>(grid.origin.y() - margin);
  const float x1 = static_cast<float>(grid.origin.x() + grid.width * grid.cellSize + margin);
  const float y1 = static_cast<float>(grid.origin.y() + grid.height * grid.cellSize + margin);

  std::printf(
      "%s workload: %zu readings, %zu with an echo (one CObservationRange each); "
      "SonarGrid at %u threads, MRPT at 1; medians of %d\n",
      stress ? "stress" : "simulated", d.readingCount(), obs.size(), threads, repeat);

  // MRPT's time does not depend on the pair: it has one sonar model and one update.
  auto mrptOnce = [&] {
    mrpt::maps::COccupancyGridMap2D map(x0, x1, y0, y1, cell);
    const Clock::time_point t0 = Clock::now();
    for (const Observation& o : obs) map.insertObservation(o.range, o.robot);
    const double ms = msSince(t0);
    if (map.getSizeX() != static_cast<unsigned>(std::lround((x1 - x0) / cell)) &&
        map.getSizeX() != static_cast<unsigned>(std::lround((x1 - x0) / cell)) + 1) {
      std::fprintf(stderr, "bench_peer_mrpt: MRPT's grid resized: a cone left it\n");
      std::exit(1);
    }
    return ms;
  };
  std::printf("%-32s %10s %10s %8s\n", "model/rule", "sonargrid", "mrpt", "ratio");
  std::vector<double> ratios;
  for (const sg::workload::Pair& p : sg::workload::allowedPairs()) {
    if (p.key().find(only) == std::string::npos) continue;
    sg::Mapper mapper(d.ring, grid, p.settings());
    std::vector<double> ours, theirs;
    for (int k = 0; k < repeat; ++k) {  // alternating, so both see the same machine load
      ours.push_back(sg::workload::remapMilliseconds(mapper, d, 1).front());
      theirs.push_back(mrptOnce());
    }
    const double a = sg::workload::median(ours), b = sg::workload::median(theirs);
    ratios.push_back(b / a);
    std::printf("%-32s %10.1f %10.1f %7.2fx\n", p.key().c_str(), a, b, b / a);
    std::fflush(stdout);
  }
  if (ratios.empty()) {
    std::fprintf(stderr, "bench_peer_mrpt: no pair matches --only %s\n", only.c_str());
    return 2;
  }
  std::printf("lowest ratio %.2fx, median %.2fx\n", *std::min_element(ratios.begin(), ratios.end()),
              sg::workload::median(ratios));
  return 0;
}
