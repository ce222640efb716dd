// SPDX-License-Identifier: GPL-3.0-or-later
// `sonargrid-cli bench`: the standard speed workloads (issue 15), so that any user can compare
// machines (docs/cli.md, "bench"):
//   - the threads used (the thread policy: --threads, SONARGRID_THREADS, the affinity mask);
//   - the full re-map of the bundled office log, median per model/rule, with the exact engine,
//     and with the fast one for the pairs whose fast engine has cells of its own, and how far the
//     fast map is from the exact one there (docs/models.md, "Exact and fast engines");
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

// The median full re-map of `data` on `grid` per pair, in ms, with the engine of `precision`
// (under fast, only the pairs whose fast engine has cells of its own: the others map the same
// code under both).
Json remapTimes(const Dataset& data, const GridSpec& grid, const std::vector<workload::Pair>& pairs,
                int repeats, const char* what, bool progress, Precision precision) {
  Json out = Json::object();
  for (const workload::Pair& p : pairs) {
    if (precision == Precision::Fast && !hasFastCells(p.model, p.rule)) continue;
    MapperSettings settings = p.settings();
    settings.precision = precision;
    Mapper mapper(data.ring, grid, settings);
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

// Per pair with fast cells of its own, how the fast engine's map of `data` differs from the exact
// one's: the share of observed cells whose level differs (%) and the largest step (levels), the
// accuracy contract's first two figures (docs/models.md, "Exact and fast engines").
Json deviation(const Dataset& data, const GridSpec& grid,
               const std::vector<workload::Pair>& pairs) {
  Json out = Json::object();
  for (const workload::Pair& p : pairs) {
    if (!hasFastCells(p.model, p.rule)) continue;
    OccupancyMap maps[2];
    for (const Precision precision : {Precision::Exact, Precision::Fast}) {
      MapperSettings settings = p.settings();
      settings.precision = precision;
      Mapper mapper(data.ring, grid, settings);
      mapper.mapDataset(data);
      maps[precision == Precision::Fast] = mapper.snapshot();
    }
    std::size_t observed = 0, differing = 0;
    int step = 0;
    for (std::size_t i = 0; i < maps[0].level.size(); ++i) {
      if (!maps[0].observed[i]) continue;
      ++observed;
      const int d = std::abs(int(maps[0].level[i]) - int(maps[1].level[i]));
      differing += d > 0;
      step = std::max(step, d);
    }
    out[p.key()] = {
        {"levels_differ_pct", observed ? 100.0 * double(differing) / double(observed) : 0.0},
        {"max_level_step", step}};
  }
  return out;
}

// Bytes per cell of a rule (its exact cells, and its fast ones where they differ, as RULE/fast):
// its planes and the grid's mark (Grid::bytesPerCell), what a snapshot
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
    for (const Precision precision : {Precision::Exact, Precision::Fast}) {
      if (precision == Precision::Fast && !hasFastCells(settings.model, rule)) continue;
      settings.precision = precision;
      Mapper mapper(SonarRing::pioneer3dx(), spec, settings);
      const OccupancyMap m = mapper.snapshot();
      out[precision == Precision::Fast ? rule + "/fast" : rule] =
          mapper.storage().bytesPerCell() + m.bytesPerCell() + kViewUploaded;
    }
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
  std::cout << "the fast engine, where it has cells of its own, ms (office, workload), and how its "
               "map of the office log differs from the exact one:\n";
  for (const auto& [key, office] : r["office_remap_ms_fast"].items()) {
    const Json& d = r["fast_deviation_office"][key];
    std::snprintf(line, sizeof line, "  %-32s %10.1f %10.1f   levels differ in %.4f %%, by <= %d\n",
                  key.c_str(), office.get<double>(), r["workload_remap_ms_fast"][key].get<double>(),
                  d["levels_differ_pct"].get<double>(), d["max_level_step"].get<int>());
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
  r["office_remap_ms"] =
      remapTimes(office, officeGrid, pairs, repeats, "office", progress, Precision::Exact);
  r["workload_remap_ms"] =
      remapTimes(work, workGrid, pairs, repeats, "workload", progress, Precision::Exact);
  r["office_remap_ms_fast"] =
      remapTimes(office, officeGrid, pairs, repeats, "office fast", progress, Precision::Fast);
  r["workload_remap_ms_fast"] =
      remapTimes(work, workGrid, pairs, repeats, "workload fast", progress, Precision::Fast);
  r["fast_deviation_office"] = deviation(office, officeGrid, pairs);
  r["load_1m_readings_s"] = loadSeconds();
  r["bytes_per_cell"] = bytesPerCell();

  if (json)
    std::cout << r.dump() << '\n';
  else
    printText(r, officePath.string(), officeGrid, workGrid, repeats);
  return 0;
}

}  // namespace sg::cli
