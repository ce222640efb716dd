// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// `sonargrid-cli reproduce`: the experiments of the three papers rerun on the bundled datasets
// (docs/reproduction.md). One file per paper; this header holds what they share.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "sonargrid/data/dataset.h"
#include "sonargrid/engine/mapper.h"
#include "sonargrid/engine/occupancy_map.h"
#include "sonargrid/metrics/reference_score.h"
#include "sonargrid/reference/reference_map.h"

namespace sg::cli {
// The grid holding every one of `maps`' grids (all of one cell size), as `compare` maps its
// configurations on when the mapper grew their grids differently (command_compare.cpp).
GridSpec unionOf(const std::vector<OccupancyMap>& maps);
}  // namespace sg::cli

namespace sg::cli::reproduce {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

struct Context {
  fs::path datasets;  // the folder holding raschke-multi/, arafat-room/, ...
  fs::path out;       // DIR/<paper> is written
  bool progress = false;
  std::size_t sets = 0;  // arafat sweep: 0 = all 1440, else that many spread evenly over the grid
};

// Each writes its files into ctx.out / <paper> and returns its part of the summary JSON.
Json runRaschke1990(const Context& ctx);
Json runOSullivan(const Context& ctx);
Json runArafat(const Context& ctx);
// Not one of the three papers: the forward model learned by EM (Thrun 2003) against every inverse
// model with its paper's rule (docs/forward-model.md, "Comparison").
Json runThrun2003(const Context& ctx);

// ---- shared by the three (and `bench`)

// Where the bundled datasets are when --datasets is not given: the source tree's (a build run from
// its tree), then the installed copy. InputError when neither exists.
fs::path defaultDatasets();

// Simulates `folders` (raschke-multi, raschke-single, arafat-room) as datasets/generate.sh does,
// under the physics `preset`, from the world.json and route.txt of source/<folder>, into
// out/<folder>/ (with a copy of world.json). InputError naming a missing or malformed file.
void simulateDatasets(const fs::path& source, const fs::path& out, const std::string& preset,
                      const std::vector<std::string>& folders);

// InputError naming the file when it is missing or malformed.
Dataset loadDataset(const fs::path& path);
ReferenceMap loadReferenceMap(const fs::path& path);

// One grid of `cell` holding every log's fitting grid and every reference corner, grown by 0.5 m,
// so that maps of several runs line up cell for cell and the whole reference is drawn.
GridSpec experimentGrid(const std::vector<const Dataset*>& logs, const ReferenceMap& reference,
                        double cell, PoseSource pose);

// The model's and rule's defaults, then `overrides`; a cone model's aperture (`omega`) follows
// the ring's unless overridden, since the papers map with their own transducers' cone.
MapperSettings settingsFor(const std::string& model, const std::string& rule, const SonarRing& ring,
                           const std::vector<std::pair<std::string, double>>& overrides);

// Maps the whole log (InputError naming `path` on a mapper error).
OccupancyMap mapLog(const Dataset& data, const fs::path& path, const GridSpec& grid,
                    const MapperSettings& settings, FootprintObserver* observer = nullptr);

// One run's maps of several configurations, compared as `sonargrid-cli compare` compares them:
// each mapped on `grid` by mapConfig(c, grid), again on their union where a mapper grew one
// (unionOf), and each scored against `reference` on the cells that all of them observed
// (commonObservedCells, compare's default `--cells common`). InputError naming `referencePath`
// when the reference has nothing on the grid.
// A metric a table reports: its key in the JSON and CSV, and its column title.
struct Benchmark {
  Metric metric;
  const char* key;
  const char* title;
};

struct CommonScores {
  std::vector<OccupancyMap> maps;
  std::vector<ReferenceScore> scores;
};
CommonScores scoreOnCommonCells(
    std::size_t configs, const GridSpec& grid,
    const std::function<OccupancyMap(std::size_t c, const GridSpec& on)>& mapConfig,
    const ReferenceMap& reference, const ScoreOptions& options, const fs::path& referencePath);

// The map as a PNG (4 pixels per cell, legend) with the reference's edges drawn over it in black.
void writeMapWithReference(const OccupancyMap& map, const ReferenceMap& reference,
                           const fs::path& path, const std::vector<Position>& markers = {});

// Creates ctx.out / name (and parents); std::runtime_error naming it on failure.
fs::path paperDirectory(const Context& ctx, const std::string& name);
// Writes `text` to `path` atomically (base/atomic_file.h); FileWriteError naming the path on
// failure.
void writeText(const fs::path& path, const std::string& text);

// Tables written twice: Markdown for reading, CSV for scripts.
struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::string markdown() const;
  std::string csv() const;
};

// Shortest text that reads back to the same double (CSV); "" for an empty optional.
std::string exact(const std::optional<double>& v);
// Fixed decimals for Markdown; "—" for an empty optional.
std::string fixed(const std::optional<double>& v, int decimals);
Json orNull(const std::optional<double>& v);

// Mean and sample standard deviation (n − 1) of the defined values; sd empty below two values.
struct MeanSd {
  std::optional<double> mean, sd;
  std::size_t n = 0;
};
MeanSd meanSd(const std::vector<std::optional<double>>& values);

// "name (done/total)" on stderr when ctx.progress.
void reportProgress(const Context& ctx, const std::string& what, std::size_t done,
                    std::size_t total);

}  // namespace sg::cli::reproduce
