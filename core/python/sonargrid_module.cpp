// SPDX-License-Identifier: BSD-3-Clause
// `import sonargrid` (docs/python.md): the core's readers, mapping, scoring, goodness measures,
// parameter declarations and sweeps for Python, with numpy arrays for the map's layers. Every
// function calls the same core code as `sonargrid-cli`, so a value here equals the CLI's JSON for
// the same settings; the dictionaries use the CLI's JSON keys. The GIL is released while a log is
// read, mapped, scored or swept, and the thread policy (concurrency.h) applies: `threads=` sets it
// for one call, set_threads() for the process.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "declarations.h"
#include "sonargrid/base/atomic_file.h"
#include "sonargrid/base/concurrency.h"
#include "sonargrid/base/log_error.h"
#include "sonargrid/data/dataset.h"
#include "sonargrid/data/scan_poses.h"
#include "sonargrid/engine/mapper.h"
#include "sonargrid/engine/sensor_model.h"
#include "sonargrid/engine/update_rule.h"
#include "sonargrid/export/map_export.h"
#include "sonargrid/forward/catalog.h"
#include "sonargrid/forward/forward_em.h"
#include "sonargrid/io/csv_log.h"
#include "sonargrid/io/log_reader.h"
#include "sonargrid/io/start_pose.h"
#include "sonargrid/io/text_lines.h"
#include "sonargrid/metrics/derivative_noise.h"
#include "sonargrid/metrics/map_entropy.h"
#include "sonargrid/metrics/reference_score.h"
#include "sonargrid/metrics/two_run_comparison.h"
#include "sonargrid/metrics/vsdns.h"
#include "sonargrid/reference/read_reference.h"
#include "sonargrid/sweep/set_evaluation.h"
#include "sonargrid/sweep/sweep_grid.h"
#include "sonargrid/sweep/sweep_metrics.h"

namespace py = pybind11;

namespace sg::python {
namespace {

// Never thrown: the type py::exception<> needs to make the module's exception classes.
struct ErrorClass : std::exception {};

// The module's exception classes (set up in PYBIND11_MODULE; they live as long as the module).
PyObject* gError = nullptr;
PyObject* gLogError = nullptr;
PyObject* gParameterError = nullptr;

// A read log: shared, never changed, so that maps and slices keep it alive without copies.
struct Log {
  std::shared_ptr<const Dataset> data;
  std::string path;  // the file it came from (for messages)
};

// A built map with what made it: goodness() maps the log again with the VSDNS observer on the
// same grid, and the layers' arrays keep this object alive instead of copying.
struct Map {
  OccupancyMap map;
  std::shared_ptr<const Dataset> log;
  std::string logPath;
  MapperSettings settings;
  double until = std::numeric_limits<double>::infinity();
  std::size_t readings = 0;
};

struct Reference {
  ReferenceMap reference;
  std::string path;
};

// Sets the thread policy for one call when `threads` is given.
class ThreadsFor {
 public:
  explicit ThreadsFor(const std::optional<unsigned>& threads) {
    if (!threads) return;
    if (*threads < 1 || *threads > kMaxThreads)
      throw py::value_error("threads must be a whole number from 1 to " +
                            std::to_string(kMaxThreads) + ", got " + std::to_string(*threads));
    scoped_.emplace(*threads);
  }

 private:
  std::optional<ScopedThreadCount> scoped_;
};

// A str or any path-like object (pathlib.Path), as open() takes it.
std::string pathOf(const py::object& path) {
  const py::object text = py::module_::import("os").attr("fspath")(path);
  if (!py::isinstance<py::str>(text))
    throw py::type_error("a path must be a str or a path-like object of str, not bytes");
  return text.cast<std::string>();
}

PoseSource poseOf(const std::string& pose) {
  if (pose == "odom") return PoseSource::Odometry;
  if (pose == "truth") return PoseSource::Truth;
  throw py::value_error("pose takes 'odom' or 'truth', got '" + pose + "'");
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// The model and rule checked and their parameters at default, then `params` set on them by name
// (ParameterError naming the parameter and its range otherwise): what `--model --rule --set` do.
MapperSettings settingsOf(const std::string& model, const std::string& rule,
                          const std::string& pose, const py::kwargs& params) {
  // The inverse models with their rules, and the forward model with EM (docs/forward-model.md).
  const std::vector<std::string> models = forward::mapModelNames();
  const std::vector<std::string> rules = forward::mapRuleNames();
  if (std::find(models.begin(), models.end(), model) == models.end())
    throw py::value_error("unknown model '" + model + "'; choose one of " + joined(models));
  if (std::find(rules.begin(), rules.end(), rule) == rules.end())
    throw py::value_error("unknown rule '" + rule + "'; choose one of " + joined(rules));
  const Compatibility c = forward::mapCompatibility(model, rule);
  if (!c.allowed)
    throw py::value_error("model '" + model + "' cannot be used with rule '" + rule +
                          "': " + c.reason);
  MapperSettings s;
  s.model = model;
  s.rule = rule;
  s.pose = poseOf(pose);
  s.parameters = forward::mapDefaultParameters(model, rule);
  for (const auto& [key, value] : params) {
    const std::string name = py::str(key);
    if (!py::isinstance<py::int_>(value) && !py::isinstance<py::float_>(value) &&
        !py::isinstance<py::bool_>(value))
      throw py::type_error("parameter '" + name + "' takes a number, got " +
                           std::string(py::str(py::type::of(value).attr("__name__"))));
    s.parameters.set(name, value.cast<double>());
  }
  return s;
}

GridSpec fittingGridOf(const Dataset& data, PoseSource pose, double cell, const std::string& path) {
  if (!(cell >= 0.001 && cell <= 10.0))
    throw py::value_error("cell must lie in [0.001, 10] metres, got " + std::to_string(cell));
  try {
    return data.fittingGrid(pose, cell);
  } catch (const GridLimitError& e) {
    throw e.inFile(path);
  }
}

// Maps `log` on `grid` as `sonargrid-cli map` does (command_map.cpp's buildMap).
OccupancyMap buildMap(const Dataset& data, const std::string& path, const MapperSettings& settings,
                      const GridSpec& grid, double until, FootprintObserver* observer,
                      std::size_t* readings) {
  if (settings.pose == PoseSource::Truth && !anyScanHasPose(data, PoseSource::Truth))
    throw MapperError(path + ": " + kNoTruePose + "; map with pose='odom'");
  if (forward::isForwardModel(settings.model)) {
    // EM over the whole log (docs/forward-model.md); no per-reading footprints to observe.
    if (observer)
      throw MapperError(path +
                        ": VSDNS replays an inverse model's evidence; the forward model "
                        "learns its map by EM and has none");
    try {
      forward::EmResult em = forward::runEm(forward::beamsOf(data, settings.pose, until), grid,
                                            forward::settingsOf(settings.parameters));
      if (readings) *readings = em.readings;
      return std::move(em.map);
    } catch (const forward::ForwardError& e) {
      throw MapperError(path + ": " + e.what());
    }
  }
  try {
    Mapper mapper(data.ring, grid, settings);
    mapper.setObserver(observer);
    mapper.mapDataset(data, until);
    if (readings) *readings = mapper.readingsIntegrated();
    return mapper.snapshot();
  } catch (const MapperError& e) {
    throw MapperError(path + ": " + e.what());
  }
}

py::object orNone(const std::optional<double>& v) {
  return v ? py::object(py::float_(*v)) : py::object(py::none());
}

// ---------------------------------------------------------------------------------------------
// Logs

py::array_t<double> poseArray(const std::vector<const Pose2D*>& poses) {
  py::array_t<double> out({static_cast<py::ssize_t>(poses.size()), py::ssize_t{3}});
  auto a = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const auto k = static_cast<py::ssize_t>(i);
    if (poses[i] == nullptr) {
      a(k, 0) = a(k, 1) = a(k, 2) = std::numeric_limits<double>::quiet_NaN();
    } else {
      a(k, 0) = poses[i]->x();
      a(k, 1) = poses[i]->y();
      a(k, 2) = poses[i]->heading;
    }
  }
  return out;
}

Log readLogPy(const py::object& file, const std::optional<std::string>& format, bool lenient,
              const std::optional<py::object>& robot, const std::optional<std::string>& columns,
              const std::optional<py::object>& poses,
              const std::optional<std::tuple<double, double, double>>& startPose) {
  const std::string path = pathOf(file);
  LogOptions o;
  if (format && !parseLogFormat(*format, o.format))
    throw py::value_error("format takes auto, sglog, carmen, player or csv, got '" + *format + "'");
  o.lenient = lenient;
  if (robot) {
    SonarRing ring;
    const std::string name = pathOf(*robot);
    if (SonarRing::preset(name, ring))
      o.ring = ring;
    else
      o.ring = readSonarGeometry(name);  // LogError naming the file when it is no geometry
  }
  if (columns) {
    try {
      o.csv = parseCsvLayout(*columns);
    } catch (const std::invalid_argument& e) {
      throw py::value_error(std::string("columns: ") + e.what());
    }
  }
  if (poses) {
    if (!columns) throw py::value_error("poses= needs columns= (it describes CSV logs)");
    o.posesPath = pathOf(*poses);
  }
  if (startPose) {
    // As --start-pose: metres, metres, degrees.
    const auto [x, y, degrees] = *startPose;
    std::string why;
    o.startPose =
        parseStartPose(text::number(x) + "," + text::number(y) + "," + text::number(degrees), &why);
    if (!o.startPose) throw py::value_error("start_pose: " + why);
  }
  auto data = std::make_shared<Dataset>();
  {
    py::gil_scoped_release release;
    *data = readLog(path, o);
  }
  return Log{std::move(data), path};
}

Log logBetween(const Log& log, double from, double to) {
  auto part = std::make_shared<Dataset>();
  part->name = log.data->name;
  part->ring = log.data->ring;
  for (const Scan& s : log.data->scans)
    if (s.time >= from && s.time < to) part->scans.push_back(s);
  return Log{std::move(part), log.path};
}

py::dict scanDict(const Scan& s) {
  py::dict d;
  d["time"] = s.time;
  d["odometry"] = py::make_tuple(s.odometry.x(), s.odometry.y(), s.odometry.heading);
  d["truth"] = s.truth ? py::object(py::make_tuple(s.truth->x(), s.truth->y(), s.truth->heading))
                       : py::object(py::none());
  py::list readings;
  for (const Reading& r : s.readings) readings.append(py::make_tuple(r.sonar, r.range, r.time));
  d["readings"] = readings;
  return d;
}

// ---------------------------------------------------------------------------------------------
// Maps

// A numpy view of `values` (height × width, row 0 at the grid's lowest y) that keeps `owner` alive.
template <class T>
py::array gridView(const GridSpec& spec, const T* values, py::handle owner,
                   const py::dtype& dtype) {
  py::array view(
      dtype, {static_cast<py::ssize_t>(spec.height), static_cast<py::ssize_t>(spec.width)},
      {static_cast<py::ssize_t>(sizeof(T)) * spec.width, static_cast<py::ssize_t>(sizeof(T))},
      values, owner);
  view.attr("setflags")(py::arg("write") = false);  // the map is an immutable snapshot
  return view;
}

template <class T>
py::array_t<T> gridCopy(const GridSpec& spec, const std::vector<T>& values) {
  py::array_t<T> out({static_cast<py::ssize_t>(spec.height), static_cast<py::ssize_t>(spec.width)});
  if (!values.empty()) std::memcpy(out.mutable_data(), values.data(), values.size() * sizeof(T));
  return out;
}

Map mapPy(const Log& log, const std::string& model, const std::string& rule, double cell,
          const std::string& pose, std::optional<unsigned> threads, std::optional<double> until,
          const py::kwargs& params) {
  Map m;
  m.settings = settingsOf(model, rule, pose, params);
  m.log = log.data;
  m.logPath = log.path;
  if (until) m.until = *until;
  const ThreadsFor policy(threads);
  const GridSpec grid = fittingGridOf(*log.data, m.settings.pose, cell, log.path);
  {
    py::gil_scoped_release release;
    m.map = buildMap(*log.data, log.path, m.settings, grid, m.until, nullptr, &m.readings);
  }
  return m;
}

py::dict parametersOf(const ParameterSet& set) {
  py::dict d;
  for (const ParameterSpec& s : set.specs()) d[py::str(s.name)] = set.get(s.name);
  return d;
}

// ---------------------------------------------------------------------------------------------
// Scores and goodness

ScoreOptions scoreOptions(const std::optional<std::vector<std::string>>& metrics, int pairs,
                          std::uint64_t seed, const std::string& iopWeight,
                          double filledThreshold) {
  ScoreOptions o;
  if (metrics) {
    std::string list;
    for (const std::string& m : *metrics) list += (list.empty() ? "" : ",") + m;
    try {
      o.metrics = parseMetricList(list);
    } catch (const std::invalid_argument& e) {
      throw py::value_error(std::string("metrics: ") + e.what());
    }
  }
  if (pairs < 0 || pairs > 1'000'000)
    throw py::value_error("pairs must lie in [0, 1000000], got " + std::to_string(pairs));
  o.pairs = pairs;
  o.seed = seed;
  if (!parseIopWeight(iopWeight, o.iop.weight))
    throw py::value_error("iop_weight takes 'evidence' or 'level', got '" + iopWeight + "'");
  if (!(filledThreshold >= 0.0 && filledThreshold <= 15.0))
    throw py::value_error("filled_threshold must lie in [0, 15]");
  o.iop.filledThreshold = filledThreshold;
  return o;
}

// cells=: None (every cell), a boolean array of the map's shape, or a list of maps whose commonly
// observed cells are scored (compare --cells common).
std::vector<std::uint8_t> cellMaskOf(const Map& map, const py::object& cells) {
  if (cells.is_none()) return {};
  if (py::isinstance<py::list>(cells) || py::isinstance<py::tuple>(cells)) {
    std::vector<const OccupancyMap*> maps{&map.map};
    for (const py::handle h : cells) maps.push_back(&h.cast<const Map&>().map);
    return commonObservedCells(maps, 0);
  }
  const auto mask = py::array_t<bool, py::array::c_style | py::array::forcecast>::ensure(cells);
  if (!mask) throw py::type_error("cells takes None, a boolean array or a list of maps");
  const GridSpec& g = map.map.spec;
  if (mask.ndim() != 2 || mask.shape(0) != g.height || mask.shape(1) != g.width)
    throw py::value_error("cells must have the map's shape (" + std::to_string(g.height) + ", " +
                          std::to_string(g.width) + ")");
  std::vector<std::uint8_t> out(g.cellCount());
  const bool* data = mask.data();
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = data[i] ? 1 : 0;
  return out;
}

py::dict scorePy(const Map& map, const Reference& reference, const py::object& cells,
                 const std::optional<std::vector<std::string>>& metrics, int pairs,
                 std::uint64_t seed, const std::string& iopWeight, double filledThreshold,
                 std::optional<unsigned> threads) {
  ScoreOptions o = scoreOptions(metrics, pairs, seed, iopWeight, filledThreshold);
  o.cellMask = cellMaskOf(map, cells);
  const ThreadsFor policy(threads);
  ReferenceScore s;
  {
    py::gil_scoped_release release;
    try {
      s = scoreAgainstReference(map.map, reference.reference, o);
    } catch (const MetricsError& e) {
      throw MetricsError(reference.path + ": " + e.what());
    }
  }
  // The keys and order of `sonargrid-cli score --json` (docs/cli.md).
  py::dict out;
  for (const Metric m : allMetrics()) {
    if (s.computed.count(m) == 0) continue;
    out[metricJsonKey(m)] = orNone(s.value(m));
  }
  out["cells_evaluated"] = s.cellsEvaluated;
  if (!s.warnings.empty()) out["warnings"] = s.warnings;
  return out;
}

py::dict goodnessPy(const Map& map, const std::optional<Log>& secondLog,
                    std::optional<unsigned> threads) {
  if (!map.log)
    throw py::value_error("goodness() needs a map made by sonargrid.map() (it maps the log again)");
  const ThreadsFor policy(threads);
  VsdnsAccumulator vsdns;
  OccupancyMap first;
  std::optional<TwoRunComparison> twoRuns;
  {
    py::gil_scoped_release release;
    // As `sonargrid-cli goodness`: with a second run, both runs on one grid over both.
    GridSpec grid = map.map.spec;
    if (secondLog) {
      const GridSpec other =
          fittingGridOf(*secondLog->data, map.settings.pose, grid.cellSize, secondLog->path);
      try {
        grid = gridOverRuns(grid, other);
      } catch (const GridLimitError& e) {
        throw e.inFile(map.logPath + " and " + secondLog->path);
      }
    }
    first = buildMap(*map.log, map.logPath, map.settings, grid, map.until, &vsdns, nullptr);
    if (secondLog) {
      const OccupancyMap second = buildMap(*secondLog->data, secondLog->path, map.settings, grid,
                                           map.until, nullptr, nullptr);
      twoRuns = compareTwoRuns(first, second);
    }
  }
  const VsdnsAccumulator::Result spread = vsdns.result();
  const DerivativeNoise noise = derivativeNoise(first);
  const MapEntropy entropy = mapEntropy(first);
  // The keys and order of `sonargrid-cli goodness --json`.
  py::dict out;
  out["vsdns"] = orNone(spread.vsdns);
  out["derivative_noise"] = noise.sum;
  out["derivative_noise_mean"] = orNone(noise.mean);
  out["entropy_bits"] = entropy.observedBits;
  out["entropy_bits_mean"] = orNone(entropy.meanBits);
  out["entropy_bits_grid"] = entropy.totalBits;
  out["two_run_positive"] = twoRuns ? py::object(py::int_(twoRuns->positive)) : py::none();
  out["two_run_negative"] = twoRuns ? py::object(py::int_(twoRuns->negative)) : py::none();
  return out;
}

// ---------------------------------------------------------------------------------------------
// Sweeps

// Rows as `sonargrid-cli sweep` writes them to its CSV: the set's index, every parameter, then
// the metrics' columns (None where a metric is undefined).
py::list sweepPy(const Log& log, const std::string& model, const std::string& rule,
                 const std::vector<std::string>& grid, const std::vector<std::string>& ties,
                 const std::vector<std::string>& metrics, const std::optional<Reference>& reference,
                 const std::optional<Log>& secondLog, double cell, const std::string& pose,
                 std::optional<unsigned> threads, const py::kwargs& params) {
  const MapperSettings base = settingsOf(model, rule, pose, params);
  if (metrics.empty())
    throw py::value_error(
        "give at least one metric (vsdns, derivative, entropy, two-run, iop, ...)");
  const std::vector<std::string> canonical = parseSweepMetrics(metrics);
  for (const std::string& m : canonical) {
    if (isReferenceMetric(m) && !reference)
      throw py::value_error("metric " + m + " compares with a reference map; give reference=");
    if (m == "two-run" && !secondLog)
      throw py::value_error("metric two-run compares two runs; give second_log=");
  }
  std::vector<SweepTie> parsedTies;
  for (const std::string& t : ties) parsedTies.push_back(parseSweepTie(t, base.parameters));
  const SweepSpace space = sweepSpace(base.parameters, grid, parsedTies);

  SetEvaluationInput input;
  input.run = log.data.get();
  input.secondRun = secondLog ? secondLog->data.get() : nullptr;
  input.reference = reference ? &reference->reference : nullptr;
  input.settings.model = model;
  input.settings.rule = rule;
  input.settings.pose = base.pose;
  input.measures = measuresOf(canonical);
  input.settings.grid = fittingGridOf(*log.data, base.pose, cell, log.path);
  if (secondLog) {
    const GridSpec other = fittingGridOf(*secondLog->data, base.pose, cell, secondLog->path);
    try {
      input.settings.grid = gridOverRuns(input.settings.grid, other);
    } catch (const GridLimitError& e) {
      throw e.inFile(log.path + " and " + secondLog->path);
    }
  }
  const ThreadsFor policy(threads);
  std::vector<std::vector<std::optional<double>>> values(space.sets.size());
  std::vector<std::size_t> indices(space.sets.size());
  for (std::size_t i = 0; i < indices.size(); ++i) indices[i] = i;
  {
    py::gil_scoped_release release;
    evaluateSets(input, space.sets, indices, [&](std::size_t k, const SetEvaluation& e) {
      values[k] = metricValues(canonical, e);
    });
  }
  const std::vector<std::string> columns = metricColumns(canonical);
  py::list rows;
  for (std::size_t i = 0; i < space.sets.size(); ++i) {
    py::dict row;
    row["index"] = i;
    for (const ParameterSpec& s : space.sets[i].specs())
      row[py::str(s.name)] = space.sets[i].get(s.name);
    for (std::size_t c = 0; c < columns.size(); ++c)
      row[py::str(columns[c])] = orNone(values[i][c]);
    rows.append(row);
  }
  return rows;
}

}  // namespace
}  // namespace sg::python

PYBIND11_MODULE(_core, m) {
  using namespace sg;
  using namespace sg::python;
  m.doc() = "SonarGrid's core: sonar logs, occupancy-grid mapping, scores (docs/python.md)";

  // Errors carry the core's message (file, line, field). sonargrid.Error is the base of the
  // module's own; the classes are made here and raised by the translator below alone.
  gError = py::exception<ErrorClass>(m, "Error").ptr();
  gLogError = py::exception<ErrorClass>(m, "LogError", gError).ptr();
  gParameterError = py::exception<ErrorClass>(m, "ParameterError", gError).ptr();
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const py::builtin_exception&) {
      throw;  // ValueError, TypeError, IndexError...: pybind11's own translator raises them
    } catch (const py::error_already_set&) {
      throw;
    } catch (const LogError& e) {
      PyErr_SetString(gLogError, e.what());
    } catch (const GridLimitError& e) {
      const std::string text = e.file().empty() ? e.what() : e.file() + ": " + e.message();
      PyErr_SetString(gError, text.c_str());
    } catch (const ParameterError& e) {
      PyErr_SetString(gParameterError, e.what());
    } catch (const SweepSpecError& e) {
      PyErr_SetString(gParameterError, e.what());
    } catch (const ThreadCountError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const FileWriteError& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    } catch (const std::runtime_error& e) {
      PyErr_SetString(gError, e.what());  // MapperError, MetricsError, the core's other errors
    }
  });

  py::class_<Log>(m, "Log", "A sonar log: scans in time order, each with its poses and readings")
      .def_property_readonly("name", [](const Log& l) { return l.data->name; })
      .def_property_readonly("path", [](const Log& l) { return l.path; })
      .def("__len__", [](const Log& l) { return l.data->scans.size(); })
      .def_property_readonly("reading_count", [](const Log& l) { return l.data->readingCount(); })
      .def_property_readonly("has_truth", [](const Log& l) { return l.data->hasTruth(); })
      .def_property_readonly(
          "times",
          [](const Log& l) {
            py::array_t<double> t(static_cast<py::ssize_t>(l.data->scans.size()));
            double* out = t.mutable_data();
            for (const Scan& s : l.data->scans) *out++ = s.time;
            return t;
          })
      .def_property_readonly("odometry",
                             [](const Log& l) {
                               std::vector<const Pose2D*> p;
                               for (const Scan& s : l.data->scans) p.push_back(&s.odometry);
                               return poseArray(p);
                             })
      .def_property_readonly("truth",
                             [](const Log& l) {
                               std::vector<const Pose2D*> p;
                               for (const Scan& s : l.data->scans)
                                 p.push_back(s.truth ? &*s.truth : nullptr);
                               return poseArray(p);
                             })
      .def_property_readonly(
          "readings",
          [](const Log& l) {
            py::array_t<double> out(
                {static_cast<py::ssize_t>(l.data->readingCount()), py::ssize_t{4}});
            auto a = out.mutable_unchecked<2>();
            py::ssize_t k = 0;
            for (std::size_t i = 0; i < l.data->scans.size(); ++i) {
              for (const Reading& r : l.data->scans[i].readings) {
                a(k, 0) = static_cast<double>(i);
                a(k, 1) = r.sonar;
                a(k, 2) = r.range;
                a(k, 3) = r.time;
                ++k;
              }
            }
            return out;
          },
          "(readings, 4) array: scan index, sonar, range in metres (inf: no echo), time")
      .def_property_readonly("ring",
                             [](const Log& l) {
                               const SonarRing& r = l.data->ring;
                               std::vector<const Pose2D*> p;
                               for (const SonarMount& s : r.sonars) p.push_back(&s.pose);
                               py::dict d;
                               d["robot"] = r.robot;
                               d["aperture"] = r.apertureRad;
                               d["min_range"] = r.minRange;
                               d["max_range"] = r.maxRange;
                               d["sonars"] = poseArray(p);
                               return d;
                             })
      .def("__getitem__",
           [](const Log& l, py::ssize_t i) {
             const auto n = static_cast<py::ssize_t>(l.data->scans.size());
             if (i < 0) i += n;
             if (i < 0 || i >= n) throw py::index_error("scan index out of range");
             return scanDict(l.data->scans[static_cast<std::size_t>(i)]);
           })
      .def("__getitem__",
           [](const Log& l, const py::slice& s) {
             if (!s.attr("step").is_none())
               throw py::value_error("a log is sliced by time in seconds, without a step");
             const py::object a = s.attr("start"), b = s.attr("stop");
             return logBetween(
                 l, a.is_none() ? -std::numeric_limits<double>::infinity() : a.cast<double>(),
                 b.is_none() ? std::numeric_limits<double>::infinity() : b.cast<double>());
           })
      .def("between", &logBetween, py::arg("start"), py::arg("stop"),
           "The scans with start <= time < stop, as a new log")
      .def("__repr__", [](const Log& l) {
        return "<sonargrid.Log '" + l.path + "': " + std::to_string(l.data->scans.size()) +
               " scans, " + std::to_string(l.data->readingCount()) + " readings>";
      });

  py::class_<Map>(m, "Map", "A built occupancy grid (an immutable snapshot)")
      .def_property_readonly(
          "p", [](const Map& mp) { return gridCopy(mp.map.spec, mp.map.probability.values()); },
          "p(occupied) per cell, float64 (height, width), row 0 at the lowest y")
      .def_property_readonly(
          "levels",
          [](py::object self) {
            const Map& mp = self.cast<const Map&>();
            return gridView(mp.map.spec, mp.map.level.data(), self, py::dtype::of<std::uint8_t>());
          },
          "the 16 certainty levels 0..15, uint8 (height, width), sharing the map's memory")
      .def_property_readonly(
          "observed",
          [](py::object self) {
            const Map& mp = self.cast<const Map&>();
            return gridView(mp.map.spec, mp.map.observed.data(), self, py::dtype::of<bool>());
          },
          "cells that a reading wrote, bool (height, width), sharing the map's memory")
      .def_property_readonly("filled",
                             [](const Map& mp) {
                               const std::vector<std::uint8_t> f = mp.map.filled.values();
                               py::array_t<bool> out({static_cast<py::ssize_t>(mp.map.spec.height),
                                                      static_cast<py::ssize_t>(mp.map.spec.width)});
                               bool* o = out.mutable_data();
                               for (std::size_t i = 0; i < f.size(); ++i) o[i] = f[i] != 0;
                               return out;
                             })
      .def_property_readonly("origin",
                             [](const Map& mp) {
                               return py::make_tuple(mp.map.spec.origin.x(),
                                                     mp.map.spec.origin.y());
                             })
      .def_property_readonly("cell", [](const Map& mp) { return mp.map.spec.cellSize; })
      .def_property_readonly("width", [](const Map& mp) { return mp.map.spec.width; })
      .def_property_readonly("height", [](const Map& mp) { return mp.map.spec.height; })
      .def_property_readonly("model", [](const Map& mp) { return mp.settings.model; })
      .def_property_readonly("rule", [](const Map& mp) { return mp.settings.rule; })
      .def_property_readonly("params",
                             [](const Map& mp) { return parametersOf(mp.settings.parameters); })
      .def_property_readonly("readings", [](const Map& mp) { return mp.readings; })
      .def_property_readonly("cells_filled", [](const Map& mp) { return mp.map.filledCount(); })
      .def_property_readonly("cv_histogram", [](const Map& mp) { return mp.map.levelHistogram(); })
      .def(
          "to_png",
          [](const Map& mp, const py::object& file, bool legend, int scale) {
            const std::string path = pathOf(file);
            if (scale < 1 || scale > 64) throw py::value_error("scale must lie in [1, 64]");
            PngOptions o;
            o.legend = legend;
            o.scale = scale;
            py::gil_scoped_release release;
            writeMapPng(mp.map, path, o);
          },
          py::arg("path"), py::arg("legend") = false, py::arg("scale") = 1,
          "Writes the map as a PNG coloured by the 16 levels (as `map --png`)")
      .def(
          "to_ros",
          [](const Map& mp, const py::object& file) {
            const std::string basename = pathOf(file);
            py::gil_scoped_release release;
            writeRosMap(mp.map, basename);
          },
          py::arg("path"), "Writes PATH.yaml and PATH.pgm for ROS map_server (as `map --ros-map`)")
      .def("__repr__", [](const Map& mp) {
        return "<sonargrid.Map " + mp.settings.model + " x " + mp.settings.rule + ": " +
               std::to_string(mp.map.spec.width) + " x " + std::to_string(mp.map.spec.height) +
               " cells of " + std::to_string(mp.map.spec.cellSize) + " m>";
      });

  py::class_<Reference>(m, "Reference", "A reference map (JSON, ArMap .map or ROS map_server)")
      .def_property_readonly("path", [](const Reference& r) { return r.path; })
      .def_property_readonly("objects",
                             [](const Reference& r) {
                               py::list out;
                               for (const ReferenceObject& o : r.reference.objects) {
                                 py::list corners;
                                 for (std::size_t c = 0; c < o.corners.size(); ++c) {
                                   const Position p = r.reference.cornerMetres(o, c);
                                   corners.append(py::make_tuple(p.x(), p.y()));
                                 }
                                 py::dict d;
                                 d["name"] = o.name;
                                 d["closed"] = o.closed;
                                 d["corners"] = corners;
                                 out.append(d);
                               }
                               return out;
                             })
      .def("__repr__", [](const Reference& r) {
        return "<sonargrid.Reference '" + r.path +
               "': " + std::to_string(r.reference.objects.size()) + " objects>";
      });

  m.def("read_log", &readLogPy, py::arg("path"), py::kw_only(), py::arg("format") = py::none(),
        py::arg("lenient") = false, py::arg("robot") = py::none(), py::arg("columns") = py::none(),
        py::arg("poses") = py::none(), py::arg("start_pose") = py::none(),
        "Reads a sonar log (.sglog, CARMEN, Player, CSV); sonargrid.LogError names file, line and "
        "field of malformed input. start_pose=(x, y, degrees): the robot's pose at the first scan "
        "in the reference's frame, where the odometry is moved (as --start-pose)");
  m.def("map", &mapPy, py::arg("log"), py::kw_only(), py::arg("model"), py::arg("rule"),
        py::arg("cell") = 0.05, py::arg("pose") = "odom", py::arg("threads") = py::none(),
        py::arg("until") = py::none(),
        "Maps the log with a model and rule; further keywords set parameters by name (as --set)");
  m.def(
      "read_reference",
      [](const py::object& file) {
        Reference r;
        r.path = pathOf(file);
        py::gil_scoped_release release;
        r.reference = readReference(r.path);
        return r;
      },
      py::arg("path"));
  m.def("score", &scorePy, py::arg("map"), py::arg("reference"), py::kw_only(),
        py::arg("cells") = py::none(), py::arg("metrics") = py::none(),
        py::arg("pairs") = kDefaultPathPairs, py::arg("seed") = kDefaultPathSeed,
        py::arg("iop_weight") = "evidence", py::arg("filled_threshold") = 0.0,
        py::arg("threads") = py::none(),
        "The map against a reference: a dict with the keys of `score --json`");
  m.def("goodness", &goodnessPy, py::arg("map"), py::kw_only(), py::arg("second_log") = py::none(),
        py::arg("threads") = py::none(),
        "Goodness without a reference: a dict with the keys of `goodness --json`");
  m.def("models", &modelsPy, "The declared models, rules and parameters (as `models --json`)");
  m.def("_sweep_rows", &sweepPy, py::arg("log"), py::kw_only(), py::arg("model"), py::arg("rule"),
        py::arg("grid"), py::arg("ties") = std::vector<std::string>{},
        py::arg("metrics") = std::vector<std::string>{"vsdns"}, py::arg("reference") = py::none(),
        py::arg("second_log") = py::none(), py::arg("cell") = 0.05, py::arg("pose") = "odom",
        py::arg("threads") = py::none());
  m.def(
      "set_threads", [](unsigned n) { setThreadCount(n); }, py::arg("count"),
      "Sets the thread policy's explicit count (0: back to SONARGRID_THREADS or the CPUs granted)");
  m.def(
      "threads", []() { return threadCount(); }, "The thread count the policy gives now");
}
