// SPDX-License-Identifier: BSD-3-Clause
// Large bag timing (docs/performance.md, "Large bags"): a bag opens in the time its sonar topics
// take, not the time of the whole file. Loads BIG (the room log beside a camera topic of about
// 1 GB: tests/bench/make_big_bag.py, written by python3-rosbag) and SMALL (the same sonar,
// odometry and truth messages alone: tests/data/bags/room/room-none.bag), each in a fresh child
// process, and reports for each the time to list its topics (inspectBag), to read it (readLog),
// and the peak RSS; then checks that both give the same log.
//
//   bench_bag BIG.bag SMALL.bag [RUNS=3]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "bench_process.h"
#include "sonargrid/io/bag/bag_log.h"
#include "sonargrid/io/log_reader.h"

namespace {

using sg::bench::msSince;
using sg::bench::statusKb;

void openAndRead(const std::string& path, int runs) {
  std::vector<double> inspect, read;
  std::size_t readings = 0, progressCalls = 0;
  for (int i = 0; i < runs; ++i) {
    auto t0 = std::chrono::steady_clock::now();
    const sg::bag::Overview o = sg::bag::inspectBag(path);
    inspect.push_back(msSince(t0));
    sg::LogOptions options;
    progressCalls = 0;
    options.progress = [&](std::uint64_t, std::uint64_t) { ++progressCalls; };
    t0 = std::chrono::steady_clock::now();
    const sg::Dataset d = sg::readLog(path, options);
    read.push_back(msSince(t0));
    readings = d.readingCount();
  }
  std::sort(inspect.begin(), inspect.end());
  std::sort(read.begin(), read.end());
  std::printf(
      "%-28s file %8.1f MB  topics %7.1f ms  read %8.1f ms (median of %d; %zu progress calls)  "
      "%zu readings  peak RSS %6.1f MB\n",
      std::filesystem::path(path).filename().c_str(),
      static_cast<double>(std::filesystem::file_size(path)) / 1e6, inspect[inspect.size() / 2],
      read[read.size() / 2], runs, progressCalls, readings,
      static_cast<double>(statusKb("VmHWM")) / 1024.0);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: bench_bag BIG.bag SMALL.bag [RUNS=3]\n");
    return 2;
  }
  const std::string big = argv[1], small = argv[2];
  const int runs = argc > 3 ? std::max(1, std::atoi(argv[3])) : 3;
  bool ok = sg::bench::inChild("bench_bag", [&] { openAndRead(small, runs); });
  ok = ok && sg::bench::inChild("bench_bag", [&] { openAndRead(big, runs); });
  ok = ok && sg::bench::inChild("bench_bag", [&] {
         const sg::Dataset a = sg::readLog(big), b = sg::readLog(small);
         // The log's name says which file it came from; the rest must be the same.
         const bool same = a.ring == b.ring && a.scans == b.scans;
         std::printf("same log from both: %s\n", same ? "yes" : "NO");
         std::fflush(stdout);
         if (!same) _exit(1);
       });
  return ok ? 0 : 1;
}
