// SPDX-License-Identifier: GPL-3.0-or-later
#include "sweep_report.h"

#include <algorithm>
#include <limits>

#include "sonargrid/sweep/optimal_sets.h"
#include "sonargrid/sweep/sweep_metrics.h"

namespace sg::cli {
namespace {

using Json = nlohmann::ordered_json;

// The rows' parameter sets as ParameterSets (names from the CSV, no range: the values were
// checked when the sweep was made).
std::vector<ParameterSet> setsOf(const SweepHeader& header, const std::vector<SweepCsvRow>& rows) {
  std::vector<ParameterSpec> specs;
  for (const std::string& name : header.parameters) {
    ParameterSpec s;
    s.name = name;
    s.min = std::numeric_limits<double>::lowest();
    s.max = std::numeric_limits<double>::max();
    specs.push_back(s);
  }
  std::vector<ParameterSet> sets;
  for (const SweepCsvRow& r : rows) {
    ParameterSet p(specs);
    for (std::size_t i = 0; i < specs.size(); ++i) p.set(specs[i].name, r.parameters[i]);
    sets.push_back(std::move(p));
  }
  return sets;
}

Json paramsJson(const SweepHeader& header, const ParameterSet& p) {
  Json j = Json::object();
  for (const std::string& name : header.parameters) j[name] = p.get(name);
  return j;
}

std::size_t columnOf(const SweepHeader& header, const std::string& column) {
  return static_cast<std::size_t>(std::find(header.columns.begin(), header.columns.end(), column) -
                                  header.columns.begin());
}

Json indicesJson(const std::vector<SweepCsvRow>& rows, const std::vector<std::size_t>& members) {
  Json j = Json::array();
  for (std::size_t m : members) j.push_back(rows[m].index);
  return j;
}

}  // namespace

int betterDirection(const std::string& column) {
  return sg::betterDirection(column);
}

Json sweepReport(const SweepHeader& header, const std::vector<SweepCsvRow>& rows) {
  Json out;
  out["sets"] = header.sets;
  out["shard"] = std::to_string(header.shardIndex) + "/" + std::to_string(header.shardCount);
  out["rows"] = rows.size();
  out["metrics"] = header.metrics;
  const std::vector<ParameterSet> sets = setsOf(header, rows);

  if (std::find(header.metrics.begin(), header.metrics.end(), "vsdns") != header.metrics.end()) {
    const std::size_t c = columnOf(header, "vsdns");
    std::vector<std::optional<double>> vsdns;
    for (const SweepCsvRow& r : rows) vsdns.push_back(r.values[c]);
    if (std::any_of(vsdns.begin(), vsdns.end(), [](const auto& v) { return v.has_value(); })) {
      const Histogram h = histogramOf(vsdns);
      Json edges = Json::array();
      for (int k = 0; k < static_cast<int>(h.counts.size()); ++k) edges.push_back(h.lowerEdge(k));
      edges.push_back(h.max);
      const OptimalSet bin = lowestBinAverage(vsdns, sets);
      const OptimalSet min = minimumVsdns(vsdns, sets);
      const OptimalSet mean = nearestMeanVsdns(vsdns, sets);
      Json rules;
      rules["histogram"] = {
          {"bins", kPaper002HistogramBins}, {"edges", edges}, {"counts", h.counts}};
      rules["optimal_histogram"] = {{"params", paramsJson(header, bin.parameters)},
                                    {"sets", bin.members.size()},
                                    {"indices", indicesJson(rows, bin.members)},
                                    {"max_vsdns_in_bin", bin.criterion}};
      rules["optimal_min"] = {{"index", rows[min.members.front()].index},
                              {"params", paramsJson(header, min.parameters)},
                              {"vsdns", min.criterion}};
      rules["optimal_mean"] = {{"index", rows[mean.members.front()].index},
                               {"params", paramsJson(header, mean.parameters)},
                               {"mean_vsdns", mean.criterion},
                               {"vsdns", *vsdns[mean.members.front()]}};
      out["paper002"] = rules;
    } else {
      out["paper002"] = nullptr;  // no set had a defined VSDNS
    }
  }

  Json best = Json::object();
  for (const std::string& metric : header.metrics) {
    // The column that ranks the metric: its first; two runs rank by agree − differ, ties to the
    // fewer differing cells (paper 002 §5, as optimal_sets.h reads it).
    const std::vector<std::string> own = metricColumns({metric});
    const std::size_t c = columnOf(header, own.front());
    std::optional<std::size_t> at;
    auto key = [&](const SweepCsvRow& r) -> std::optional<std::pair<double, double>> {
      if (metric == "two-run") {
        if (!r.values[c] || !r.values[c + 1]) return std::nullopt;
        return std::make_pair(*r.values[c] - *r.values[c + 1], -*r.values[c + 1]);
      }
      if (!r.values[c]) return std::nullopt;
      return std::make_pair(betterDirection(own.front()) * *r.values[c], 0.0);
    };
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const auto k = key(rows[i]);
      if (k && (!at || *k > *key(rows[*at]))) at = i;
    }
    if (!at) {
      best[metric] = nullptr;
      continue;
    }
    Json entry;
    entry["index"] = rows[*at].index;
    for (std::size_t k = 0; k < own.size(); ++k) {
      const std::optional<double>& v = rows[*at].values[c + k];
      entry[own[k]] = v ? Json(*v) : Json(nullptr);
    }
    entry["params"] = paramsJson(header, sets[*at]);
    best[metric] = entry;
  }
  out["best"] = best;
  return out;
}

}  // namespace sg::cli
