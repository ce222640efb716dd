// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The scoring flags `score` and `compare` share (docs/cli.md): --metrics, --pairs, --seed,
// --iop-weight, --filled-threshold; and the text labels of the metrics.

#include <optional>
#include <vector>

#include "arguments.h"
#include "sonargrid/metrics/reference_score.h"

namespace sg::cli {

// Consumes the scoring flags; UsageError naming the flag for a bad value.
ScoreOptions parseScoreOptions(Arguments& args);

// One metric as `score` prints it: its text label, unit and decimals. Its JSON key (the
// contract) is metricJsonKey(metric).
struct MetricFormat {
  Metric metric;
  const char* label;  // "IOP", "correlation", ...
  const char* unit;   // " mm", " %", ""
  int precision;
};
// Every metric, in the order of the JSON contract.
const std::vector<MetricFormat>& metricFormats();

// "12.34 mm" with the metric's decimals; "undefined" when empty.
std::string formatMetric(const std::optional<double>& v, const char* unit, int precision);

}  // namespace sg::cli
