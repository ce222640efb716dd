// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Every metric of a built map against a reference, computed together so that the APG, the distance
// transform and the ideal map are built once. What `sonargrid-cli score` prints and the GUI's
// metrics view shows (docs/metrics.md).

#include <cstdint>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "sonargrid/metrics/ideal_map.h"
#include "sonargrid/metrics/index_of_performance.h"
#include "sonargrid/metrics/map_agreement.h"
#include "sonargrid/metrics/occupancy_classification.h"
#include "sonargrid/metrics/path_comparison.h"
#include "sonargrid/occupancy_map.h"
#include "sonargrid/reference/reference_map.h"

namespace sg {

// Each metric by the stem of its JSON key (iop for iop_mm, correlation for correlation_pct...).
enum class Metric {
  Iop,
  Correlation,
  MapScore,
  MapScoreOccupied,
  Match,
  PathFalsePositive,
  PathFalseNegative,
  CrossEntropy,
  Brier,
  Auc,
  Precision,
  Recall,
  F1,
  Iou,
};

const std::vector<Metric>& allMetrics();
const char* metricName(Metric m);  // "iop", "correlation", ..., "path_false_positive"
// A comma-separated list of names; "path" stands for both path metrics. Throws
// std::invalid_argument naming an unknown or empty name and listing the known ones.
std::set<Metric> parseMetricList(const std::string& list);

class MetricsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ScoreOptions {
  std::set<Metric> metrics{allMetrics().begin(), allMetrics().end()};
  int pairs = kDefaultPathPairs;
  std::uint64_t seed = kDefaultPathSeed;
  // The cells to score, row-major like the map's GridSpec (non-zero: scored); empty: every cell.
  // A cell outside the mask counts as never observed and not filled: it leaves IOP, every
  // agreement and classification metric and the path endpoints, and the path planner treats it as
  // unknown (passable). How several maps are compared on the cells all of them observed (the GUI's
  // comparison table; docs/metrics.md, "Scoring on a set of cells").
  std::vector<std::uint8_t> cellMask;
};

struct ReferenceScore {
  std::set<Metric> computed;
  std::size_t apgCells = 0;
  std::size_t cellsEvaluated = 0;
  std::size_t idealFree = 0, idealOccupied = 0, idealUnknown = 0;
  IndexOfPerformance iop;
  MapAgreement agreement;
  OccupancyClassification classification;
  PathComparison paths;

  // The value of one metric; empty when it is undefined for this map (e.g. IOP of a map with no
  // filled cell) or was not computed.
  std::optional<double> value(Metric m) const;
};

// Throws MetricsError when no reference edge or obstacle touches the map's grid (nothing to score
// against), std::invalid_argument for a map whose layers (or options.cellMask, when given) do not
// match its grid.
ReferenceScore scoreAgainstReference(const OccupancyMap& map, const ReferenceMap& reference,
                                     const ScoreOptions& options = {});

}  // namespace sg
