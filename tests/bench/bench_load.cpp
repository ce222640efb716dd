// SPDX-License-Identifier: BSD-3-Clause
// Large-log timing (issue 6, "Large logs"): writes a log of one million readings (62 500 scans of a
// 16-sonar Pioneer ring driving loops in a 10 m x 8 m room) as .sglog and as CARMEN, then, each in
// a fresh child process so that nothing else inflates its memory, loads it through readLog and maps
// it with the engine. Reports load time, bytes per reading in memory (RSS growth and the Dataset's
// own arithmetic), peak RSS (VmHWM) and mapping time.
//
//   bench_load [READINGS]        (default 1000000; the files go to $TMPDIR and are removed)

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "bench_process.h"
#include "sonargrid/engine/mapper.h"
#include "sonargrid/io/carmen.h"
#include "sonargrid/io/log_reader.h"
#include "sonargrid/io/sglog.h"
#include "sonargrid/sim/benchmark_workload.h"

namespace {

using sg::bench::msSince;
using sg::bench::statusKb;

// The Dataset's heap and inline bytes, from its vectors' capacities.
std::size_t datasetBytes(const sg::Dataset& d) {
  std::size_t bytes = sizeof(sg::Dataset) + d.scans.capacity() * sizeof(sg::Scan);
  for (const sg::Scan& s : d.scans) bytes += s.readings.capacity() * sizeof(sg::Reading);
  return bytes;
}

void loadAndMap(const std::string& path, const char* label) {
  const long rssBefore = statusKb("VmRSS");
  int progressCalls = 0;
  sg::LogOptions options;
  options.progress = [&](std::uint64_t, std::uint64_t) { ++progressCalls; };
  const auto t0 = std::chrono::steady_clock::now();
  sg::LoadReport report;
  const sg::Dataset d = sg::readLog(path, options, &report);
  const double loadMs = msSince(t0);
  const long rssAfter = statusKb("VmRSS");
  const long hwm = statusKb("VmHWM");
  const auto n = static_cast<double>(d.readingCount());

  sg::MapperSettings settings;
  settings.model = "himm";
  settings.rule = "himm";
  settings.parameters = sg::defaultParameters(settings.model, settings.rule);
  const sg::GridSpec grid = d.fittingGrid(sg::PoseSource::Odometry, 0.05);
  sg::Mapper mapper(d.ring, grid, settings);
  const auto t1 = std::chrono::steady_clock::now();
  mapper.mapDataset(d);
  const double mapMs = msSince(t1);

  std::printf(
      "%-7s %9.0f readings  file %6.1f MB  load %7.1f ms (%d progress calls)  "
      "RSS +%6.1f MB = %5.1f B/reading  Dataset %5.1f B/reading  peak RSS %6.1f MB  "
      "map himm x himm %7.1f ms (%zu x %zu cells)\n",
      label, n, static_cast<double>(std::filesystem::file_size(path)) / 1e6, loadMs, progressCalls,
      static_cast<double>(rssAfter - rssBefore) / 1024.0,
      static_cast<double>(rssAfter - rssBefore) * 1024.0 / n,
      static_cast<double>(datasetBytes(d)) / n, static_cast<double>(hwm) / 1024.0, mapMs,
      static_cast<std::size_t>(grid.width), static_cast<std::size_t>(grid.height));
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const std::size_t readings = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 1000000;
  const std::filesystem::path dir = std::filesystem::temp_directory_path();
  const std::string stem = (dir / ("bench_load_" + std::to_string(getpid()))).string();
  const std::string sglog = stem + ".sglog";
  const std::string carmen = stem + ".clf";
  bool ok = sg::bench::inChild("bench_load", [&] {
    const sg::Dataset d = sg::workload::roomLoopLog(readings);
    sg::writeSglog(d, sglog);
    sg::writeCarmen(d, carmen);
  });
  ok = ok && sg::bench::inChild("bench_load", [&] { loadAndMap(sglog, "sglog"); });
  ok = ok && sg::bench::inChild("bench_load", [&] { loadAndMap(carmen, "carmen"); });
  std::filesystem::remove(sglog);
  std::filesystem::remove(carmen);
  return ok ? 0 : 1;
}
