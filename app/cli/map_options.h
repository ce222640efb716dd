// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The flags every command that builds a map shares (`map`, `score`, `goodness`):
// --log, --pose, --model, --rule, --set, --cell, --until, --threads (thread_flags.h), and the
// log-reading flags --format, --lenient, --robot, --columns, --poses (log_flags.cpp) that every
// command reading a log takes.

#include <atomic>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "arguments.h"
#include "sonargrid/data/dataset.h"
#include "sonargrid/engine/mapper.h"
#include "sonargrid/engine/occupancy_map.h"
#include "sonargrid/io/log_options.h"

namespace sg::cli {

struct MapOptions {
  std::string log;
  LogOptions read;  // how to read --log (and a second log)
  MapperSettings settings;
  double cell = 0.05;
  double until = std::numeric_limits<double>::infinity();
  // The forward model's line of progress per EM iteration on stderr (`map`, `score`); `compare`,
  // which maps several configurations at once, turns it off.
  bool progress = true;
};

// Consumes the map flags; throws UsageError for bad, missing or unknown ones (model, rule, --set,
// --threads, SONARGRID_THREADS) and InputError for an incompatible model/rule pair. --threads sets
// the thread policy for the rest of the command.
MapOptions parseMapOptions(Arguments& args);

// Consumes --format, --lenient, --robot, --columns and --poses; throws UsageError for bad values
// and InputError for a malformed geometry file.
LogOptions parseLogOptions(Arguments& args);

// Reads the log (InputError naming file, line and field when it is malformed). Lines skipped with
// --lenient are reported on stderr, one line per reason.
Dataset loadLog(const std::string& path, const LogOptions& options, LoadReport* report = nullptr);
Dataset loadLog(const std::string& path);

// What EM did for a forward-model map (docs/forward-model.md).
struct ForwardRun {
  std::vector<double> logLikelihood;  // the start, then after each iteration
  int iterations = 0;
  bool converged = false;
  std::size_t coneCells = 0;  // cells of all cones: what one iteration visits
};

struct BuiltMap {
  OccupancyMap map;
  std::size_t readings = 0;
  double elapsedMs = 0.0;  // mapping only, not reading the log
  // Scans left out for want of the pose asked for (--pose truth: a scan without a true pose;
  // core/sonargrid/data/scan_poses.h). buildMap says so on stderr.
  std::size_t scansWithoutTruth = 0;
  std::optional<ForwardRun> em;  // for --model forward-em
};
// The log's fitting grid at --cell; GridLimitError naming `logPath`, the scan and the grid limit
// when it cannot be made (main() makes that exit status 2).
GridSpec fittingGridOf(const Dataset& data, const MapOptions& options, const std::string& logPath);
// A map stopped part-way by `cancel` (buildMap): nothing was made.
struct MapStopped {};

// Maps `data`, read from `logPath` (for messages), on `grid` — by default the log's own fitting
// grid at --cell — feeding `observer` (if any) every footprint. `cancel` (a signal's flag, for a
// command that maps one log: `map`) stops it part-way with MapStopped.
BuiltMap buildMap(const Dataset& data, const MapOptions& options, const std::string& logPath,
                  const std::optional<GridSpec>& grid = std::nullopt,
                  FootprintObserver* observer = nullptr, const std::atomic<bool>* cancel = nullptr);

}  // namespace sg::cli
