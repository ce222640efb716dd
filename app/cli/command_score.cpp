// SPDX-License-Identifier: GPL-3.0-or-later
// `sonargrid-cli score`: a built map against a reference (docs/cli.md, docs/metrics.md). The map
// is built from a log with the flags of `map`, or read from a ROS map_server .yaml.

#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "commands.h"
#include "map_options.h"
#include "sonargrid/metrics/reference_score.h"
#include "sonargrid/reference/read_reference.h"
#include "sonargrid/reference/ros_map_reader.h"

namespace sg::cli {
namespace {

// The JSON keys of the contract, in order, with the metric each reports.
struct JsonKey {
  const char* key;
  Metric metric;
};
constexpr JsonKey kJsonKeys[] = {
    {"iop_mm", Metric::Iop},
    {"correlation_pct", Metric::Correlation},
    {"map_score_pct", Metric::MapScore},
    {"map_score_occupied_pct", Metric::MapScoreOccupied},
    {"match_bits", Metric::Match},
    {"path_false_positive_pct", Metric::PathFalsePositive},
    {"path_false_negative_pct", Metric::PathFalseNegative},
    {"cross_entropy", Metric::CrossEntropy},
    {"brier", Metric::Brier},
    {"auc", Metric::Auc},
    {"precision", Metric::Precision},
    {"recall", Metric::Recall},
    {"f1", Metric::F1},
    {"iou", Metric::Iou},
};

std::string formatted(const std::optional<double>& v, const char* unit, int precision = 2) {
  if (!v) return "undefined";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f%s", precision, *v, unit);
  return buffer;
}

struct Line {
  Metric metric;
  const char* label;
  const char* unit;
  int precision;
};

void printText(const ReferenceScore& s, const OccupancyMap& map, const std::string& source,
               const std::string& referencePath, const ScoreOptions& options, double elapsedMs) {
  std::cout << source << " scored against " << referencePath << "\n  grid " << map.spec.width
            << " x " << map.spec.height << " cells of " << map.spec.cellSize << " m; APG "
            << s.apgCells << " cells; ideal map: " << s.idealOccupied << " occupied, "
            << s.idealFree << " free, " << s.idealUnknown << " unknown; " << s.cellsEvaluated
            << " cells evaluated\n";
  static const Line kLines[] = {
      {Metric::Iop, "IOP", " mm", 1},
      {Metric::Correlation, "correlation", " %", 2},
      {Metric::MapScore, "map score", " %", 2},
      {Metric::MapScoreOccupied, "map score, occupied cells", " %", 2},
      {Metric::Match, "match (Moravec-Blackwell)", " bits", 1},
      {Metric::PathFalsePositive, "path false positives", " %", 1},
      {Metric::PathFalseNegative, "path false negatives", " %", 1},
      {Metric::CrossEntropy, "cross-entropy", " bits/cell", 4},
      {Metric::Brier, "Brier score", "", 4},
      {Metric::Auc, "ROC AUC", "", 4},
      {Metric::Precision, "precision (occupied)", "", 4},
      {Metric::Recall, "recall (occupied)", "", 4},
      {Metric::F1, "F1 (occupied)", "", 4},
      {Metric::Iou, "IoU (occupied)", "", 4},
  };
  for (const Line& l : kLines) {
    if (s.computed.count(l.metric) == 0) continue;
    std::string label = l.label;
    label.resize(28, ' ');
    std::cout << "  " << label << formatted(s.value(l.metric), l.unit, l.precision);
    if (l.metric == Metric::Iop) {
      std::cout << "  (" << s.iop.filledCells << " filled cells, sum of CV " << s.iop.cvSum << ")";
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
  ScoreOptions options;
  if (const auto list = args.value("--metrics")) {
    try {
      options.metrics = parseMetricList(*list);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--metrics: ") + e.what());
    }
  }
  const double pairs = args.number("--pairs", kDefaultPathPairs, 0, 1'000'000);
  if (pairs != std::floor(pairs)) throw UsageError("--pairs expects a whole number");
  options.pairs = static_cast<int>(pairs);
  if (const auto seed = args.value("--seed")) options.seed = parseSeed(*seed);
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

  if (json) {
    nlohmann::ordered_json out;
    for (const JsonKey& k : kJsonKeys) {
      if (score.computed.count(k.metric) == 0) continue;  // not asked for: omitted
      const std::optional<double> v = score.value(k.metric);
      out[k.key] =
          v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(nullptr);  // undefined: null
    }
    out["cells_evaluated"] = score.cellsEvaluated;
    std::cout << out.dump() << '\n';
  } else {
    printText(score, map, source, referencePath, options, elapsedMs);
  }
  return 0;
}

}  // namespace sg::cli
