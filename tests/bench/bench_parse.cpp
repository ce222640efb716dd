// SPDX-License-Identifier: BSD-3-Clause
// Log parsing speed (moved out of tst_sglog, where no unit test may time anything): a 12 500-scan
// Pioneer log of 200 000 readings parsed from memory, as .sglog (the project's writer) and as a
// Player 3 writelog (its "%+07.3f" poses and "%.3f" ranges, the printf number rule). Reports body
// lines per second.
//   build/tests/bench/bench_parse --benchmark_repetitions=5 --benchmark_report_aggregates_only=true

#include <benchmark/benchmark.h>

#include <cstdio>
#include <sstream>
#include <string>

#include "sonargrid/io/log_reader.h"
#include "sonargrid/io/sglog.h"

namespace {

// 12 500 scans of the Pioneer's 16 sonars: ranges cycling over 0.2..4.7 m, a slow spiral of poses.
sg::Dataset makeLog() {
  sg::Dataset d;
  d.ring = sg::SonarRing::pioneer3dx();
  for (int i = 0; i < 12500; ++i) {
    sg::Scan& s = d.scans.emplace_back();
    s.time = i * 0.1;
    s.odometry = sg::Pose2D(i * 0.01, i * -0.003, i * 0.001);
    for (std::uint16_t k = 0; k < 16; ++k)
      s.readings.push_back({k, 0.2 + 0.0137 * ((i * 16 + k) % 331), i * 0.1 + k * 0.004});
  }
  return d;
}

const sg::Dataset& log() {
  static const sg::Dataset d = makeLog();
  return d;
}

void sglogParse(benchmark::State& state) {
  std::ostringstream out;
  sg::writeSglog(log(), out);
  const std::string text = out.str();
  for (auto _ : state) {
    std::istringstream in(text);
    const sg::Dataset back = sg::parseSglog(in, "bench");
    if (!(back == log())) state.SkipWithError("the parsed log differs from the written one");
    benchmark::DoNotOptimize(back.scans.data());
  }
  state.counters["lines/s"] =
      benchmark::Counter(static_cast<double>(log().readingCount() + log().scans.size()),
                         benchmark::Counter::kIsIterationInvariantRate);
  state.counters["bytes"] = static_cast<double>(text.size());
}

// The same scans as Player 3's writelog writes them (position2d 1:1 then sonar 1:1).
std::string playerText() {
  std::string out = "## Player version 3.0.2 \n## File version 0.3.0 \n";
  char buf[256];
  const sg::Dataset& d = log();
  std::snprintf(buf, sizeof buf, "%014.3f %u %u %s %02u %03u %03u %u ", 0.0, 16777343U, 6665U,
                "sonar", 0U, 4U, 1U, 16U);
  out += buf;
  for (const sg::SonarMount& m : d.ring.sonars) {
    std::snprintf(buf, sizeof buf, "%+07.3f %+07.3f %+07.4f ", m.pose.x(), m.pose.y(),
                  m.pose.heading);
    out += buf;
  }
  out += '\n';
  for (const sg::Scan& s : d.scans) {
    std::snprintf(buf, sizeof buf,
                  "%014.3f %u %u %s %02u %03u %03u %+07.3f %+07.3f %+04.3f %+07.3f %+07.3f "
                  "%+07.3f %d\n",
                  s.time, 16777343U, 6665U, "position2d", 0U, 1U, 1U, s.odometry.x(),
                  s.odometry.y(), s.odometry.heading, 0.3, 0.0, 0.1, 0);
    out += buf;
    std::snprintf(buf, sizeof buf, "%014.3f %u %u %s %02u %03u %03u %u ", s.time + 0.001, 16777343U,
                  6665U, "sonar", 0U, 1U, 1U, 16U);
    out += buf;
    for (const sg::Reading& r : s.readings) {
      std::snprintf(buf, sizeof buf, "%.3f ", r.range);
      out += buf;
    }
    out += '\n';
  }
  return out;
}

void playerParse(benchmark::State& state) {
  const std::string text = playerText();
  sg::LogOptions options;
  options.format = sg::LogFormat::Player;
  std::size_t lines = 0;
  for (auto _ : state) {
    sg::LoadReport report;
    const sg::Dataset d = sg::parseLog(text, "bench.log", options, &report);
    if (d.scans.size() != log().scans.size()) state.SkipWithError("scans lost");
    lines = report.lines;
    benchmark::DoNotOptimize(d.scans.data());
  }
  state.counters["lines/s"] =
      benchmark::Counter(static_cast<double>(lines), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["bytes"] = static_cast<double>(text.size());
}

}  // namespace

BENCHMARK(sglogParse)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(playerParse)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
