// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What the metrics panel and the comparison table show, computed by the core functions the CLI
// uses (never again here): sg::scoreAgainstReference() as `sonargrid-cli score`, and
// sg::evaluateSet() (VSDNS, derivative noise, two runs) on the grid `sonargrid-cli goodness` uses.
// Plain functions of immutable inputs, so that they run on a worker thread; the widgets own the
// threads (metrics_panel.h, comparison_table.h).

#include <QImage>
#include <QString>
#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sonargrid/data/dataset.h"
#include "sonargrid/engine/mapper.h"
#include "sonargrid/engine/occupancy_map.h"
#include "sonargrid/metrics/reference_score.h"
#include "sonargrid/reference/reference_map.h"
#include "sonargrid/sweep/set_evaluation.h"

namespace sg::ui {

// One number as the panel, the table and the JSON name it.
struct MetricInfo {
  const char* key;    // the JSON key of `score --json` or `goodness --json`
  QString label;      // e.g. "IOP"
  QString unit;       // e.g. "mm"; empty for a pure number
  int precision = 2;  // decimals shown
  QString source;     // the tooltip: what it is and which paper defines it
  bool lowerIsBetter = true;
};

// In the order of `sonargrid-cli score --json`: the 14 metrics, then cells_evaluated.
const std::vector<MetricInfo>& referenceMetricInfo();
// In the order of `sonargrid-cli goodness --json`.
const std::vector<MetricInfo>& goodnessMetricInfo();

struct MetricsInput {
  std::shared_ptr<const OccupancyMap> map;  // the map to score (the one the window shows)
  std::shared_ptr<const ReferenceMap> reference;
  // For the goodness measures, which map the run again with an observer (VSDNS): the log, the
  // second run (two-run comparison) and what the map was built with.
  std::shared_ptr<const Dataset> run, secondRun;
  MapperSettings settings;
  double cellSize = 0.05;
  bool goodness = true;     // VSDNS and derivative noise (the panel: when there is no reference)
  bool dminOverlay = true;  // the D_min tint of the map (needs a reference)
  ScoreOptions score;       // metrics, pairs, seed and cell mask: the CLI's defaults
};

struct MetricsResult {
  std::optional<ReferenceScore> score;
  QString scoreError;  // why there is no score although a reference was given
  std::optional<SetEvaluation> goodness;
  QString goodnessError;
  std::shared_ptr<const QImage> dminTint;  // one pixel per cell of `spec`
  GridSpec spec;
  double elapsedMs = 0.0;

  // Every number by its JSON key, in the CLI's order: score --json's keys when scored, then
  // goodness --json's when computed. Empty value: undefined (null in JSON).
  struct Value {
    std::string key;
    std::optional<double> value;
    bool integer = false;  // a count (cells_evaluated, two-run counts)
  };
  std::vector<Value> values() const;
  std::optional<double> value(const std::string& key) const;
};

// Empty when `cancel` was raised before it finished. Errors of the core (no reference edge on the
// grid, a truth pose the log lacks) are reported in the result, never thrown.
std::optional<MetricsResult> computeMetrics(const MetricsInput& input,
                                            const std::atomic<bool>* cancel = nullptr);

// The grid `sonargrid-cli goodness` maps a log on: its fitting grid at `cellSize`, or, with a
// second run, one grid covering both (so that the runs' cells line up).
GridSpec goodnessGrid(const Dataset& run, const Dataset* secondRun, PoseSource pose,
                      double cellSize);

// The result as one JSON object, with the keys and value types of `score --json` (and
// `goodness --json`), e.g. {"iop_mm":86.2,...,"cells_evaluated":5210}.
std::string metricsJson(const MetricsResult& result);

// A value as the panel prints it ("—" when undefined).
QString formatValue(const std::optional<double>& value, int precision);

}  // namespace sg::ui
