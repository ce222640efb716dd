// SPDX-License-Identifier: GPL-3.0-or-later
// `sonargrid-cli map`: map a log with one model and rule, print a summary (or --json), export PNG
// and ROS maps.

#include <algorithm>
#include <chrono>
#include <csignal>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "map_options.h"
#include "sonargrid/data/scan_poses.h"
#include "sonargrid/export/map_export.h"
#include "sonargrid/forward/forward_em.h"
#include "stop_signal.h"
#include "thread_flags.h"

namespace sg::cli {

MapOptions parseMapOptions(Arguments& args) {
  MapOptions o;
  o.log = args.required("--log");
  o.read = parseLogOptions(args);
  applyThreadOptions(args);
  const std::string pose = args.value("--pose").value_or("odom");
  if (pose == "odom")
    o.settings.pose = PoseSource::Odometry;
  else if (pose == "truth")
    o.settings.pose = PoseSource::Truth;
  else
    throw UsageError("--pose takes odom or truth, got '" + pose + "'");
  o.settings.model = args.required("--model");
  const bool forwardModel = o.settings.model == forward::kModelName;
  if (forwardModel) {
    // EM is the forward model's own way of combining readings (docs/forward-model.md).
    o.settings.rule = args.value("--rule").value_or(forward::kRuleName);
    if (o.settings.rule != forward::kRuleName) {
      throw UsageError("--model " + o.settings.model +
                       " learns its map by EM and takes no update rule: leave out --rule '" +
                       o.settings.rule + "'");
    }
  } else {
    o.settings.rule = args.required("--rule");
  }
  o.cell = args.number("--cell", 0.05, 0.001, 10.0);
  o.until = args.number("--until", o.until, -1e300, 1e300);
  // The exact engine by default, until the fast one is faster (docs/models.md, "Exact and fast
  // engines"): today it only keeps the Bayes family's cells in four bytes.
  const std::string precision = args.value("--precision").value_or("exact");
  try {
    o.settings.precision = precisionFromName(precision);
  } catch (const std::invalid_argument&) {
    throw UsageError("--precision takes fast or exact, got '" + precision + "'");
  }

  if (!forwardModel && !makeSensorModel(o.settings.model)) {
    std::string names;
    for (const std::string& n : sensorModelNames()) names += (names.empty() ? "" : ", ") + n;
    throw UsageError("unknown --model '" + o.settings.model + "'; choose one of " + names + ", " +
                     forward::kModelName);
  }
  if (forwardModel) {
    o.settings.parameters = forward::defaultForwardParameters();
  } else if (!makeUpdateRule(o.settings.rule)) {
    std::string names;
    for (const std::string& n : updateRuleNames()) names += (names.empty() ? "" : ", ") + n;
    throw UsageError("unknown --rule '" + o.settings.rule + "'; choose one of " + names);
  }
  if (!forwardModel) {
    const Compatibility c = compatibility(o.settings.model, o.settings.rule);
    if (!c.allowed) {
      throw InputError("model '" + o.settings.model + "' cannot be used with rule '" +
                       o.settings.rule + "': " + c.reason);
    }
    o.settings.parameters = defaultParameters(o.settings.model, o.settings.rule);
  }
  std::vector<std::string> seen;
  for (const std::string& kv : args.values("--set")) {
    const auto eq = kv.find('=');
    if (eq == std::string::npos || eq == 0)
      throw UsageError("--set expects NAME=VALUE, got '" + kv + "'");
    const std::string name = kv.substr(0, eq);
    if (std::find(seen.begin(), seen.end(), name) != seen.end())
      throw UsageError("--set " + name + " is given twice");
    seen.push_back(name);
    try {
      o.settings.parameters.set(name, parseNumber(kv.substr(eq + 1), "--set " + name));
    } catch (const ParameterError& e) {
      throw UsageError(std::string("--set: ") + e.what());
    }
  }
  if (const auto iterations = args.value("--iterations")) {
    if (!forwardModel)
      throw UsageError("--iterations caps EM's iterations: it goes with --model forward-em");
    if (std::find(seen.begin(), seen.end(), "iterations") != seen.end())
      throw UsageError("--iterations and --set iterations= say the same: give one");
    try {
      o.settings.parameters.set("iterations", parseNumber(*iterations, "--iterations"));
    } catch (const ParameterError& e) {
      throw UsageError(std::string("--iterations: ") + e.what());
    }
  }
  return o;
}

GridSpec fittingGridOf(const Dataset& data, const MapOptions& o, const std::string& logPath) {
  try {
    return data.fittingGrid(o.settings.pose, o.cell);
  } catch (const GridLimitError& e) {
    throw e.inFile(logPath);
  }
}

namespace {

// The forward model's map: EM over the whole log (docs/forward-model.md), with a line of progress
// per iteration on stderr; `cancel` stops it between iterations (MapStopped).
BuiltMap buildForwardMap(const Dataset& data, const MapOptions& o, const std::string& logPath,
                         const GridSpec& grid, BuiltMap out, const std::atomic<bool>* cancel) {
  const forward::ForwardSettings settings = forward::settingsOf(o.settings.parameters);
  try {
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<forward::ForwardBeam> beams =
        forward::beamsOf(data, o.settings.pose, o.until);
    forward::EmResult em =
        forward::runEm(beams, grid, settings, cancel, [&](const forward::EmProgress& p) {
          if (!o.progress) return;
          std::cerr << "sonargrid-cli: EM iteration " << p.iteration << " of at most " << p.cap
                    << ": log-likelihood " << std::setprecision(10) << p.logLikelihood << '\n';
        });
    if (em.cancelled) throw MapStopped{};
    out.elapsedMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    out.readings = em.readings;
    out.map = std::move(em.map);
    out.em = ForwardRun{std::move(em.logLikelihood), em.iterations, em.converged, em.coneCells};
  } catch (const forward::ForwardError& e) {
    throw InputError(logPath + ": " + e.what());
  }
  return out;
}

}  // namespace

BuiltMap buildMap(const Dataset& data, const MapOptions& o, const std::string& logPath,
                  const std::optional<GridSpec>& onGrid, FootprintObserver* observer,
                  const std::atomic<bool>* cancel) {
  if (o.settings.pose == PoseSource::Truth && !anyScanHasPose(data, PoseSource::Truth)) {
    throw InputError(logPath + ": " + kNoTruePose + "; map with --pose odom");
  }
  const GridSpec grid = onGrid ? *onGrid : fittingGridOf(data, o, logPath);
  BuiltMap out;
  out.scansWithoutTruth = scansWithoutPose(data, o.settings.pose);
  if (out.scansWithoutTruth != 0) {
    std::cerr << "sonargrid-cli: note: " << logPath << ": " << out.scansWithoutTruth << " of "
              << data.scans.size() << " scans have no true pose and are left out of the map\n";
  }
  if (o.settings.model == forward::kModelName) {
    if (observer) {
      throw UsageError("--model " + o.settings.model +
                       " writes no per-reading evidence to take statistics of; choose an inverse "
                       "model");
    }
    return buildForwardMap(data, o, logPath, grid, std::move(out), cancel);
  }
  try {
    Mapper mapper(data.ring, grid, o.settings);
    mapper.setObserver(observer);
    const auto t0 = std::chrono::steady_clock::now();
    if (!mapper.mapDataset(data, o.until, cancel)) throw MapStopped{};
    out.elapsedMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    out.readings = mapper.readingsIntegrated();
    out.map = mapper.snapshot();
  } catch (const MapperError& e) {
    throw InputError(logPath + ": " + e.what());
  }
  return out;
}

int runMap(Arguments& args) {
  const MapOptions o = parseMapOptions(args);
  const auto png = args.value("--png");
  const bool legend = args.flag("--legend");
  const int scale = args.integer("--scale", 1, 1, 64);
  const auto ros = args.value("--ros-map");
  const bool json = args.flag("--json");
  args.finish();
  if (!png && (legend || scale != 1))
    throw UsageError("--legend and --scale shape the PNG; give --png FILE");

  const Dataset data = loadLog(o.log, o.read);
  // Ctrl-C (SIGINT) or SIGTERM stops the mapping (the forward model's EM takes up to a minute):
  // nothing is written, exit status 128 + the signal.
  BuiltMap built;
  {
    const StopOnSignal stop;
    try {
      built = buildMap(data, o, o.log, std::nullopt, nullptr, &stop.flag());
    } catch (const MapStopped&) {
      const int signal = stop.signalNumber() == 0 ? SIGINT : stop.signalNumber();
      std::cerr << "sonargrid-cli: map stopped by " << (signal == SIGTERM ? "SIGTERM" : "SIGINT")
                << "; nothing written\n";
      return 128 + signal;
    }
  }

  if (png) {
    PngOptions po;
    po.legend = legend;
    po.scale = scale;
    writeMapPng(built.map, *png, po);
  }
  if (ros) writeRosMap(built.map, *ros);

  const OccupancyMap& m = built.map;
  if (json) {
    nlohmann::ordered_json out;
    out["model"] = o.settings.model;
    out["rule"] = o.settings.rule;
    out["precision"] = o.settings.precision == Precision::Fast ? "fast" : "exact";
    nlohmann::ordered_json params = nlohmann::ordered_json::object();
    for (const ParameterSpec& s : o.settings.parameters.specs())
      params[s.name] = o.settings.parameters.get(s.name);
    out["params"] = params;
    out["grid"] = {{"width", m.spec.width},
                   {"height", m.spec.height},
                   {"cell_m", m.spec.cellSize},
                   {"origin", {m.spec.origin.x(), m.spec.origin.y()}}};
    out["readings"] = built.readings;
    out["scans_without_truth"] = built.scansWithoutTruth;
    out["cells_filled"] = m.filledCount();
    out["cv_histogram"] = m.levelHistogram();
    out["elapsed_ms"] = built.elapsedMs;
    if (built.em) {
      out["em"] = {{"iterations", built.em->iterations},
                   {"converged", built.em->converged},
                   {"cone_cells", built.em->coneCells},
                   {"log_likelihood", built.em->logLikelihood}};
    }
    std::cout << out.dump() << '\n';
  } else {
    std::cout << o.log << ": " << built.readings << " readings mapped with " << o.settings.model
              << " × " << o.settings.rule
              << (o.settings.precision == Precision::Fast ? " (fast engine)" : "") << " on "
              << m.spec.width << " x " << m.spec.height << " cells of " << m.spec.cellSize
              << " m in " << built.elapsedMs << " ms; " << m.filledCount() << " cells filled\n";
    if (png) std::cout << "wrote " << *png << '\n';
    if (ros) std::cout << "wrote " << *ros << ".yaml and " << *ros << ".pgm\n";
  }
  return 0;
}

}  // namespace sg::cli
