// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/metrics/reference_score.h"

#include <array>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "sonargrid/reference/actual_position_grid.h"

namespace sg {
namespace {

// Each metric's name (--metrics, metricName) and its JSON key (metricJsonKey): the keys of
// `sonargrid-cli score --json` and of the GUI's metrics JSON, a contract (docs/cli.md).
struct MetricNames {
  Metric metric;
  const char* name;
  const char* jsonKey;
};
constexpr std::array<MetricNames, 14> kNames{{
    {Metric::Iop, "iop", "iop_mm"},
    {Metric::Correlation, "correlation", "correlation_pct"},
    {Metric::MapScore, "map_score", "map_score_pct"},
    {Metric::MapScoreOccupied, "map_score_occupied", "map_score_occupied_pct"},
    {Metric::Match, "match", "match_bits"},
    {Metric::PathFalsePositive, "path_false_positive", "path_false_positive_pct"},
    {Metric::PathFalseNegative, "path_false_negative", "path_false_negative_pct"},
    {Metric::CrossEntropy, "cross_entropy", "cross_entropy"},
    {Metric::Brier, "brier", "brier"},
    {Metric::Auc, "auc", "auc"},
    {Metric::Precision, "precision", "precision"},
    {Metric::Recall, "recall", "recall"},
    {Metric::F1, "f1", "f1"},
    {Metric::Iou, "iou", "iou"},
}};

bool wants(const std::set<Metric>& s, std::initializer_list<Metric> any) {
  for (Metric m : any) {
    if (s.count(m) != 0) return true;
  }
  return false;
}

}  // namespace

const std::vector<Metric>& allMetrics() {
  static const std::vector<Metric> all = [] {
    std::vector<Metric> v;
    for (const MetricNames& n : kNames) v.push_back(n.metric);
    return v;
  }();
  return all;
}

const char* metricName(Metric m) {
  for (const MetricNames& n : kNames) {
    if (n.metric == m) return n.name;
  }
  return "?";
}

const char* metricJsonKey(Metric m) {
  for (const MetricNames& n : kNames) {
    if (n.metric == m) return n.jsonKey;
  }
  return "?";
}

std::set<Metric> parseMetricList(const std::string& list) {
  std::set<Metric> out;
  std::size_t start = 0;
  while (start <= list.size()) {
    std::size_t comma = list.find(',', start);
    if (comma == std::string::npos) comma = list.size();
    const std::string name = list.substr(start, comma - start);
    bool known = false;
    if (name == "path") {
      out.insert(Metric::PathFalsePositive);
      out.insert(Metric::PathFalseNegative);
      known = true;
    }
    for (const MetricNames& n : kNames) {
      if (name == n.name) {
        out.insert(n.metric);
        known = true;
      }
    }
    if (!known) {
      std::string names = "path";
      for (const MetricNames& n : kNames) names += std::string(", ") + n.name;
      throw std::invalid_argument(
          (name.empty() ? std::string("an empty metric name") : "unknown metric '" + name + "'") +
          "; choose from " + names);
    }
    start = comma + 1;
  }
  return out;
}

std::optional<double> ReferenceScore::value(Metric m) const {
  if (computed.count(m) == 0) return std::nullopt;
  switch (m) {
    case Metric::Iop:
      return iop.mm;
    case Metric::Correlation:
      return agreement.correlationPct;
    case Metric::MapScore:
      return agreement.mapScorePct;
    case Metric::MapScoreOccupied:
      return agreement.mapScoreOccupiedPct;
    case Metric::Match:
      return agreement.matchBits;
    case Metric::PathFalsePositive:
      return paths.falsePositivePct;
    case Metric::PathFalseNegative:
      return paths.falseNegativePct;
    case Metric::CrossEntropy:
      return agreement.crossEntropyBits;
    case Metric::Brier:
      return agreement.brier;
    case Metric::Auc:
      return classification.auc;
    case Metric::Precision:
      return classification.precision;
    case Metric::Recall:
      return classification.recall;
    case Metric::F1:
      return classification.f1;
    case Metric::Iou:
      return classification.iou;
  }
  return std::nullopt;
}

std::vector<std::uint8_t> commonObservedCells(const std::vector<const OccupancyMap*>& maps) {
  if (maps.empty()) throw std::invalid_argument("common cells: no map given");
  for (const OccupancyMap* m : maps) {
    if (m != nullptr && !(m->spec == maps.front()->spec))
      throw std::invalid_argument("common cells: the maps are not on the same grid");
  }
  return commonObservedCells(maps, 0);
}

std::vector<std::uint8_t> commonObservedCells(const std::vector<const OccupancyMap*>& maps,
                                              std::size_t on) {
  if (maps.empty()) throw std::invalid_argument("common cells: no map given");
  if (on >= maps.size()) throw std::invalid_argument("common cells: no map of that index");
  for (const OccupancyMap* m : maps) {
    if (m == nullptr) throw std::invalid_argument("common cells: a null map");
    if (m->observed.size() != m->spec.cellCount())
      throw std::invalid_argument("common cells: a map's observed layer does not match its grid");
  }
  const OccupancyMap& own = *maps[on];
  const GridSpec& g = own.spec;
  std::vector<std::uint8_t> common(own.observed.size(), 0);
  for (std::size_t c = 0; c < common.size(); ++c) {
    if (own.observed[c] == 0) continue;
    const Position centre = g.cellCentre(g.fromLinear(c));
    bool all = true;
    for (std::size_t j = 0; j < maps.size() && all; ++j) {
      const OccupancyMap& other = *maps[j];
      if (other.spec == g) {
        all = other.observed[c] != 0;  // the same cell
      } else {
        const CellIndex k = other.spec.worldToCell(centre);
        all = other.spec.contains(k) && other.observed[other.spec.linear(k)] != 0;
      }
    }
    common[c] = all ? 1 : 0;
  }
  return common;
}

OccupancyMap restrictedToCells(const OccupancyMap& map, const std::vector<std::uint8_t>& mask) {
  if (mask.empty()) return map;
  if (mask.size() != map.spec.cellCount() || map.observed.size() != mask.size())
    throw std::invalid_argument("score: the cell mask is not of the map's size");
  OccupancyMap out = map;
  const std::uint8_t unobservedLevel = levelOfProbability(0.5);
  const bool hasEvidence = out.evidence.size() == mask.size();
  for (std::size_t i = 0; i < mask.size(); ++i) {
    if (mask[i] != 0) continue;
    out.probability[i] = 0.5;
    out.level[i] = unobservedLevel;
    out.filled[i] = 0;
    out.observed[i] = 0;
    if (hasEvidence) out.evidence[i] = 0.0;
  }
  return out;
}

ReferenceScore scoreAgainstReference(const OccupancyMap& unmasked, const ReferenceMap& reference,
                                     const ScoreOptions& options) {
  const std::size_t n = unmasked.spec.cellCount();
  if (n == 0 || unmasked.probability.size() != n || unmasked.level.size() != n ||
      unmasked.filled.size() != n || unmasked.observed.size() != n) {
    throw std::invalid_argument("score: the map's layers do not match its grid");
  }
  const OccupancyMap restricted =
      options.cellMask.empty() ? OccupancyMap{} : restrictedToCells(unmasked, options.cellMask);
  const OccupancyMap& map = options.cellMask.empty() ? unmasked : restricted;
  ReferenceScore out;
  out.computed = options.metrics;
  const ActualPositionGrid apg = ActualPositionGrid::rasterise(reference, map.spec);
  out.apgCells = apg.count();
  if (out.apgCells == 0) {
    std::ostringstream msg;
    msg << "no edge of the reference crosses the map's grid (" << map.spec.widthMetres() << " m x "
        << map.spec.heightMetres() << " m from (" << map.spec.origin.x() << ", "
        << map.spec.origin.y() << ")): are the reference and the map in the same frame and unit?";
    throw MetricsError(msg.str());
  }
  const IdealMap ideal = IdealMap::fromReference(reference, apg);
  out.idealFree = ideal.count(IdealCell::Free);
  out.idealOccupied = ideal.count(IdealCell::Occupied);
  out.idealUnknown = ideal.count(IdealCell::Unknown);
  for (std::size_t i = 0; i < n; ++i) {
    out.cellsEvaluated += evaluatedCell(map, ideal, i) ? 1 : 0;
    out.apgCellsObserved += apg.cells[i] != 0 && map.observed[i] != 0 ? 1 : 0;
  }
  if (out.apgCellsObserved == 0) {
    std::ostringstream msg;
    msg << "the map observed none of the " << out.apgCells
        << " cells on the reference's edges: is the reference of this place, in the map's frame?";
    out.warnings.push_back(msg.str());
  }

  const std::set<Metric>& m = options.metrics;
  if (wants(m, {Metric::Iop})) out.iop = indexOfPerformance(map, apg, options.iop);
  if (wants(m, {Metric::Correlation, Metric::MapScore, Metric::MapScoreOccupied, Metric::Match,
                Metric::CrossEntropy, Metric::Brier})) {
    out.agreement = mapAgreement(map, ideal);
  }
  if (wants(m, {Metric::Auc, Metric::Precision, Metric::Recall, Metric::F1, Metric::Iou})) {
    out.classification = classifyOccupancy(map, ideal);
  }
  if (wants(m, {Metric::PathFalsePositive, Metric::PathFalseNegative})) {
    out.paths = comparePaths(map, ideal, options.pairs, options.seed);
  }
  return out;
}

}  // namespace sg
