// SPDX-License-Identifier: GPL-3.0-or-later
// The scoring flags of `score` and `compare` (docs/cli.md, "score").

#include "score_flags.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace sg::cli {

ScoreOptions parseScoreOptions(Arguments& args) {
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
  if (const auto weight = args.value("--iop-weight")) {
    if (!parseIopWeight(*weight, options.iop.weight))
      throw UsageError("--iop-weight takes evidence or level, got '" + *weight + "'");
  }
  options.iop.filledThreshold = args.number("--filled-threshold", 0.0, 0.0, 15.0);
  return options;
}

const std::vector<MetricFormat>& metricFormats() {
  static const std::vector<MetricFormat> formats = {
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
  return formats;
}

std::string formatMetric(const std::optional<double>& v, const char* unit, int precision) {
  if (!v) return "undefined";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f%s", precision, *v, unit);
  return buffer;
}

}  // namespace sg::cli
