// SPDX-License-Identifier: GPL-3.0-or-later
#include "remap_controller.h"

#include <QMetaObject>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <functional>
#include <optional>

#include "sonargrid/data/scan_poses.h"
#include "sonargrid/forward/catalog.h"
#include "sonargrid/forward/forward_em.h"

namespace sg::ui {

// The mapper of the last complete run, kept for continuing it forward in time. When the log's
// readings are in time order, a batch run to `until` has applied exactly the readings of the log
// up to `until`, a prefix of the log; a batch run to a later time applies that prefix and then the
// readings in (until, later], in log order, which is what continuing the mapper does. A live log
// adds scans after the first `scans`: their readings up to the new time follow in the same order.
struct RemapController::WarmMapper {
  std::shared_ptr<const Dataset> data;
  std::shared_ptr<const ScanSource> source;
  bool ordered = false;  // the readings' times never decrease along the log
  std::unique_ptr<Mapper> mapper;
  MapperSettings settings;
  double cellSize = 0.0;
  double until = 0.0;
  std::size_t nextScan = 0;        // the first scan holding a reading after `until`
  std::size_t scans = 0;           // of a live log: the scans there were when it was last mapped
  std::optional<GridSpec> ground;  // of a live log: the limits its map last had
};

// What one run maps, as it was when it was asked for.
struct RemapController::Request {
  std::shared_ptr<const ScanSource> source;
  bool live = false;  // on a growing grid
  MapperSettings settings;
  double cellSize = 0.05;
  double until = 0.0;
  std::shared_ptr<std::atomic<bool>> cancel;
  quint64 generation = 0;
  bool append = false;  // scansAppended(): clears appendWaiting_ when it starts
  std::function<void(const forward::EmProgress&)> progress;  // the forward model's EM
};

struct RemapController::Outcome {
  std::shared_ptr<const OccupancyMap> map;
  double ms = 0.0;
  bool interrupted = false;
  bool incremental = false;
  QString error;
};

namespace {

bool readingsInTimeOrder(const Dataset& data) {
  double last = -std::numeric_limits<double>::infinity();
  for (const Scan& scan : data.scans)
    for (const Reading& r : scan.readings) {
      if (r.time < last) return false;
      last = r.time;
    }
  return true;
}

// A mapper for the log's fitting grid at `cellSize`: what a full run and a preview both start from.
std::unique_ptr<Mapper> mapperFor(const Dataset& data, const MapperSettings& settings,
                                  double cellSize) {
  return std::make_unique<Mapper>(data.ring, data.fittingGrid(settings.pose, cellSize), settings);
}

template <class Scans>
std::size_t firstScanAfter(const Scans& scans, std::size_t count, double until, std::size_t from) {
  for (std::size_t i = from; i < count; ++i)
    for (const Reading& r : scans[i].readings)
      if (r.time > until) return i;
  return count;
}

// Scan `scan` with only its readings in (after, until].
Scan readingsBetween(const Scan& scan, double after, double until) {
  Scan part;
  part.time = scan.time;
  part.odometry = scan.odometry;
  part.truth = scan.truth;
  for (const Reading& r : scan.readings)
    if (r.time > after && r.time <= until) part.readings.push_back(r);
  return part;
}

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

RemapController::RemapController(QObject* parent)
    : QObject(parent), warm_(std::make_shared<WarmMapper>()) {
  connect(&jobs_, &JobQueue::busyChanged, this, &RemapController::busyChanged);
}

RemapController::~RemapController() {
  if (cancelRunning_) cancelRunning_->store(true);
  jobs_.waitForDone();
}

void RemapController::adopt(std::shared_ptr<const ScanSource> source, bool live, double cellSize) {
  source_ = std::move(source);
  live_ = live;
  cellSize_ = cellSize;
  previewMsPerReading_ = 0.0;  // another log or cell size: its previews' cost is not known yet
}

void RemapController::setSource(std::shared_ptr<const ScanSource> source, double cellSize) {
  const bool live = source && !source->complete();
  adopt(std::move(source), live, cellSize);
  remap();
}

void RemapController::start(std::shared_ptr<const ScanSource> source, double cellSize,
                            const MapperSettings& settings, double until) {
  const bool live = source && !source->complete();
  adopt(std::move(source), live, cellSize);
  settings_ = effective(settings);
  haveSettings_ = true;
  until_ = until;
  remap();
}

void RemapController::startLive(std::shared_ptr<const ScanSource> source, double cellSize,
                                const MapperSettings& settings, double until) {
  adopt(std::move(source), true, cellSize);
  settings_ = effective(settings);
  haveSettings_ = true;
  until_ = until;
  remap();
}

void RemapController::setDataset(std::shared_ptr<const Dataset> data, double cellSize) {
  setSource(data ? std::make_shared<const ScanSource>(std::move(data)) : nullptr, cellSize);
}

void RemapController::start(std::shared_ptr<const Dataset> data, double cellSize,
                            const MapperSettings& settings, double until) {
  start(data ? std::make_shared<const ScanSource>(std::move(data)) : nullptr, cellSize, settings,
        until);
}

MapperSettings RemapController::effective(const MapperSettings& settings) const {
  MapperSettings s = settings;
  s.precision = hasFastCells(s.model, s.rule) ? precision_ : Precision::Exact;
  return s;
}

bool RemapController::mapsWith(const MapperSettings& settings) const {
  return haveSettings_ && effective(settings) == settings_;
}

void RemapController::setPrecision(Precision precision) {
  if (precision == precision_) return;
  precision_ = precision;
  if (!haveSettings_) return;
  const MapperSettings now = effective(settings_);
  if (now == settings_) return;  // a pair whose cells are the same under both engines
  settings_ = now;
  remap();
}

void RemapController::setSettings(const MapperSettings& settings) {
  // Another model or rule costs another amount per reading: the next preview's stride starts from
  // the full map's cost again.
  if (settings.model != settings_.model || settings.rule != settings_.rule)
    previewMsPerReading_ = 0.0;
  settings_ = effective(settings);
  haveSettings_ = true;
  run(previewFactor_ > 1 && lastFullMs_ > previewAboveMs_);
}

void RemapController::setPreview(int factor, double aboveMs) {
  previewFactor_ = std::max(1, factor);
  previewAboveMs_ = aboveMs;
}

void RemapController::setPreviewBudget(double ms) {
  previewBudgetMs_ = std::max(0.0, ms);
}

// Readings of the log up to `until` (all of them for +infinity).
static std::size_t readingsUpTo(const Dataset& data, double until) {
  std::size_t n = 0;
  for (const Scan& scan : data.scans)
    for (const Reading& r : scan.readings) n += r.time <= until;
  return n;
}

int RemapController::previewStride() const {
  if (previewBudgetMs_ <= 0.0 || !source_) return 1;
  const std::shared_ptr<const Dataset> data = source_->view();
  if (!data) return 1;
  const double readings = static_cast<double>(readingsUpTo(*data, until_));
  if (readings <= 0.0) return 1;
  // Before any preview: cells `factor` times larger cost about 60 % of the full map on the bundled
  // logs at a factor of 2 (raschke-multi at 5 cm: 25 against 39 ms).
  const double perReading =
      previewMsPerReading_ > 0.0 ? previewMsPerReading_ : 0.6 * lastFullMs_ / readings;
  const double stride = std::ceil(readings * perReading / previewBudgetMs_);
  return static_cast<int>(std::clamp(stride, 1.0, double(kMaxPreviewStride)));
}

void RemapController::startPreview(quint64 generation,
                                   const std::shared_ptr<std::atomic<bool>>& cancel) {
  struct Preview {
    std::shared_ptr<const OccupancyMap> map;
    double ms = 0.0;
    double mappingMs = 0.0;  // the readings' own, without the grid's set-up and the snapshot
    std::size_t readings = 0;
  };
  const int stride = previewStride();
  jobs_.run<Preview>(
      cancel,
      [data = source_->view(), settings = settings_, cellSize = cellSize_ * previewFactor_,
       until = until_, stride, ground = previewGround_](const std::atomic<bool>* stop) {
        Preview p;
        const auto t0 = std::chrono::steady_clock::now();
        // The same ground as the full map (the log's fitting grid, kept for the next preview: it
        // reads every reading), so the view keeps its place.
        if (ground->data != data || ground->cellSize != cellSize || ground->pose != settings.pose) {
          ground->spec = data->fittingGrid(settings.pose, cellSize);
          ground->data = data;
          ground->cellSize = cellSize;
          ground->pose = settings.pose;
        }
        Mapper mapper(data->ring, ground->spec, settings);
        // One scan in `stride` of those the pose source places (with true poses, a scan without
        // one is left out of any map).
        Dataset thin;
        const Dataset* mapped = data.get();
        if (stride > 1) {
          thin.ring = data->ring;
          thin.scans.reserve(data->scans.size() / std::size_t(stride) + 1);
          std::size_t placed = 0;
          for (const Scan& scan : data->scans) {
            if (settings.pose == PoseSource::Truth && !scan.truth) continue;
            if (placed++ % std::size_t(stride) == 0) thin.scans.push_back(scan);
          }
          mapped = &thin;
        }
        const auto t1 = std::chrono::steady_clock::now();
        if (mapper.mapDataset(*mapped, until, stop)) {
          p.mappingMs = msSince(t1);
          p.map = std::make_shared<const OccupancyMap>(mapper.snapshot());
          p.ms = msSince(t0);
          p.readings = mapper.readingsIntegrated();
        }
        return p;
      },
      [this, generation, stride](JobOutcome<Preview> outcome) {
        // An error is the full run's to report; a superseded preview says nothing of the settings
        // or cells now in force.
        if (!outcome.value || !outcome.value->map || generation != generation_) return;
        if (outcome.value->readings > 0)
          previewMsPerReading_ = outcome.value->mappingMs / double(outcome.value->readings);
        emit previewed(outcome.value->map, outcome.value->ms, generation, stride);
      });
}

void RemapController::setUntil(double until) {
  until_ = until;
  remap();
}

void RemapController::remap() {
  run(false);
}

void RemapController::run(bool preview) {
  if (!source_ || !haveSettings_) return;
  if (cancelRunning_) cancelRunning_->store(true);
  auto cancel = std::make_shared<std::atomic<bool>>(false);
  cancelRunning_ = cancel;
  const quint64 generation = ++generation_;
  lastRemapGeneration_ = generation;
  // Previews are of loaded logs: a live map is continued, which is already quick. The forward
  // model's EM has none: a coarser grid is another EM problem, no quicker to read.
  const bool forwardModel = forward::isForwardModel(settings_.model);
  if (preview && !live_ && !forwardModel) startPreview(generation, cancel);  // queued first
  Request request{source_, live_, settings_, cellSize_, until_, cancel, generation, false, {}};
  if (forwardModel) {
    request.progress = [this, generation](const forward::EmProgress& p) {
      QMetaObject::invokeMethod(
          this,
          [this, p, generation] {
            emit emProgress(p.iteration, p.cap, p.logLikelihood, generation);
          },
          Qt::QueuedConnection);
    };
  }
  enqueue(std::move(request));
  emit started(generation);
}

void RemapController::stop() {
  if (cancelRunning_) cancelRunning_->store(true);
}

void RemapController::scansAppended() {
  if (!source_ || !live_ || !haveSettings_) return;
  // A queued append run takes the source's scans when it starts: these are among them.
  if (appendWaiting_.exchange(true)) return;
  // The running run's cancel flag: a re-map asked for later stops this run too.
  if (!cancelRunning_) cancelRunning_ = std::make_shared<std::atomic<bool>>(false);
  enqueue(Request{
      source_, true, settings_, cellSize_, until_, cancelRunning_, ++generation_, true, {}});
}

void RemapController::enqueue(Request request) {
  auto cancel = request.cancel;
  const quint64 generation = request.generation;
  const bool append = request.append;
  jobs_.run<Outcome>(
      std::move(cancel),
      [this, append] {
        // Its turn came: appends from now on need a run of their own (this one may be skipped).
        if (append) appendWaiting_.store(false);
      },
      [this, request = std::move(request), warm = warm_](const std::atomic<bool>*) {
        try {
          if (forward::isForwardModel(request.settings.model)) return mapForward(*warm, request);
          return request.live ? mapLive(*warm, request) : mapLoaded(*warm, request);
        } catch (...) {
          warm->mapper.reset();
          throw;
        }
      },
      [this, generation](JobOutcome<Outcome> outcome) {
        if (outcome.value) {
          finish(generation, *outcome.value);
        } else {
          Outcome o;
          // Superseded before it started: the warm mapper is unchanged.
          o.interrupted = outcome.skipped;
          o.error = outcome.error;
          finish(generation, o);
        }
      });
}

RemapController::Outcome RemapController::mapLoaded(WarmMapper& warm, const Request& request) {
  const std::shared_ptr<const Dataset> log = request.source->view();
  const Dataset& data = *log;
  const MapperSettings& settings = request.settings;
  const double until = request.until;
  if (settings.pose == PoseSource::Truth && !anyScanHasPose(data, PoseSource::Truth))
    throw MapperError(std::string(kNoTruePose) + "; map with odometry");
  Outcome out;
  const auto t0 = std::chrono::steady_clock::now();
  if (warm.data != log) {
    warm.mapper.reset();
    warm.source.reset();
    warm.data = log;
    warm.ordered = readingsInTimeOrder(data);
  }
  out.incremental = warm.mapper && warm.ordered && warm.cellSize == request.cellSize &&
                    warm.settings == settings && until >= warm.until;
  if (out.incremental) {
    for (std::size_t i = warm.nextScan; i < data.scans.size() && !out.interrupted; ++i) {
      const Scan& scan = data.scans[i];
      if (!scan.readings.empty() && scan.readings.front().time > until) break;
      if (request.cancel->load(std::memory_order_relaxed)) {
        out.interrupted = true;
        break;
      }
      // Only the readings the mapper has not seen yet: those after the previous time.
      warm.mapper->integrate(readingsBetween(scan, warm.until, until), until);
    }
  } else {
    warm.mapper.reset();
    auto mapper = mapperFor(data, settings, request.cellSize);
    out.interrupted = !mapper->mapDataset(data, until, request.cancel.get());
    warm.mapper = std::move(mapper);
  }
  if (out.interrupted) {
    warm.mapper.reset();
    return out;
  }
  // A continued map recomputes the rows its readings wrote; a new one is computed whole and
  // handed over without a copy.
  out.map = std::make_shared<const OccupancyMap>(out.incremental ? warm.mapper->liveMap()
                                                                 : warm.mapper->snapshot());
  out.ms = msSince(t0);
  warm.nextScan =
      firstScanAfter(data.scans, data.scans.size(), until, out.incremental ? warm.nextScan : 0);
  warm.settings = settings;
  warm.cellSize = request.cellSize;
  warm.until = until;
  return out;
}

RemapController::Outcome RemapController::mapForward(WarmMapper& warm, const Request& request) {
  if (request.live) {
    throw forward::ForwardError(
        "the forward model learns its map by EM over a whole log; map a live link with an inverse "
        "model, or record it and open the log");
  }
  const std::shared_ptr<const Dataset> log = request.source->view();
  const Dataset& data = *log;
  const MapperSettings& settings = request.settings;
  if (settings.pose == PoseSource::Truth && !anyScanHasPose(data, PoseSource::Truth))
    throw MapperError(std::string(kNoTruePose) + "; map with odometry");
  // The next inverse-model run starts afresh.
  warm.mapper.reset();
  warm.data.reset();
  warm.source.reset();
  Outcome out;
  const auto t0 = std::chrono::steady_clock::now();
  forward::EmResult em = forward::runEm(forward::beamsOf(data, settings.pose, request.until),
                                        data.fittingGrid(settings.pose, request.cellSize),
                                        forward::settingsOf(settings.parameters),
                                        request.cancel.get(), request.progress);
  if (em.cancelled) {
    out.interrupted = true;
    return out;
  }
  out.map = std::make_shared<const OccupancyMap>(std::move(em.map));
  out.ms = msSince(t0);
  return out;
}

RemapController::Outcome RemapController::mapLive(WarmMapper& warm, const Request& request) {
  const ScanPrefix scans = request.source->prefix();
  const MapperSettings& settings = request.settings;
  const double until = request.until;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Outcome out;
  const auto t0 = std::chrono::steady_clock::now();
  if (warm.source != request.source) {
    warm.mapper.reset();
    warm.data.reset();
    warm.ground.reset();
    warm.source = request.source;
  }
  // Continuing adds the readings after the mapped ones: a prefix of the log in log order when the
  // readings are in time order, or when every reading of the scans mapped so far was taken.
  out.incremental = warm.mapper && warm.cellSize == request.cellSize && warm.settings == settings &&
                    until >= warm.until && (scans.readingsInTimeOrder() || warm.until == kInf);
  if (!out.incremental) {
    // From the last limits when there are some for these cells (a live view keeps its ground),
    // else one cell at the first pose; append() grows it.
    GridSpec start;
    if (warm.ground && warm.ground->cellSize == request.cellSize) {
      start = *warm.ground;
    } else {
      const Position p = scans.empty() ? Position(0.0, 0.0) : scans[0].odometry.position;
      start = GridSpec::covering(p, p, request.cellSize, 0.0);
    }
    warm.mapper.reset();
    warm.mapper = std::make_unique<Mapper>(request.source->ring(), start, settings);
    warm.until = -kInf;
    warm.nextScan = 0;
    warm.scans = 0;
  }
  Mapper& mapper = *warm.mapper;
  const std::atomic<bool>* cancel = request.cancel.get();
  // The mapped scans' readings in (warm.until, until], then the new scans' up to `until`.
  std::vector<Scan> late;
  for (std::size_t i = warm.nextScan; i < warm.scans; ++i)
    late.push_back(readingsBetween(scans[i], warm.until, until));
  bool completed = mapper.append(late, until, cancel);
  for (const std::span<const Scan> part : scans.spans(warm.scans, scans.size())) {
    if (!completed) break;
    completed = mapper.append(part, until, cancel);
  }
  if (!completed) {
    out.interrupted = true;
    warm.mapper.reset();
    return out;
  }
  out.map = std::make_shared<const OccupancyMap>(mapper.liveMap());
  out.ms = msSince(t0);
  warm.ground = mapper.grid();
  warm.nextScan = firstScanAfter(scans, scans.size(), until, warm.nextScan);
  warm.scans = scans.size();
  warm.settings = settings;
  warm.cellSize = request.cellSize;
  warm.until = until;
  return out;
}

void RemapController::finish(quint64 generation, const Outcome& outcome) {
  // Superseded by a newer re-map (appends supersede nothing: each continues the one before).
  const bool stale = generation < lastRemapGeneration_;
  if (!outcome.error.isEmpty() && !stale) {
    emit failed(outcome.error, generation);
  } else if (stale || outcome.interrupted || !outcome.map) {
    emit cancelled(generation, outcome.interrupted);
  } else {
    if (!outcome.incremental) lastFullMs_ = outcome.ms;
    lastMap_ = outcome.map;
    emit mapped(outcome.map, outcome.ms, generation, outcome.incremental);
  }
}

}  // namespace sg::ui
