// SPDX-License-Identifier: GPL-3.0-or-later
// `sonargrid-cli bench`: the standard speed workloads (issue 15), so that any user can compare
// machines (docs/cli.md, "bench"):
//   - the threads used (the thread policy: --threads, SONARGRID_THREADS, the affinity mask);
//   - the full re-map of the bundled office log, median per model/rule;
//   - the full re-map of the 100 000-reading, 16-sonar, 40 m × 30 m, 5 cm workload
//     (core/sonargrid/sim/benchmark_workload.h), median per model/rule;
//   - the load time of a 1 000 000-reading .sglog;
//   - the bytes each cell takes per rule, for a map at rest: the rule's planes, the grid's
//     observed/dirty mark, the snapshot's own layers and the OpenGL view's uploaded levels.

#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <system_error>
#include <vector>

#include "commands.h"
#include "reproduce/reproduce.h"
#include "sonargrid/base/concurrency.h"
#include "sonargrid/engine/mapper.h"
#include "sonargrid/io/log_reader.h"
#include "sonargrid/io/sglog.h"
#include "sonargrid/sim/benchmark_workload.h"
#include "thread_flags.h"

namespace sg::cli {
namespace {

using Json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

// Re-maps per pair whose median is reported: one in --quick.
constexpr int kRepeats = 5;
constexpr std::size_t kLoadReadings = 1000000;

double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// The median full re-map of `data` on `grid` per pair, in ms.
Json remapTimes(const Dataset& data, const GridSpec& grid, const std::vector<workload::Pair>& pairs,
                int repeats, const char* what, bool progress) {
  Json out = Json::object();
  for (const workload::Pair& p : pairs) {
    Mapper mapper(data.ring, grid, p.settings());
    out[p.key()] = workload::median(workload::remapMilliseconds(mapper, data, repeats));
    if (progress)
      std::cerr << "\r" << what << " " << out.size() << "/" << pairs.size() << std::flush;
  }
  if (progress) std::cerr << '\n';
  return out;
}

// Seconds to read a 1 000 000-reading .sglog (written to the temporary folder first, then
// removed).
double loadSeconds() {
  namespace fs = std::filesystem;
  const fs::path path =
      fs::temp_directory_path() / ("sonargrid_bench_" + std::to_string(getpid()) + ".sglog");
  writeSglog(workload::roomLoopLog(kLoadReadings), path.string());
  struct Remove {
    fs::path path;
    ~Remove() {
      std::error_code ec;
      fs::remove(path, ec);
    }
  } remove{path};
  const Clock::time_point t0 = Clock::now();
  const Dataset d = readLog(path.string());
  const double s = msSince(t0) / 1000.0;
  if (d.readingCount() != kLoadReadings) {
    throw std::runtime_error("the load benchmark read " + std::to_string(d.readingCount()) +
                             " readings of " + std::to_string(kLoadReadings));
  }
  return s;
}

// Bytes per cell of a rule: its planes and the grid's mark (Grid::bytesPerCell), what a snapshot
// keeps of its own (OccupancyMap::bytesPerCell: the level and observed flag; its other layers read
// the grid's planes, which it shares), and the byte per cell the OpenGL view keeps of the levels it
// uploaded (GridGlSurface, to send only the rows that changed).
Json bytesPerCell() {
  constexpr std::size_t kViewUploaded = 1;
  Json out = Json::object();
  const GridSpec spec = GridSpec::covering(Position(0, 0), Position(1, 1), 0.05, 0.0);
  for (const std::string& rule : updateRuleNames()) {
    MapperSettings settings;
    settings.rule = rule;
    settings.model = compatibility(settings.model, rule).allowed ? "hpf" : "himm";
    Mapper mapper(SonarRing::pioneer3dx(), spec, settings);
    const OccupancyMap m = mapper.snapshot();
    out[rule] = mapper.storage().bytesPerCell() + m.bytesPerCell() + kViewUploaded;
  }
  return out;
}

void printText(const Json& r, const std::string& officePath, const GridSpec& officeGrid,
               const GridSpec& workGrid, int repeats) {
  std::cout << "threads " << r["cores"].get<unsigned>() << "; medians of " << repeats
            << (repeats == 1 ? " re-map" : " re-maps") << " per pair\n";
  std::cout << "office full re-map (" << officePath << ", "
            << r["office_readings"].get<std::size_t>() << " readings, " << officeGrid.width << " x "
            << officeGrid.height << " cells of " << officeGrid.cellSize << " m) and the "
            << workload::kReadings << "-reading workload (" << workGrid.width << " x "
            << workGrid.height << " cells), ms:\n";
  char line[160];
  std::snprintf(line, sizeof line, "  %-32s %10s %10s\n", "model/rule", "office", "workload");
  std::cout << line;
  for (const auto& [key, office] : r["office_remap_ms"].items()) {
    std::snprintf(line, sizeof line, "  %-32s %10.1f %10.1f\n", key.c_str(), office.get<double>(),
                  r["workload_remap_ms"][key].get<double>());
    std::cout << line;
  }
  std::snprintf(line, sizeof line, "load of a %zu-reading .sglog: %.2f s\n", kLoadReadings,
                r["load_1m_readings_s"].get<double>());
  std::cout << line
            << "bytes per cell at rest (rule planes, grid marks, the snapshot's own layers, the "
               "view's levels):\n";
  for (const auto& [rule, bytes] : r["bytes_per_cell"].items())
    std::cout << "  " << rule << ' ' << bytes.get<std::size_t>() << '\n';
}

}  // namespace

int runBench(Arguments& args) {
  const bool quick = args.flag("--quick");
  const bool json = args.flag("--json");
  const bool progress = args.flag("--progress");
  applyThreadOptions(args);
  args.finish();

  const int repeats = quick ? 1 : kRepeats;
  const std::vector<workload::Pair> pairs = workload::allowedPairs();
  const reproduce::fs::path officePath = reproduce::defaultDatasets() / "office" / "office.sglog";
  const Dataset office = reproduce::loadDataset(officePath);
  const GridSpec officeGrid = office.fittingGrid(PoseSource::Odometry, 0.05);
  const Dataset work = workload::simulatedWorkload(workload::kReadings);
  const GridSpec workGrid = workload::benchmarkGrid();

  Json r;
  r["cores"] = threadCount();
  r["office_readings"] = office.readingCount();
  r["office_remap_ms"] = remapTimes(office, officeGrid, pairs, repeats, "office", progress);
  r["workload_remap_ms"] = remapTimes(work, workGrid, pairs, repeats, "workload", progress);
  r["load_1m_readings_s"] = loadSeconds();
  r["bytes_per_cell"] = bytesPerCell();

  if (json)
    std::cout << r.dump() << '\n';
  else
    printText(r, officePath.string(), officeGrid, workGrid, repeats);
  return 0;
}

}  // namespace sg::cli
