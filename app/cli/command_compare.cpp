// SPDX-License-Identifier: GPL-3.0-or-later
// `sonargrid-cli compare`: the papers' side-by-side tables as one command (docs/cli.md). Several
// model/rule configurations map the same logs; every reference metric is reported per
// configuration as the mean and standard deviation over the logs (paper 000, Table 1), by default
// on the cells that every configuration observed (issue 16: HPF reaches 10 m where Konolige stops
// at 2.5 m, so scoring each on its own cells compares different things).

#include <algorithm>
#include <atomic>
#include <functional>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "commands.h"
#include "map_options.h"
#include "reproduce/reproduce.h"
#include "score_flags.h"
#include "sonargrid/base/atomic_file.h"
#include "sonargrid/base/concurrency.h"
#include "sonargrid/forward/forward_em.h"
#include "sonargrid/reference/read_reference.h"
#include "thread_flags.h"

namespace sg::cli {
namespace {

using Json = nlohmann::ordered_json;

struct Config {
  std::string text;  // as given: "konolige/log:k=0.5"
  MapperSettings settings;
};

// "model/rule[:name=value,...]" with the model's and rule's defaults under the overrides.
Config parseConfig(const std::string& text, PoseSource pose) {
  const std::string flag = "--config '" + text + "': ";
  const std::size_t colon = text.find(':');
  const std::string pair = text.substr(0, colon);
  const std::size_t slash = pair.find('/');
  if (slash == std::string::npos || slash == 0 || slash + 1 == pair.size())
    throw UsageError(flag + "expected MODEL/RULE[:NAME=VALUE,...]");
  Config c;
  c.text = text;
  c.settings.pose = pose;
  c.settings.model = pair.substr(0, slash);
  c.settings.rule = pair.substr(slash + 1);
  if (c.settings.model == forward::kModelName) {
    // The forward model's map is learned by EM, its own rule (docs/forward-model.md).
    if (c.settings.rule != forward::kRuleName) {
      throw UsageError(flag + "the forward model learns its map by EM: write " +
                       forward::kModelName + "/" + forward::kRuleName);
    }
    c.settings.parameters = forward::defaultForwardParameters();
  } else if (!makeSensorModel(c.settings.model)) {
    std::string names;
    for (const std::string& n : sensorModelNames()) names += (names.empty() ? "" : ", ") + n;
    throw UsageError(flag + "unknown model '" + c.settings.model + "'; choose one of " + names +
                     ", " + forward::kModelName);
  }
  if (c.settings.model != forward::kModelName) {
    if (!makeUpdateRule(c.settings.rule)) {
      std::string names;
      for (const std::string& n : updateRuleNames()) names += (names.empty() ? "" : ", ") + n;
      throw UsageError(flag + "unknown rule '" + c.settings.rule + "'; choose one of " + names);
    }
    const Compatibility compatible = compatibility(c.settings.model, c.settings.rule);
    if (!compatible.allowed) throw UsageError(flag + compatible.reason);
    c.settings.parameters = defaultParameters(c.settings.model, c.settings.rule);
  }
  if (colon == std::string::npos) return c;
  std::vector<std::string> seen;
  std::stringstream list(text.substr(colon + 1));
  std::string kv;
  while (std::getline(list, kv, ',')) {
    const std::size_t eq = kv.find('=');
    if (eq == std::string::npos || eq == 0)
      throw UsageError(flag + "expected NAME=VALUE, got '" + kv + "'");
    const std::string name = kv.substr(0, eq);
    if (std::find(seen.begin(), seen.end(), name) != seen.end())
      throw UsageError(flag + name + " is given twice");
    seen.push_back(name);
    try {
      c.settings.parameters.set(name, parseNumber(kv.substr(eq + 1), "--config " + name));
    } catch (const ParameterError& e) {
      throw UsageError(flag + e.what());
    }
  }
  if (seen.empty() || text.back() == ',') throw UsageError(flag + "nothing after ':'");
  return c;
}

}  // namespace

// One grid holding every map's grid (the mapper grows a grid when a model reaches past it); grids
// of one cell size are snapped to its multiples, so the union lines up with each of them. Also
// used by `reproduce osullivan` (reproduce.h).
GridSpec unionOf(const std::vector<OccupancyMap>& maps) {
  Position lo = maps.front().spec.origin, hi = lo;
  for (const OccupancyMap& m : maps) {
    lo = lo.cwiseMin(m.spec.origin);
    hi = hi.cwiseMax(m.spec.origin + Position(m.spec.widthMetres(), m.spec.heightMetres()));
  }
  const double cell = maps.front().spec.cellSize;
  // Half a cell inside both corners: the corners are cell multiples, and a rounding of either
  // must not add a row or a column.
  const Position half(cell / 2, cell / 2);
  return GridSpec::covering(lo + half, hi - half, cell, 0.0);
}

namespace {

// Runs job(0) ... job(count − 1) on the thread policy's threads; each job writes only its own
// slot, so results do not depend on the number of threads.
void forEachParallel(std::size_t count, const std::function<void(std::size_t)>& job) {
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  runParallel(
      static_cast<unsigned>(std::clamp<std::size_t>(count, 1, parallelThreads())),
      [&](unsigned) {
        while (!stop.load(std::memory_order_relaxed)) {
          const std::size_t i = next.fetch_add(1, std::memory_order_relaxed);
          if (i >= count) return;
          job(i);
        }
      },
      [&] { stop.store(true); });
}

struct Row {
  Config config;
  std::size_t cellsScored = 0;                             // summed over the logs
  std::vector<std::size_t> cellsPerLog;                    // per log
  std::vector<std::vector<std::optional<double>>> values;  // [metric format][log]
};

std::string paramsText(const ParameterSet& p) {
  std::string out;
  for (const auto& [name, value] : p.values())
    out += (out.empty() ? "" : ";") + name + "=" + reproduce::exact(value);
  return out;
}

std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char ch : s) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return q + "\"";
}

}  // namespace

int runCompare(Arguments& args) {
  const std::vector<std::string> logs = args.values("--log");
  const std::string referencePath = args.required("--reference");
  const std::vector<std::string> configTexts = args.values("--config");
  const std::string cells = args.value("--cells").value_or("common");
  if (cells != "common" && cells != "own")
    throw UsageError("--cells takes common or own, got '" + cells + "'");
  const std::string pose = args.value("--pose").value_or("odom");
  if (pose != "odom" && pose != "truth")
    throw UsageError("--pose takes odom or truth, got '" + pose + "'");
  MapOptions base;
  base.settings.pose = pose == "truth" ? PoseSource::Truth : PoseSource::Odometry;
  base.cell = args.number("--cell", 0.05, 0.001, 10.0);
  base.read = parseLogOptions(args);
  applyThreadOptions(args);
  const ScoreOptions scoreOptions = parseScoreOptions(args);
  const auto csvPath = args.value("--csv");
  const auto markdownPath = args.value("--markdown");
  const bool json = args.flag("--json");
  args.finish();
  if (logs.empty()) throw UsageError("compare needs at least one --log FILE");
  if (configTexts.empty()) throw UsageError("compare needs at least one --config MODEL/RULE");
  std::vector<Config> configs;
  for (const std::string& t : configTexts) {
    for (const Config& c : configs) {
      if (c.text == t) throw UsageError("--config '" + t + "' is given twice");
    }
    configs.push_back(parseConfig(t, base.settings.pose));
  }

  ReferenceMap reference;
  try {
    reference = readReference(referencePath);
  } catch (const LogError& e) {
    throw InputError(e.what());
  }

  std::vector<Row> rows(configs.size());
  for (std::size_t c = 0; c < configs.size(); ++c) {
    rows[c].config = configs[c];
    rows[c].values.assign(metricFormats().size(), {});
  }
  for (const std::string& logPath : logs) {
    const Dataset data = loadLog(logPath, base.read);
    // Every configuration on the log's fitting grid, so that their cells line up.
    std::vector<OccupancyMap> maps(configs.size());
    const GridSpec fitting = fittingGridOf(data, base, logPath);
    auto mapConfig = [&](std::size_t c, const GridSpec& grid) {
      MapOptions o = base;
      o.log = logPath;
      o.settings = configs[c].settings;
      o.progress = false;  // configurations map at once: their EM lines would interleave
      maps[c] = buildMap(data, o, logPath, grid).map;
    };
    forEachParallel(configs.size(), [&](std::size_t c) { mapConfig(c, fitting); });
    if (std::any_of(maps.begin(), maps.end(),
                    [&](const OccupancyMap& m) { return !(m.spec == maps.front().spec); })) {
      const GridSpec all = unionOf(maps);
      std::vector<std::size_t> again;
      for (std::size_t c = 0; c < maps.size(); ++c)
        if (!(maps[c].spec == all)) again.push_back(c);
      forEachParallel(again.size(), [&](std::size_t k) { mapConfig(again[k], all); });
    }

    ScoreOptions options = scoreOptions;
    if (cells == "common") {
      std::vector<const OccupancyMap*> pointers;
      for (const OccupancyMap& m : maps) pointers.push_back(&m);
      options.cellMask = commonObservedCells(pointers);
    }
    std::vector<ReferenceScore> scores(configs.size());
    forEachParallel(configs.size(), [&](std::size_t c) {
      try {
        scores[c] = scoreAgainstReference(maps[c], reference, options);
      } catch (const MetricsError& e) {
        throw InputError(referencePath + ": " + e.what());
      }
    });
    for (std::size_t c = 0; c < configs.size(); ++c) {
      for (const std::string& w : scores[c].warnings) {
        std::cerr << "sonargrid-cli: warning: " << logPath << ", " << configs[c].text << ": " << w
                  << '\n';
      }
      rows[c].cellsScored += scores[c].cellsEvaluated;
      rows[c].cellsPerLog.push_back(scores[c].cellsEvaluated);
      for (std::size_t k = 0; k < metricFormats().size(); ++k)
        rows[c].values[k].push_back(scores[c].value(metricFormats()[k].metric));
    }
  }

  // The table: one row per configuration, each metric as mean ± sd over the logs.
  reproduce::Table table{{"config", "cells scored"}, {}};
  std::vector<std::size_t> shown;
  for (std::size_t k = 0; k < metricFormats().size(); ++k) {
    if (scoreOptions.metrics.count(metricFormats()[k].metric) == 0) continue;
    shown.push_back(k);
    const MetricFormat& f = metricFormats()[k];
    table.header.push_back(std::string(f.label) +
                           (f.unit[0] != '\0' ? std::string(" (") + (f.unit + 1) + ")" : ""));
  }
  std::string csv = "config,params,cells_scored";
  for (std::size_t k : shown) {
    const std::string key = metricJsonKey(metricFormats()[k].metric);
    csv += "," + key + "_mean," + key + "_sd";
  }
  csv += '\n';
  Json jsonRows = Json::array();
  for (const Row& r : rows) {
    std::vector<std::string> line{r.config.text, std::to_string(r.cellsScored)};
    csv += csvField(r.config.text) + "," + csvField(paramsText(r.config.settings.parameters)) +
           "," + std::to_string(r.cellsScored);
    Json params = Json::object();
    for (const auto& [name, value] : r.config.settings.parameters.values()) params[name] = value;
    Json metrics = Json::object();
    for (std::size_t k : shown) {
      const MetricFormat& f = metricFormats()[k];
      const reproduce::MeanSd m = reproduce::meanSd(r.values[k]);
      std::string cell = reproduce::fixed(m.mean, f.precision);
      if (m.sd) cell += " ± " + reproduce::fixed(m.sd, f.precision);
      line.push_back(cell);
      csv += "," + reproduce::exact(m.mean) + "," + reproduce::exact(m.sd);
      metrics[metricJsonKey(f.metric)] =
          Json{{"mean", reproduce::orNull(m.mean)}, {"sd", reproduce::orNull(m.sd)}, {"n", m.n}};
    }
    csv += '\n';
    table.rows.push_back(line);
    jsonRows.push_back(Json{{"config", r.config.text},
                            {"model", r.config.settings.model},
                            {"rule", r.config.settings.rule},
                            {"params", params},
                            {"cells_scored", r.cellsScored},
                            {"cells_scored_per_log", r.cellsPerLog},
                            {"metrics", metrics}});
  }
  std::ostringstream intro;
  intro << "Against `" << referencePath << "`, " << logs.size()
        << (logs.size() == 1 ? " log" : " logs") << ", " << base.cell << " m cells, "
        << (cells == "common" ? "on the cells every configuration observed"
                              : "each configuration on the cells it observed")
        << "; IOP weight " << iopWeightName(scoreOptions.iop.weight)
        << ". Each value is the mean ± the standard deviation over the logs.\n\n";
  const std::string markdown = intro.str() + table.markdown();
  // A FileWriteError (naming the path) is exit 1, as for every output of the CLI.
  if (csvPath) writeFileAtomically(*csvPath, csv);
  if (markdownPath) writeFileAtomically(*markdownPath, markdown);
  if (json) {
    Json out{{"cells", cells},
             {"iop_weight", iopWeightName(scoreOptions.iop.weight)},
             {"logs", logs},
             {"reference", referencePath},
             {"rows", jsonRows}};
    std::cout << out.dump() << '\n';
  } else {
    std::cout << markdown;
  }
  return 0;
}

}  // namespace sg::cli
