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

#include "sonargrid/engine/occupancy_map.h"
#include "sonargrid/metrics/ideal_map.h"
#include "sonargrid/metrics/index_of_performance.h"
#include "sonargrid/metrics/map_agreement.h"
#include "sonargrid/metrics/occupancy_classification.h"
#include "sonargrid/metrics/path_comparison.h"
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
// The metric's key in `sonargrid-cli score --json` and the GUI's metrics JSON (docs/cli.md):
// "iop_mm", "correlation_pct", ..., "iou". A contract: never rename one.
const char* metricJsonKey(Metric m);
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
  // The cells to score, row-major on the map's grid (1 scored, 0 left out); empty: every cell.
  // A cell left out counts as one the map never observed, in every metric: it is not evaluated,
  // not filled for the IOP, and passable and never an end point for the path comparison. Used to
  // score several maps on the same cells (commonObservedCells, docs/metrics.md).
  std::vector<std::uint8_t> cellMask;
  IopOptions iop;  // the IOP's weight and filled threshold
};

// The cells that every one of `maps` observed (1) or not (0), row-major. Throws
// std::invalid_argument when `maps` is empty, holds a null pointer, or the maps are not all on the
// same grid.
std::vector<std::uint8_t> commonObservedCells(const std::vector<const OccupancyMap*>& maps);
// The same on the grid of maps[on], for maps that may lie on different grids (e.g. of other cell
// sizes): a cell counts when maps[on] observed it and every other map observed the cell that
// holds its centre (one outside another map's grid does not count). Throws std::invalid_argument
// when `maps` is empty, `on` is not an index of it, a map is null, or a map's observed layer does
// not match its grid.
std::vector<std::uint8_t> commonObservedCells(const std::vector<const OccupancyMap*>& maps,
                                              std::size_t on);

// `map` with every cell outside `mask` made never observed (p 0.5, level 8, not filled, no
// evidence): what ScoreOptions::cellMask scores. An empty mask returns the map unchanged. Throws
// std::invalid_argument when the mask is not of the map's size.
OccupancyMap restrictedToCells(const OccupancyMap& map, const std::vector<std::uint8_t>& mask);

struct ReferenceScore {
  std::set<Metric> computed;
  std::size_t apgCells = 0;
  std::size_t cellsEvaluated = 0;
  std::size_t apgCellsObserved = 0;  // APG cells (reference edges) that the scored map observed
  // What the numbers cannot be trusted for, one sentence each (e.g. the map never observed any
  // reference edge: a reference of another place, or in another frame). Empty when all is well.
  std::vector<std::string> warnings;
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
