// SPDX-License-Identifier: GPL-3.0-or-later
// `sonargrid-cli score`: a built map against a reference (docs/cli.md, docs/metrics.md). The map
// is built from a log with the flags of `map`, or read from a ROS map_server .yaml.

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "commands.h"
#include "map_options.h"
#include "score_flags.h"
#include "sonargrid/metrics/reference_score.h"
#include "sonargrid/reference/read_reference.h"
#include "sonargrid/reference/ros_map_reader.h"

namespace sg::cli {
namespace {

void printText(const ReferenceScore& s, const OccupancyMap& map, const std::string& source,
               const std::string& referencePath, const ScoreOptions& options, double elapsedMs) {
  std::cout << source << " scored against " << referencePath << "\n  grid " << map.spec.width
            << " x " << map.spec.height << " cells of " << map.spec.cellSize << " m; APG "
            << s.apgCells << " cells; ideal map: " << s.idealOccupied << " occupied, "
            << s.idealFree << " free, " << s.idealUnknown << " unknown; " << s.cellsEvaluated
            << " cells evaluated\n";
  for (const MetricFormat& l : metricFormats()) {
    if (s.computed.count(l.metric) == 0) continue;
    std::string label = l.label;
    label.resize(28, ' ');
    std::cout << "  " << label << formatMetric(s.value(l.metric), l.unit, l.precision);
    if (l.metric == Metric::Iop) {
      std::cout << "  (" << s.iop.filledCells << " filled cells, sum of CV " << s.iop.cvSum
                << ", weight " << iopWeightName(options.iop.weight) << ")";
    } else if (l.metric == Metric::PathFalsePositive) {
      std::cout << "  (" << s.paths.collisions << " of " << s.paths.pathsFound << " paths collide)";
    } else if (l.metric == Metric::PathFalseNegative) {
      std::cout << "  (" << s.paths.noPath << " of " << s.paths.pairs
                << " pairs without a path; seed " << options.seed << ")";
    }
    std::cout << '\n';
  }
  std::cout << "  scored in " << elapsedMs << " ms\n";
}

}  // namespace

int runScore(Arguments& args) {
  const std::string referencePath = args.required("--reference");
  const ScoreOptions options = parseScoreOptions(args);
  const bool json = args.flag("--json");

  // --map FILE.yaml, or --log FILE with the flags of `map` (parsed by the same code).
  const std::optional<std::string> mapPath = args.value("--map");
  std::optional<MapOptions> mapOptions;
  if (mapPath) {
    if (args.value("--log")) throw UsageError("give --log or --map, not both");
  } else {
    Arguments probe = args;
    if (!probe.value("--log"))
      throw UsageError("score needs --log FILE (with the flags of map) or --map FILE.yaml");
    mapOptions = parseMapOptions(args);
  }
  args.finish();

  ReferenceMap reference;
  try {
    reference = readReference(referencePath);
  } catch (const LogError& e) {
    throw InputError(e.what());
  }

  OccupancyMap map;
  std::string source;
  if (mapPath) {
    try {
      map = rosMapAsBuiltMap(readRosMap(*mapPath));
    } catch (const LogError& e) {
      throw InputError(e.what());
    }
    source = *mapPath;
  } else {
    const Dataset data = loadLog(mapOptions->log, mapOptions->read);
    map = buildMap(data, *mapOptions, mapOptions->log).map;
    source = mapOptions->log + " (" + mapOptions->settings.model + " x " +
             mapOptions->settings.rule + ")";
  }

  const auto t0 = std::chrono::steady_clock::now();
  ReferenceScore score;
  try {
    score = scoreAgainstReference(map, reference, options);
  } catch (const MetricsError& e) {
    throw InputError(referencePath + ": " + e.what());
  }
  const double elapsedMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();

  // A reference that the map never saw gives numbers that mean nothing: say so, on stderr and in
  // the JSON (issue 17).
  for (const std::string& w : score.warnings)
    std::cerr << "sonargrid-cli: warning: " << referencePath << ": " << w << '\n';
  if (json) {
    nlohmann::ordered_json out;
    for (const MetricFormat& k : metricFormats()) {
      if (score.computed.count(k.metric) == 0) continue;  // not asked for: omitted
      const std::optional<double> v = score.value(k.metric);
      out[metricJsonKey(k.metric)] =
          v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(nullptr);  // undefined: null
    }
    out["cells_evaluated"] = score.cellsEvaluated;
    if (!score.warnings.empty()) out["warnings"] = score.warnings;
    std::cout << out.dump() << '\n';
  } else {
    printText(score, map, source, referencePath, options, elapsedMs);
  }
  return 0;
}

}  // namespace sg::cli
