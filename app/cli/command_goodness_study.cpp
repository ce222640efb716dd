// SPDX-License-Identifier: GPL-3.0-or-later
// `sonargrid-cli goodness-study` (docs/goodness-study.md): paper 002's open question — which
// measure of a map's goodness, computed without a reference, predicts its quality against one?
// Over the sets of a sweep (sweep's flags: --grid, --tie, --set ...) every set is mapped and
// measured once by the sweep's own evaluation (set_evaluation.h); then, for each reference-free
// measure and each reference metric, Spearman's ρ over the sets and its percentile bootstrap
// interval (rank_correlation.h).

#include <chrono>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "commands.h"
#include "sonargrid/base/atomic_file.h"
#include "sonargrid/sweep/rank_correlation.h"
#include "sweep_options.h"

namespace sg::cli {
namespace {

using Json = nlohmann::ordered_json;

// One set's values, looked up by the sweep's CSV column names (metricColumns()).
class SetColumns {
 public:
  SetColumns(const std::vector<std::string>& columns,
             const std::vector<std::optional<double>>& values)
      : columns_(columns), values_(values) {}
  std::optional<double> get(const std::string& column) const {
    for (std::size_t c = 0; c < columns_.size(); ++c) {
      if (columns_[c] == column) return values_[c];
    }
    return std::nullopt;
  }

 private:
  const std::vector<std::string>& columns_;
  const std::vector<std::optional<double>>& values_;
};

// The reference-free measures of the study, one line each: the name in the output, the sweep
// --metric that computes it, which way is better (+1 higher, −1 lower) and its value from a set's
// columns. A measure whose metric needs a second log is left out without --second-log.
struct FreeMeasure {
  const char* name;
  const char* metric;
  int better;
  std::optional<double> (*value)(const SetColumns&);
};
constexpr FreeMeasure kFreeMeasures[] = {
    // Paper 002 §5, first approach: mean of the non-zero per-cell σ of the model's values.
    {"vsdns", "vsdns", -1, [](const SetColumns& c) { return c.get("vsdns"); }},
    // Paper 002 §5, second approach: D_map, and D_map per scored cell.
    {"derivative_noise", "derivative", -1,
     [](const SetColumns& c) { return c.get("derivative_noise"); }},
    {"derivative_noise_mean", "derivative", -1,
     [](const SetColumns& c) { return c.get("derivative_noise_mean"); }},
    // Paper 002 §5, third approach: the share of the cells both runs observed on which their
    // thresholded maps agree, positive / (positive + negative). A share rather than either count,
    // since how many cells both runs observe changes with the parameters.
    {"two_run_agreement", "two-run", 1,
     [](const SetColumns& c) -> std::optional<double> {
       const auto positive = c.get("two_run_positive");
       const auto negative = c.get("two_run_negative");
       if (!positive || !negative || *positive + *negative <= 0.0) return std::nullopt;
       return *positive / (*positive + *negative);
     }},
    // Map entropy (Martin & Moravec 1996, named in paper 002): the bits of uncertainty left in the
    // observed cells, Σ −p log2 p − (1 − p) log2 (1 − p). Lower is better: a map that has made up
    // its mind (docs/metrics.md, "Map entropy"; it rewards confidence, not truth).
    {"entropy", "entropy", -1, [](const SetColumns& c) { return c.get("map_entropy"); }},
};

struct ReferenceMeasure {
  const char* name;  // the sweep's column (`score --json` key)
  const char* metric;
  int better;
};
constexpr ReferenceMeasure kReferenceMeasures[] = {
    {"iop_mm", "iop", -1},                  // paper 000 eq 9
    {"correlation_pct", "correlation", 1},  // paper 001 benchmark 1
    {"auc", "auc", 1},
};

struct Row {
  std::string free;
  std::string reference;
  int oriented = 1;  // +1 when both have the same better direction
  std::size_t n = 0;
  SpearmanBootstrap result;
};

std::string fixed(std::optional<double> v, int decimals) {
  if (!v) return "-";
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(decimals);
  s << (*v == 0.0 ? 0.0 : *v);  // no "-0.000"
  return s.str();
}

}  // namespace

int runGoodnessStudy(Arguments& args) {
  bool secondLog = false;
  {
    Arguments probe = args;
    if (!probe.values("--metric").empty())
      throw UsageError(
          "--metric does not go with goodness-study: it measures VSDNS, derivative noise, map "
          "entropy, the two-run agreement (with --second-log), IOP, correlation and AUC itself");
    if (!probe.value("--reference"))
      throw UsageError("goodness-study compares with a reference map; give --reference REF");
    secondLog = probe.value("--second-log").has_value();
  }
  std::vector<const FreeMeasure*> free;
  std::vector<std::string> metricTexts;
  for (const FreeMeasure& f : kFreeMeasures) {
    if (std::string(f.metric) == "two-run" && !secondLog) continue;
    free.push_back(&f);
    metricTexts.emplace_back(f.metric);
  }
  for (const ReferenceMeasure& r : kReferenceMeasures) metricTexts.emplace_back(r.metric);
  SweepOptions o = parseSweepOptions(args, metricTexts);

  const std::vector<std::string> gridTexts = args.values("--grid");
  const int bootstrap = args.integer("--bootstrap", 1000, 0, 1000000);
  std::uint64_t seed = 1;
  if (const auto s = args.value("--seed")) seed = parseSeed(*s);
  const std::optional<std::string> csvPath = args.value("--csv");
  const bool json = args.flag("--json");
  const bool progress = args.flag("--progress");
  args.finish();

  const SweepSpace space = parseSweepSpace(gridTexts, o);
  const std::vector<ParameterSet>& sets = space.sets;
  if (sets.size() < 3)
    throw UsageError("--grid gives " + std::to_string(sets.size()) +
                     (sets.size() == 1 ? " set" : " sets") +
                     "; a rank correlation over sets needs at least 3");

  // Every set mapped and measured once, in set order whatever the thread that did it.
  const auto t0 = std::chrono::steady_clock::now();
  const SweepData data = loadSweepData(o);
  const std::vector<std::string> columns = metricColumns(o.metrics);
  std::vector<std::vector<std::optional<double>>> values(sets.size());
  std::vector<std::size_t> all(sets.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  std::size_t done = 0;
  try {
    evaluateSets(data.input(), sets, all, [&](std::size_t k, const SetEvaluation& e) {
      values[k] = metricValues(o.metrics, e);
      if (progress) std::cerr << "\rgoodness-study " << ++done << "/" << sets.size() << " sets";
    });
  } catch (const std::exception&) {
    rethrowEvaluationError(o);
  }
  if (progress) std::cerr << '\n';

  // The sets as a sweep CSV: the bytes `sweep` writes for the same flags and metrics.
  if (csvPath) {
    SweepHeader header;
    header.sets = sets.size();
    describeSweep(o, header);
    header.fields.insert(header.fields.end(), space.fields.begin(), space.fields.end());
    std::string bytes = header.text();
    for (std::size_t i = 0; i < sets.size(); ++i) {
      SweepCsvRow row;
      row.index = i;
      for (const std::string& name : header.parameters) row.parameters.push_back(sets[i].get(name));
      row.values = values[i];
      bytes += rowText(row);
    }
    writeFileAtomically(*csvPath, bytes);
  }

  // Each pair of measures over the sets where both are defined.
  std::vector<Row> table;
  for (const FreeMeasure* f : free) {
    for (const ReferenceMeasure& r : kReferenceMeasures) {
      std::vector<double> x, y;
      for (const auto& v : values) {
        const SetColumns c(columns, v);
        const std::optional<double> a = f->value(c);
        const std::optional<double> b = c.get(r.name);
        if (a && b) {
          x.push_back(*a);
          y.push_back(*b);
        }
      }
      Row row;
      row.free = f->name;
      row.reference = r.name;
      row.oriented = f->better * r.better;
      row.n = x.size();
      row.result = bootstrapSpearman(x, y, static_cast<std::size_t>(bootstrap), seed);
      table.push_back(std::move(row));
    }
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  if (json) {
    Json out;
    out["sets"] = sets.size();
    out["bootstrap"] = bootstrap;
    out["seed"] = seed;
    Json rows = Json::array();
    for (const Row& row : table) {
      Json j;
      j["free"] = row.free;
      j["reference"] = row.reference;
      j["spearman"] = row.result.rho ? Json(*row.result.rho) : Json(nullptr);
      j["ci95"] = row.result.lo ? Json::array({*row.result.lo, *row.result.hi}) : Json(nullptr);
      j["n"] = row.n;
      // ρ signed so that > 0 means "ranks the sets in the reference's order of quality".
      j["oriented"] = row.result.rho ? Json(row.oriented * *row.result.rho) : Json(nullptr);
      j["bootstrap_defined"] = row.result.defined;
      rows.push_back(j);
    }
    out["table"] = rows;
    std::cout << out.dump() << '\n';
    return 0;
  }
  std::string lower, higher;
  auto sense = [&](const std::string& name, int better) {
    std::string& list = better > 0 ? higher : lower;
    list += (list.empty() ? "" : ", ") + name;
  };
  for (const FreeMeasure* f : free) sense(f->name, f->better);
  for (const ReferenceMeasure& r : kReferenceMeasures) sense(r.name, r.better);
  std::cout << "goodness-study: " << sets.size() << " sets, " << bootstrap
            << " bootstrap replicates, seed " << seed << ", " << fixed(seconds, 1) << " s\n"
            << "  lower is better: " << lower << "; higher: " << higher << "\n"
            << "  oriented: rho signed so that > 0 means the free measure ranks the sets as the "
               "reference does\n\n";
  char line[160];
  std::snprintf(line, sizeof line, "%-22s %-16s %5s %8s %19s %9s\n", "free measure", "reference",
                "n", "rho", "95% CI", "oriented");
  std::cout << line;
  for (const Row& row : table) {
    const std::string ci =
        row.result.lo ? "[" + fixed(row.result.lo, 3) + ", " + fixed(row.result.hi, 3) + "]" : "-";
    const std::string oriented = row.result.rho ? fixed(row.oriented * *row.result.rho, 3) : "-";
    std::snprintf(line, sizeof line, "%-22s %-16s %5zu %8s %19s %9s\n", row.free.c_str(),
                  row.reference.c_str(), row.n, fixed(row.result.rho, 3).c_str(), ci.c_str(),
                  oriented.c_str());
    std::cout << line;
  }
  if (csvPath) std::cout << "\nwrote " << *csvPath << '\n';
  return 0;
}

}  // namespace sg::cli
