// SPDX-License-Identifier: GPL-3.0-or-later
#include "sweep_options.h"

#include <charconv>
#include <exception>
#include <filesystem>
#include <limits>

#include "sonargrid/metrics/reference_score.h"
#include "sonargrid/reference/read_reference.h"

namespace sg::cli {

SweepOptions parseSweepOptions(Arguments& args) {
  const std::vector<std::string> metricTexts = args.values("--metric");
  return parseSweepOptions(args, metricTexts);
}

SweepOptions parseSweepOptions(Arguments& args, const std::vector<std::string>& metricTexts) {
  SweepOptions o;
  {
    // The log-reading flags as written, before parseMapOptions consumes them: they decide how the
    // log reads, so they belong in the sweep's fingerprint.
    Arguments probe = args;
    for (const char* flag : {"--format", "--robot", "--columns", "--poses", "--start-pose",
                             "--odom-topic", "--truth-topic"}) {
      if (const auto v = probe.value(flag)) o.logFlags.emplace_back(flag, *v);
    }
    for (const std::string& v : probe.values("--sonar-topic"))
      o.logFlags.emplace_back("--sonar-topic", v);
    if (probe.flag("--lenient")) o.logFlags.emplace_back("--lenient", "yes");
    // A sweep's batched evaluation maps every set with the exact engine (docs/models.md, "Exact
    // and fast engines"): its rankings are the oracle's.
    if (probe.value("--precision").value_or("exact") != "exact")
      throw UsageError(
          "sweeps, the optimiser and the goodness study map with the exact engine: leave out "
          "--precision");
  }
  o.map = parseMapOptions(args);
  o.map.settings.precision = Precision::Exact;
  if (o.map.until != std::numeric_limits<double>::infinity())
    throw UsageError("--until does not go with a sweep: every set maps the whole log");
  o.secondLog = args.value("--second-log");
  o.referencePath = args.value("--reference");
  if (metricTexts.empty())
    throw UsageError("give at least one --metric (vsdns, derivative, entropy, two-run, iop, ...)");
  o.metrics = parseSweepMetrics(metricTexts);
  o.firstMetric =
      parseSweepMetrics({metricTexts.front().substr(0, metricTexts.front().find(','))}).front();
  for (const std::string& m : o.metrics) {
    if (isReferenceMetric(m) && !o.referencePath)
      throw UsageError("--metric " + m + " compares with a reference map; give --reference REF");
    if (m == "two-run" && !o.secondLog)
      throw UsageError("--metric two-run compares two runs; give --second-log FILE");
  }
  for (const std::string& t : args.values("--tie")) {
    try {
      o.ties.push_back(parseSweepTie(t, o.map.settings.parameters));
    } catch (const SweepSpecError& e) {
      throw UsageError(std::string("--tie ") + e.what());
    }
  }
  return o;
}

SetEvaluationInput SweepData::input() const {
  SetEvaluationInput in;
  in.run = &run;
  in.secondRun = secondRun ? &*secondRun : nullptr;
  in.reference = reference ? &*reference : nullptr;
  in.settings = settings;
  in.measures = measures;
  return in;
}

SweepData loadSweepData(const SweepOptions& o) {
  SweepData d;
  d.run = loadLog(o.map.log, o.map.read);
  d.settings.model = o.map.settings.model;
  d.settings.rule = o.map.settings.rule;
  d.settings.pose = o.map.settings.pose;
  d.measures = measuresOf(o.metrics);
  GridSpec& grid = d.settings.grid;
  grid = fittingGridOf(d.run, o.map, o.map.log);
  if (o.secondLog) {
    d.secondRun = loadLog(*o.secondLog, o.map.read);
    // One grid over both runs, as `goodness` makes it: both fitting grids are snapped to
    // multiples of the cell size, so the union is too and the runs' cells line up.
    const GridSpec b = fittingGridOf(*d.secondRun, o.map, *o.secondLog);
    try {
      grid = gridOverRuns(grid, b);
    } catch (const GridLimitError& e) {
      throw e.inFile(o.map.log + " and " + *o.secondLog);
    }
  }
  if (o.referencePath) {
    try {
      d.reference = readReference(*o.referencePath);
    } catch (const LogError& e) {
      throw InputError(e.what());
    }
  }
  return d;
}

void describeSweep(const SweepOptions& o, SweepHeader& h) {
  std::string metrics;
  for (const std::string& m : o.metrics) metrics += (metrics.empty() ? "" : ",") + m;
  h.metrics = o.metrics;
  h.columns = metricColumns(o.metrics);
  h.fields.emplace_back("metrics", metrics);
  h.fields.emplace_back("model", o.map.settings.model);
  h.fields.emplace_back("rule", o.map.settings.rule);
  h.fields.emplace_back("pose", o.map.settings.pose == PoseSource::Truth ? "truth" : "odom");
  h.fields.emplace_back("cell", shortestText(o.map.cell));
  std::string base;
  for (const ParameterSpec& s : o.map.settings.parameters.specs()) {
    base += (base.empty() ? "" : " ") + s.name + "=" +
            shortestText(o.map.settings.parameters.get(s.name));
    h.parameters.push_back(s.name);
  }
  h.fields.emplace_back("base", base);
  for (const auto& [flag, value] : o.logFlags) {
    const bool file =
        (flag == "--robot" || flag == "--poses") && std::filesystem::is_regular_file(value);
    h.fields.emplace_back("log-flag", flag + " " + (file ? "file " + fileHash(value) : value));
  }
  h.fields.emplace_back("log", fileHash(o.map.log));
  h.notes.emplace_back("log", o.map.log);
  if (o.secondLog) {
    h.fields.emplace_back("second-log", fileHash(*o.secondLog));
    h.notes.emplace_back("second-log", *o.secondLog);
  }
  if (o.referencePath) {
    h.fields.emplace_back("reference", fileHash(*o.referencePath));
    h.notes.emplace_back("reference", *o.referencePath);
  }
}

void rethrowEvaluationError(const SweepOptions& o) {
  try {
    throw;
  } catch (const MapperError& e) {
    throw InputError(o.map.log + ": " + e.what());
  } catch (const MetricsError& e) {
    throw InputError(o.referencePath.value_or("reference") + ": " + e.what());
  }
}

SweepSpace parseSweepSpace(const std::vector<std::string>& gridTexts, const SweepOptions& o) {
  try {
    return sweepSpace(o.map.settings.parameters, gridTexts, o.ties);
  } catch (const SweepSpaceError& e) {
    const std::string what = e.what();
    if (e.axis) throw UsageError("--grid " + what);
    throw UsageError(what.rfind("--tie", 0) == 0 ? what : "--grid: " + what);
  }
}

std::pair<std::size_t, std::size_t> parseShard(const std::string& text) {
  const auto slash = text.find('/');
  std::size_t i = 0, n = 0;
  auto read = [](const std::string& t, std::size_t& v) {
    const char* end = t.data() + t.size();
    const auto [ptr, ec] = std::from_chars(t.data(), end, v);
    return !t.empty() && ec == std::errc() && ptr == end;
  };
  if (slash == std::string::npos || !read(text.substr(0, slash), i) ||
      !read(text.substr(slash + 1), n) || n == 0 || i >= n || n > 1000000)
    throw UsageError("--shard expects I/N with 0 <= I < N (e.g. 0/4), got '" + text + "'");
  return {i, n};
}

}  // namespace sg::cli
