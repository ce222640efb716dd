// SPDX-License-Identifier: GPL-3.0-or-later
// `sonargrid-cli reproduce raschke1990|osullivan|arafat --out DIR`: reruns a paper's experiment on
// the bundled datasets and on the same runs simulated under each physics preset (docs/cli.md,
// docs/reproduction.md) and writes its tables and figures.
// This file parses the arguments and holds what the three experiments share.

#include <unistd.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "commands.h"
#include "map_options.h"
#include "reproduce/reproduce.h"
#include "sonargrid/base/atomic_file.h"
#include "sonargrid/export/map_export.h"
#include "sonargrid/forward/forward_em.h"
#include "sonargrid/reference/read_reference.h"
#include "sonargrid/sim/physics_parameters.h"
#include "thread_flags.h"

namespace sg::cli {
namespace reproduce {

Dataset loadDataset(const fs::path& path) {
  if (!fs::exists(path))
    throw InputError(path.string() +
                     ": dataset file not found (give the datasets folder with --datasets DIR)");
  return loadLog(path.string());
}

ReferenceMap loadReferenceMap(const fs::path& path) {
  if (!fs::exists(path))
    throw InputError(path.string() +
                     ": reference map not found (give the datasets folder with --datasets DIR)");
  try {
    return readReference(path.string());
  } catch (const LogError& e) {
    throw InputError(e.what());
  }
}

GridSpec experimentGrid(const std::vector<const Dataset*>& logs, const ReferenceMap& reference,
                        double cell, PoseSource pose) {
  Position lo(std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity());
  Position hi = -lo;
  for (const Dataset* d : logs) {
    const GridSpec g = d->fittingGrid(pose, cell, 0.0);
    lo = lo.cwiseMin(g.origin);
    hi = hi.cwiseMax(g.origin + Position(g.widthMetres(), g.heightMetres()));
  }
  for (const ReferenceObject& o : reference.objects) {
    for (std::size_t k = 0; k < o.corners.size(); ++k) {
      lo = lo.cwiseMin(reference.cornerMetres(o, k));
      hi = hi.cwiseMax(reference.cornerMetres(o, k));
    }
  }
  return GridSpec::covering(lo, hi, cell, 0.5);
}

MapperSettings settingsFor(const std::string& model, const std::string& rule, const SonarRing& ring,
                           const std::vector<std::pair<std::string, double>>& overrides) {
  MapperSettings s;
  s.model = model;
  s.rule = rule;
  s.pose = PoseSource::Odometry;  // the maps the robot itself could build (docs/reproduction.md)
  s.parameters = model == forward::kModelName ? forward::defaultForwardParameters()
                                              : defaultParameters(model, rule);
  if (s.parameters.has("omega")) s.parameters.set("omega", radToDeg(ring.apertureRad));
  for (const auto& [name, value] : overrides) s.parameters.set(name, value);
  return s;
}

OccupancyMap mapLog(const Dataset& data, const fs::path& path, const GridSpec& grid,
                    const MapperSettings& settings, FootprintObserver* observer) {
  try {
    if (settings.model == forward::kModelName) {  // EM over the whole log (docs/forward-model.md)
      if (observer) throw InputError("the forward model writes no per-reading footprints");
      return forward::runEm(forward::beamsOf(data, settings.pose), grid,
                            forward::settingsOf(settings.parameters))
          .map;
    }
    Mapper mapper(data.ring, grid, settings);
    mapper.setObserver(observer);
    mapper.mapDataset(data);
    return mapper.snapshot();
  } catch (const forward::ForwardError& e) {
    throw InputError(path.string() + ": " + e.what());
  } catch (const MapperError& e) {
    throw InputError(path.string() + ": " + e.what());
  }
}

CommonScores scoreOnCommonCells(
    std::size_t configs, const GridSpec& grid,
    const std::function<OccupancyMap(std::size_t c, const GridSpec& on)>& mapConfig,
    const ReferenceMap& reference, const ScoreOptions& options, const fs::path& referencePath) {
  CommonScores out;
  out.maps.resize(configs);
  for (std::size_t c = 0; c < configs; ++c) out.maps[c] = mapConfig(c, grid);
  if (std::any_of(out.maps.begin(), out.maps.end(),
                  [&](const OccupancyMap& m) { return !(m.spec == out.maps.front().spec); })) {
    const GridSpec all = unionOf(out.maps);
    for (std::size_t c = 0; c < configs; ++c)
      if (!(out.maps[c].spec == all)) out.maps[c] = mapConfig(c, all);
  }
  ScoreOptions common = options;
  std::vector<const OccupancyMap*> observed;
  for (const OccupancyMap& m : out.maps) observed.push_back(&m);
  common.cellMask = commonObservedCells(observed);
  for (const OccupancyMap& m : out.maps) {
    try {
      out.scores.push_back(scoreAgainstReference(m, reference, common));
    } catch (const MetricsError& e) {
      throw InputError(referencePath.string() + ": " + e.what());
    }
  }
  return out;
}

void writeMapWithReference(const OccupancyMap& map, const ReferenceMap& reference,
                           const fs::path& path, const std::vector<Position>& markers) {
  PngOptions options;
  options.scale = 4;
  options.legend = true;
  for (const ReferenceObject& o : reference.objects) {
    for (const auto& edge : reference.edgesMetres(o)) options.lines.push_back(edge);
  }
  options.markers = markers;
  writeMapPng(map, path.string(), options);
}

fs::path paperDirectory(const Context& ctx, const std::string& name) {
  const fs::path dir = ctx.out / name;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw std::runtime_error("cannot create '" + dir.string() + "': " + ec.message());
  return dir;
}

void writeText(const fs::path& path, const std::string& text) {
  writeFileAtomically(path.string(), text);
}

std::string Table::markdown() const {
  auto line = [](const std::vector<std::string>& cells) {
    std::string s = "|";
    for (const std::string& c : cells) s += " " + c + " |";
    return s + "\n";
  };
  std::string out = line(header);
  out += "|";
  for (std::size_t k = 0; k < header.size(); ++k) out += k == 0 ? "---|" : "---:|";
  out += "\n";
  for (const auto& r : rows) out += line(r);
  return out;
}

std::string Table::csv() const {
  auto line = [](const std::vector<std::string>& cells) {
    std::string s;
    for (std::size_t k = 0; k < cells.size(); ++k) {
      const std::string& c = cells[k];
      const bool quote = c.find_first_of(",\"\n") != std::string::npos;
      std::string q = c;
      if (quote) {
        q.clear();
        for (char ch : c) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
        q = "\"" + q + "\"";
      }
      s += (k ? "," : "") + q;
    }
    return s + "\n";
  };
  std::string out = line(header);
  for (const auto& r : rows) out += line(r);
  return out;
}

std::string exact(const std::optional<double>& v) {
  if (!v) return "";
  std::array<char, 32> buf{};
  const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), *v);
  return std::string(buf.data(), r.ptr);
}

std::string fixed(const std::optional<double>& v, int decimals) {
  if (!v) return "—";
  std::ostringstream s;
  s << std::fixed << std::setprecision(decimals) << *v;
  return s.str();
}

Json orNull(const std::optional<double>& v) {
  return v ? Json(*v) : Json(nullptr);
}

MeanSd meanSd(const std::vector<std::optional<double>>& values) {
  MeanSd r;
  double sum = 0.0;
  for (const auto& v : values) {
    if (v) {
      sum += *v;
      ++r.n;
    }
  }
  if (r.n == 0) return r;
  const double mean = sum / static_cast<double>(r.n);
  r.mean = mean;
  if (r.n < 2) return r;
  double ss = 0.0;
  for (const auto& v : values) {
    if (v) ss += (*v - mean) * (*v - mean);
  }
  r.sd = std::sqrt(ss / static_cast<double>(r.n - 1));
  return r;
}

void reportProgress(const Context& ctx, const std::string& what, std::size_t done,
                    std::size_t total) {
  if (!ctx.progress) return;
  std::cerr << "\r" << what << " " << done << "/" << total << (done == total ? "\n" : "")
            << std::flush;
}

}  // namespace reproduce

namespace reproduce {

fs::path defaultDatasets() {
#ifdef SONARGRID_SOURCE_DATASETS
  if (fs::is_directory(SONARGRID_SOURCE_DATASETS)) return SONARGRID_SOURCE_DATASETS;
#endif
#ifdef SONARGRID_INSTALLED_DATASETS
  if (fs::is_directory(SONARGRID_INSTALLED_DATASETS)) return SONARGRID_INSTALLED_DATASETS;
#endif
  throw InputError("no bundled datasets folder found; give one with --datasets DIR");
}

}  // namespace reproduce

int runReproduce(Arguments& args) {
  namespace fs = reproduce::fs;
  std::optional<std::string> paper;
  for (const char* name : {"raschke1990", "osullivan", "arafat", "thrun2003"}) {
    if (!args.flag(name)) continue;
    if (paper) throw UsageError("reproduce takes one paper, got " + *paper + " and " + name);
    paper = name;
  }
  reproduce::Context ctx;
  ctx.out = args.required("--out");
  const std::optional<std::string> datasets = args.value("--datasets");
  const bool json = args.flag("--json");
  const bool progress = args.flag("--progress");
  ctx.sets = static_cast<std::size_t>(args.integer("--sets", 0, 0, 1440));
  const std::string physics = args.value("--physics").value_or("all");
  std::vector<std::string> presets;
  if (physics == "all") {
    presets = physicsPresetNames();
  } else if (physicsPreset(physics)) {
    presets = {physics};
  } else {
    throw UsageError("--physics expects clean, default, harsh or all, got '" + physics + "'");
  }
  applyThreadOptions(args);
  if (!paper) {
    // A word left over is most likely a misspelt paper; finish() names it.
    try {
      args.finish();
    } catch (const UsageError& e) {
      throw UsageError(std::string(e.what()) +
                       "; reproduce takes a paper: raschke1990, osullivan, arafat or thrun2003");
    }
    throw UsageError("reproduce needs a paper: raschke1990, osullivan, arafat or thrun2003");
  }
  args.finish();
  if (*paper != "arafat" && ctx.sets != 0) throw UsageError("--sets shapes the arafat sweep only");
  ctx.datasets = datasets ? fs::path(*datasets) : reproduce::defaultDatasets();
  if (!fs::is_directory(ctx.datasets))
    throw InputError("--datasets " + ctx.datasets.string() + ": not a directory");
  // Progress is for a person watching: on a terminal, or when asked; never in the way of --json.
  ctx.progress = progress || isatty(STDERR_FILENO) == 1;

  // Each preset's run (docs/reproduction.md): `default` on the datasets folder (the bundled logs
  // are the default's), the others on logs simulated like datasets/generate.sh's into
  // DIR/datasets-PRESET, their tables and figures in DIR/physics-PRESET/<paper>/.
  const auto runPaper = [&](const reproduce::Context& c) {
    if (*paper == "raschke1990") return reproduce::runRaschke1990(c);
    if (*paper == "osullivan") return reproduce::runOSullivan(c);
    if (*paper == "thrun2003") return reproduce::runThrun2003(c);
    return reproduce::runArafat(c);
  };
  const std::vector<std::string> folders =
      *paper == "raschke1990" ? std::vector<std::string>{"raschke-multi", "raschke-single"}
      : *paper == "thrun2003" ? std::vector<std::string>{"arafat-room", "raschke-multi"}
                              : std::vector<std::string>{"arafat-room"};
  reproduce::Json presetResults = reproduce::Json::object();
  for (const std::string& preset : presets) {
    reproduce::Context c = ctx;
    if (preset != "default") {
      c.datasets = ctx.out / ("datasets-" + preset);
      c.out = ctx.out / ("physics-" + preset);
      if (ctx.progress) std::cerr << "simulating the " << preset << " datasets\n";
      reproduce::simulateDatasets(ctx.datasets, c.datasets, preset, folders);
    }
    presetResults[preset] = runPaper(c);
  }
  // The top level is the default preset's (or the one preset asked for), as before presets.
  const std::string first =
      presetResults.contains("default") ? std::string("default") : presets.front();
  reproduce::Json summary = reproduce::Json::object();
  summary[*paper] = presetResults[first];
  summary[*paper]["physics"] = first;
  summary[*paper]["presets"] = presetResults;

  if (json) {
    std::cout << summary.dump() << '\n';
  } else {
    std::cout << "wrote " << (ctx.out / *paper).string()
              << "/ (tables in *.md and *.csv, figures in *.png)\n"
              << summary.dump(2) << '\n';
  }
  return 0;
}

}  // namespace sg::cli
