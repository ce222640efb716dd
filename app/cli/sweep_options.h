// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The flags `sweep` and `optimize` share (docs/sweeps.md): the map flags of `map` (log, model,
// rule, pose, cell, --set, --threads, the log-reading flags), --second-log, --reference, --metric
// (repeatable) and --tie (repeatable); the logs and the reference read once; the fields that
// identify the sweep in its CSV.

#include <optional>
#include <string>
#include <vector>

#include "map_options.h"
#include "sonargrid/reference/reference_map.h"
#include "sonargrid/sweep/set_evaluation.h"
#include "sonargrid/sweep/sweep_grid.h"
#include "sweep_csv.h"

namespace sg::cli {

struct SweepOptions {
  MapOptions map;
  std::optional<std::string> secondLog;
  std::optional<std::string> referencePath;
  std::vector<std::string> metrics;  // canonical (parseSweepMetrics)
  std::string firstMetric;           // the first one written (optimize's objective)
  std::vector<SweepTie> ties;
  std::vector<std::pair<std::string, std::string>> logFlags;  // as given, for the fingerprint
};

// Consumes the shared flags. Throws UsageError for bad or missing ones: no --metric, a reference
// metric without --reference, two-run without --second-log, a bad --tie (naming the flag).
SweepOptions parseSweepOptions(Arguments& args);
// The same with the metrics chosen by the caller instead of --metric (`goodness-study`).
SweepOptions parseSweepOptions(Arguments& args, const std::vector<std::string>& metricTexts);

struct SweepData {
  Dataset run;
  std::optional<Dataset> secondRun;
  std::optional<ReferenceMap> reference;
  SweepSettings settings;  // model, rule, pose; grid: the log's fitting grid at --cell (with a
                           // second log, one grid over both runs)
  SetMeasures measures;    // what --metric asked for
  SetEvaluationInput input() const;
};
// Reads the logs and the reference (InputError naming the file).
SweepData loadSweepData(const SweepOptions& o);

// The identity fields of the sweep's CSV (metrics, model, rule, pose, cell, every parameter of the
// base set, the log-reading flags, a hash of each file read) and the notes (the files' paths).
// The caller appends its own fields (grid axes, ties).
void describeSweep(const SweepOptions& o, SweepHeader& header);

// "what: message" for an error while mapping or scoring: InputError naming the log or reference.
[[noreturn]] void rethrowEvaluationError(const SweepOptions& o);

// The --grid texts' axes and sets with the ties of `o` (sweepSpace()), UsageError naming the flag
// at fault ("--grid ...", "--grid: ..." or "--tie ...").
SweepSpace parseSweepSpace(const std::vector<std::string>& gridTexts, const SweepOptions& o);

// Parses "--shard I/N" (0 ≤ I < N); UsageError naming the flag.
std::pair<std::size_t, std::size_t> parseShard(const std::string& text);

}  // namespace sg::cli
