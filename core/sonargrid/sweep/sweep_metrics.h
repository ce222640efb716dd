// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The metrics a generic sweep can measure (docs/sweeps.md, --metric), shared by `sonargrid-cli
// sweep`/`optimize` and the app's sweep view so that both read one grammar and name the columns
// alike: paper 002's goodness measures (vsdns, derivative, two-run) and every reference metric of
// reference_score.h.

#include <optional>
#include <string>
#include <vector>

#include "sonargrid/sweep/set_evaluation.h"

namespace sg {

// Canonical names in column order: vsdns, derivative, two-run, then the reference metrics of
// `score` (iop, correlation, ...). Each text may be a comma-separated list; "path" stands for both
// path metrics. Duplicates are dropped. Throws SweepSpecError (sweep_grid.h) naming an unknown
// metric and listing the known ones.
std::vector<std::string> parseSweepMetrics(const std::vector<std::string>& texts);
// Every name parseSweepMetrics() accepts (without "path"), in column order.
std::vector<std::string> allSweepMetrics();
bool isReferenceMetric(const std::string& name);
// The columns of the metrics (the JSON keys of `score --json` and `goodness --json`).
std::vector<std::string> metricColumns(const std::vector<std::string>& metrics);
SetMeasures measuresOf(const std::vector<std::string>& metrics);
// One value per column of metricColumns(); empty where the metric is undefined for this map.
std::vector<std::optional<double>> metricValues(const std::vector<std::string>& metrics,
                                                const SetEvaluation& evaluation);
// +1 when a larger value of the column is better, -1 when a smaller one is.
int betterDirection(const std::string& column);

}  // namespace sg
