// SPDX-License-Identifier: GPL-3.0-or-later
// `sonargrid-cli optimize` (docs/sweeps.md, "Optimize"): the evaluations of a sweep, chosen by a
// derivative-free optimiser of NLopt instead of a grid. The first --metric is the objective
// (minimised or maximised as the metric's sense says); every other --metric is reported for each
// evaluation. The parameters of --range are searched in [lo, hi], scaled to [0, 1] so that one
// step means the same for a probability and for an angle in degrees; --tie and --set as in sweep.

#include <chrono>
#include <cmath>
#include <csignal>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <nlopt.hpp>

#include "commands.h"
#include "sonargrid/base/atomic_file.h"
#include "stop_signal.h"
#include "sweep_options.h"
#include "sweep_report.h"

namespace sg::cli {
namespace {

using Json = nlohmann::ordered_json;

struct Algorithm {
  const char* name;
  nlopt::algorithm global;  // the first stage
  bool polish;              // then BOBYQA from the best point with the rest of the budget
  const char* what;
};
// The default: CRS2 with local mutation (Kaelo & Ali 2006) spreads a seeded population over the
// box and contracts it towards the best points, which finds the basin of a multi-modal,
// non-smooth objective such as IOP over a cone model's parameters; BOBYQA (Powell 2009) then
// refines inside that basin with a quadratic model, far fewer evaluations than CRS2 would need.
constexpr Algorithm kAlgorithms[] = {
    {"crs2+bobyqa", nlopt::GN_CRS2_LM, true, "CRS2-LM for 2/3 of the budget, then BOBYQA"},
    {"crs2", nlopt::GN_CRS2_LM, false, "controlled random search with local mutation"},
    {"direct-l+bobyqa", nlopt::GN_DIRECT_L, true, "DIRECT-L for 2/3 of the budget, then BOBYQA"},
    {"direct-l", nlopt::GN_DIRECT_L, false, "locally biased DIRECT (deterministic)"},
    {"isres", nlopt::GN_ISRES, false, "improved stochastic ranking evolution strategy"},
    {"esch", nlopt::GN_ESCH, false, "evolutionary algorithm"},
    {"bobyqa", nlopt::LN_BOBYQA, false, "BOBYQA from the middle of the box (local)"},
    {"cobyla", nlopt::LN_COBYLA, false, "COBYLA from the middle of the box (local)"},
    {"sbplx", nlopt::LN_SBPLX, false, "Subplex from the middle of the box (local)"},
    {"neldermead", nlopt::LN_NELDERMEAD, false, "Nelder-Mead from the middle of the box (local)"},
};

bool isLocal(nlopt::algorithm a) {
  return a == nlopt::LN_BOBYQA || a == nlopt::LN_COBYLA || a == nlopt::LN_SBPLX ||
         a == nlopt::LN_NELDERMEAD;
}

struct Evaluation {
  ParameterSet set;
  std::vector<std::optional<double>> values;  // metricColumns(metrics)
  std::optional<double> objective;            // in the metric's own sense; empty if undefined
};

// Thrown from the objective to end the optimiser early (budget reached, signal).
struct StopSearch {};

}  // namespace

int runOptimize(Arguments& args) {
  SweepOptions o = parseSweepOptions(args);
  std::vector<SweepRange> ranges;
  for (const std::string& r : args.values("--range")) {
    try {
      ranges.push_back(parseSweepRange(r, o.map.settings.parameters));
    } catch (const SweepSpecError& e) {
      throw UsageError(std::string("--range ") + e.what());
    }
  }
  if (ranges.empty()) throw UsageError("optimize needs at least one --range P=LO:HI");
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (ranges[i].parameter == ranges[j].parameter)
        throw UsageError("--range " + ranges[i].parameter + " is given twice");
    }
    for (const SweepTie& t : o.ties) {
      if (t.parameter == ranges[i].parameter)
        throw UsageError("--tie '" + t.text() + "': " + t.parameter + " is searched by --range");
    }
  }
  const int budget = args.integer("--budget", 150, 1, 1000000);
  std::uint64_t seed = 1;
  if (const auto s = args.value("--seed")) seed = parseSeed(*s);
  const std::string algorithmName = args.value("--algorithm").value_or("crs2+bobyqa");
  const std::optional<std::string> csvPath = args.value("--csv");
  const bool json = args.flag("--json");
  const bool progress = args.flag("--progress");
  args.finish();
  const Algorithm* algorithm = nullptr;
  for (const Algorithm& a : kAlgorithms) {
    if (algorithmName == a.name) algorithm = &a;
  }
  if (!algorithm) {
    std::string names;
    for (const Algorithm& a : kAlgorithms)
      names += (names.empty() ? "" : ", ") + std::string(a.name);
    throw UsageError("--algorithm takes " + names + ", got '" + algorithmName + "'");
  }
  // Ties are checked on the box's corners' middle now rather than at some evaluation later.
  {
    ParameterSet middle = o.map.settings.parameters;
    for (const SweepRange& r : ranges) middle.set(r.parameter, (r.lo + r.hi) / 2.0);
    try {
      applyTies(middle, o.ties);
    } catch (const SweepSpecError& e) {
      throw UsageError(e.what());
    }
  }

  const SweepData data = loadSweepData(o);
  const SetEvaluationInput input = data.input();
  const std::vector<std::string> columns = metricColumns(o.metrics);
  const std::vector<std::string> objectiveColumns = metricColumns({o.firstMetric});
  const std::size_t objectiveAt = static_cast<std::size_t>(
      std::find(columns.begin(), columns.end(), objectiveColumns.front()) - columns.begin());
  const int sense = o.firstMetric == "two-run" ? 1 : betterDirection(objectiveColumns.front());

  std::vector<Evaluation> path;
  std::optional<std::size_t> best;
  StopOnSignal stop;
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t n = ranges.size();

  // x in [0, 1]^n → the parameter set (integer parameters rounded), evaluated; returns the value
  // NLopt minimises.
  auto evaluate = [&](const std::vector<double>& x) -> double {
    if (stop.flag().load() || path.size() >= static_cast<std::size_t>(budget)) throw StopSearch{};
    ParameterSet set = o.map.settings.parameters;
    for (std::size_t i = 0; i < n; ++i) {
      const SweepRange& r = ranges[i];
      double v = r.lo + std::clamp(x[i], 0.0, 1.0) * (r.hi - r.lo);
      for (const ParameterSpec& s : set.specs()) {
        if (s.name == r.parameter && s.integer) v = std::round(v);
      }
      set.set(r.parameter, std::clamp(v, r.lo, r.hi));
    }
    applyTies(set, o.ties);
    std::optional<SetEvaluation> e;
    try {
      e = evaluateSet(input, set, &stop.flag());
    } catch (const std::exception&) {
      rethrowEvaluationError(o);
    }
    if (!e) throw StopSearch{};
    Evaluation ev;
    ev.set = set;
    ev.values = metricValues(o.metrics, *e);
    if (o.firstMetric == "two-run") {
      if (ev.values[objectiveAt] && ev.values[objectiveAt + 1])
        ev.objective = *ev.values[objectiveAt] - *ev.values[objectiveAt + 1];
    } else {
      ev.objective = ev.values[objectiveAt];
    }
    path.push_back(ev);
    if (ev.objective && (!best || sense * *ev.objective > sense * *path[*best].objective))
      best = path.size() - 1;
    if (progress) {
      std::cerr << "\roptimize " << path.size() << "/" << budget << " evaluations";
      if (best) std::cerr << ", best " << objectiveColumns.front() << " " << *path[*best].objective;
      std::cerr << std::flush;
    }
    // An undefined objective (no filled cell, say) is the worst value there is; NLopt needs a
    // finite one.
    return ev.objective ? -sense * *ev.objective : 1e30;
  };

  auto runStage = [&](nlopt::algorithm a, std::vector<double>& x, int evaluations,
                      double initialStep) {
    if (evaluations <= 0) return;
    nlopt::opt opt(a, static_cast<unsigned>(n));
    opt.set_lower_bounds(std::vector<double>(n, 0.0));
    opt.set_upper_bounds(std::vector<double>(n, 1.0));
    opt.set_maxeval(evaluations);
    if (isLocal(a)) opt.set_initial_step(initialStep);
    // The NLopt callback: exceptions must not cross its C frames, so a stop is passed as
    // force_stop and an error is kept and rethrown after.
    struct Context {
      decltype(evaluate)* f;
      nlopt::opt* opt;
      std::exception_ptr error;
    } context{&evaluate, &opt, nullptr};
    opt.set_min_objective(
        [](unsigned dim, const double* xs, double*, void* state) -> double {
          auto* c = static_cast<Context*>(state);
          try {
            return (*c->f)(std::vector<double>(xs, xs + dim));
          } catch (const StopSearch&) {
          } catch (...) {
            c->error = std::current_exception();
          }
          c->opt->force_stop();
          return 0.0;
        },
        &context);
    double value = 0.0;
    try {
      opt.optimize(x, value);
    } catch (const nlopt::forced_stop&) {
    } catch (const std::runtime_error&) {
      // NLopt's generic failure after a forced stop or a roundoff-limited run: the path so far
      // stands.
    }
    if (context.error) std::rethrow_exception(context.error);
  };

  nlopt::srand(static_cast<unsigned long>(seed));
  std::vector<double> x(n, 0.5);
  const int globalBudget = algorithm->polish ? budget * 2 / 3 : budget;
  runStage(algorithm->global, x, globalBudget, 0.25);
  if (algorithm->polish && best && !stop.flag().load()) {
    // BOBYQA from the best point found, with a step a tenth of the box.
    for (std::size_t i = 0; i < n; ++i) {
      const SweepRange& r = ranges[i];
      x[i] = (path[*best].set.get(r.parameter) - r.lo) / (r.hi - r.lo);
    }
    runStage(nlopt::LN_BOBYQA, x, budget - static_cast<int>(path.size()), 0.1);
  }
  if (progress) std::cerr << '\n';
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  auto paramsJson = [&](const ParameterSet& p) {
    Json j = Json::object();
    for (const ParameterSpec& s : p.specs()) j[s.name] = p.get(s.name);
    return j;
  };
  auto entryJson = [&](std::size_t k) {
    Json j;
    j["evaluation"] = k;
    j["params"] = paramsJson(path[k].set);
    for (std::size_t c = 0; c < columns.size(); ++c)
      j[columns[c]] = path[k].values[c] ? Json(*path[k].values[c]) : Json(nullptr);
    return j;
  };

  if (csvPath) {
    std::string bytes = "evaluation";
    for (const ParameterSpec& s : o.map.settings.parameters.specs()) bytes += "," + s.name;
    for (const std::string& c : columns) bytes += "," + c;
    bytes += "\n";
    for (std::size_t k = 0; k < path.size(); ++k) {
      bytes += std::to_string(k);
      for (const ParameterSpec& s : path[k].set.specs())
        bytes += "," + shortestText(path[k].set.get(s.name));
      for (const std::optional<double>& v : path[k].values)
        bytes += "," + (v ? shortestText(*v) : "");
      bytes += "\n";
    }
    writeFileAtomically(*csvPath, bytes);
  }

  const int signal = stop.signalNumber();
  if (json) {
    Json out;
    out["algorithm"] = algorithm->name;
    out["seed"] = seed;
    out["budget"] = budget;
    out["objective"] = o.firstMetric;
    out["sense"] = sense > 0 ? "maximise" : "minimise";
    out["evaluations"] = path.size();
    out["ranges"] = Json::object();
    for (const SweepRange& r : ranges) out["ranges"][r.parameter] = {r.lo, r.hi};
    out["best"] = best ? entryJson(*best) : Json(nullptr);
    Json all = Json::array();
    for (std::size_t k = 0; k < path.size(); ++k) all.push_back(entryJson(k));
    out["path"] = all;
    std::cout << out.dump() << '\n';
  } else {
    std::cout << "optimize: " << algorithm->name << ", seed " << seed << ", " << path.size()
              << " evaluations in " << seconds << " s\n";
    if (best) {
      std::cout << "  best (evaluation " << *best << "): " << objectiveColumns.front() << " "
                << *path[*best].objective << "\n  ";
      for (const SweepRange& r : ranges)
        std::cout << " " << r.parameter << "=" << path[*best].set.get(r.parameter);
      for (const SweepTie& t : o.ties)
        std::cout << " " << t.parameter << "=" << path[*best].set.get(t.parameter);
      std::cout << '\n';
    } else {
      std::cout << "  no evaluation gave a defined " << objectiveColumns.front() << '\n';
    }
  }
  if (signal != 0) {
    std::cerr << "sonargrid-cli: optimize stopped by " << (signal == SIGTERM ? "SIGTERM" : "SIGINT")
              << " after " << path.size() << " evaluations\n";
    return 128 + signal;
  }
  return 0;
}

}  // namespace sg::cli
