// SPDX-License-Identifier: GPL-3.0-or-later
// The forward model learned by EM (Thrun 2003; docs/forward-model.md) against every inverse model
// with its paper's rule, on the bundled datasets: the benchmarks that show what cell independence
// costs (IOP and correlation for the walls, path false positives for walls left open, path false
// negatives for doorways closed), each configuration scored on the cells all of them observed, as
// `sonargrid-cli compare --cells common` scores them.

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "arguments.h"
#include "reproduce/reproduce.h"
#include "sonargrid/engine/sensor_model.h"
#include "sonargrid/forward/forward_em.h"

namespace sg::cli::reproduce {
namespace {

constexpr double kCell = 0.05;

struct Source {
  const char* folder;
  std::vector<const char*> runs;
};
// The runs mapped: a room with furniture and an L-shaped test course, two runs of each.
const Source kSources[] = {
    {"arafat-room", {"run-1.sglog", "run-2.sglog"}},
    {"raschke-multi", {"in-motion-01.sglog", "in-motion-02.sglog"}},
};

constexpr Benchmark kBenchmarks[] = {
    {Metric::Iop, "iop_mm", "IOP (mm)"},
    {Metric::Correlation, "correlation_pct", "correlation (%)"},
    {Metric::PathFalsePositive, "path_false_positive_pct", "path false positives (%)"},
    {Metric::PathFalseNegative, "path_false_negative_pct", "path false negatives (%)"},
};

struct Config {
  std::string model, rule;
  std::string id() const { return model + "/" + rule; }
};

std::vector<Config> configs() {
  std::vector<Config> out;
  for (const std::string& m : sensorModelNames())
    out.push_back({m, sensorModelInfo(m).preferredRule});
  out.push_back({forward::kModelName, forward::kRuleName});
  return out;
}

const char* poseName(PoseSource p) {
  return p == PoseSource::Truth ? "truth" : "odometry";
}

}  // namespace

Json runThrun2003(const Context& ctx) {
  const fs::path dir = paperDirectory(ctx, "thrun2003");
  const std::vector<Config> list = configs();
  ScoreOptions options;
  options.metrics.clear();
  for (const Benchmark& b : kBenchmarks) options.metrics.insert(b.metric);

  Table table{{"dataset", "poses", "model / rule"}, {}};
  Table perRun{{"dataset", "run", "poses", "model", "rule"}, {}};
  for (const Benchmark& b : kBenchmarks) {
    table.header.push_back(b.title);
    perRun.header.push_back(b.key);
  }
  Json summary = Json::object();
  std::size_t done = 0;
  const std::size_t total = 2 * (std::size(kSources[0].runs) + std::size(kSources[1].runs));
  for (const Source& source : kSources) {
    const fs::path folder = ctx.datasets / source.folder;
    const ReferenceMap reference = loadReferenceMap(folder / "world.json");
    std::vector<Dataset> logs;
    for (const char* run : source.runs) logs.push_back(loadDataset(folder / run));
    for (const PoseSource pose : {PoseSource::Odometry, PoseSource::Truth}) {
      std::vector<const Dataset*> pointers;
      for (const Dataset& d : logs) pointers.push_back(&d);
      const GridSpec grid = experimentGrid(pointers, reference, kCell, pose);
      // Per configuration, per benchmark, the value of each run.
      std::map<std::string, std::vector<std::vector<std::optional<double>>>> values;
      for (std::size_t r = 0; r < logs.size(); ++r) {
        const fs::path path = folder / source.runs[r];
        const CommonScores run = scoreOnCommonCells(
            list.size(), grid,
            [&](std::size_t c, const GridSpec& on) {
              MapperSettings settings = settingsFor(list[c].model, list[c].rule, logs[r].ring, {});
              settings.pose = pose;
              return mapLog(logs[r], path, on, settings);
            },
            reference, options, folder / "world.json");
        const std::vector<OccupancyMap>& maps = run.maps;
        for (std::size_t c = 0; c < list.size(); ++c) {
          const ReferenceScore& score = run.scores[c];
          auto& perBenchmark = values[list[c].id()];
          perBenchmark.resize(std::size(kBenchmarks));
          std::vector<std::string> row{source.folder, source.runs[r], poseName(pose), list[c].model,
                                       list[c].rule};
          for (std::size_t k = 0; k < std::size(kBenchmarks); ++k) {
            perBenchmark[k].push_back(score.value(kBenchmarks[k].metric));
            row.push_back(exact(score.value(kBenchmarks[k].metric)));
          }
          perRun.rows.push_back(row);
          if (r == 0) {
            writeMapWithReference(maps[c], reference,
                                  dir / (std::string(source.folder) + "-" + poseName(pose) + "-" +
                                         list[c].model + ".png"));
          }
        }
        reportProgress(ctx, "thrun2003 maps", ++done, total);
      }
      for (const Config& c : list) {
        std::vector<std::string> row{source.folder, poseName(pose), c.id()};
        Json entry = Json::object();
        for (std::size_t k = 0; k < std::size(kBenchmarks); ++k) {
          const MeanSd m = meanSd(values.at(c.id())[k]);
          row.push_back(fixed(m.mean, k == 0 ? 1 : 2));
          entry[kBenchmarks[k].key] = orNull(m.mean);
        }
        table.rows.push_back(row);
        summary[source.folder][poseName(pose)][c.id()] = entry;
      }
    }
  }
  const std::string intro =
      "Every inverse model with its paper's rule and the forward model learned by EM "
      "(`forward-em`), all at their defaults (a cone's aperture that of the robot's "
      "transducers), on 5 cm cells, scored against each dataset's `world.json` on the cells that "
      "every configuration observed (as `sonargrid-cli compare --cells common`); each value the "
      "mean over the two runs (per run: `runs.csv`). IOP and path false positives and negatives: "
      "lower is better; correlation: higher is better.\n\n";
  writeText(
      dir / "comparison.md",
      "# The forward model (Thrun 2003) against the inverse models\n\n" + intro + table.markdown());
  writeText(dir / "comparison.csv", table.csv());
  writeText(dir / "runs.csv", perRun.csv());
  return summary;
}

}  // namespace sg::cli::reproduce
