#include "remap_controller.h"

#include <QMetaObject>
#include <algorithm>
#include <chrono>
#include <exception>

namespace sg::ui {

// The mapper of the last complete run, kept for continuing it forward in time. When the log's
// readings are in time order, a batch run to `until` has applied exactly the readings of the log
// up to `until`, a prefix of the log; a batch run to a later time applies that prefix and then the
// readings in (until, later], in log order, which is what continuing the mapper does.
struct RemapController::WarmMapper {
  std::shared_ptr<const Dataset> data;
  bool ordered = false;  // the readings' times never decrease along the log
  std::unique_ptr<Mapper> mapper;
  MapperSettings settings;
  double cellSize = 0.0;
  double until = 0.0;
  std::size_t nextScan = 0;  // the first scan holding a reading after `until`
};

namespace {

bool sameSettings(const MapperSettings& a, const MapperSettings& b) {
  return a.model == b.model && a.rule == b.rule && a.pose == b.pose && a.parameters == b.parameters;
}

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

std::size_t firstScanAfter(const Dataset& data, double until, std::size_t from) {
  for (std::size_t i = from; i < data.scans.size(); ++i)
    for (const Reading& r : data.scans[i].readings)
      if (r.time > until) return i;
  return data.scans.size();
}

}  // namespace

RemapController::RemapController(QObject* parent)
    : QObject(parent), warm_(std::make_shared<WarmMapper>()) {
  pool_.setMaxThreadCount(1);
}

RemapController::~RemapController() {
  if (cancelRunning_) cancelRunning_->store(true);
  pool_.waitForDone();
}

void RemapController::setDataset(std::shared_ptr<const Dataset> data, double cellSize) {
  data_ = std::move(data);
  cellSize_ = cellSize;
  remap();
}

void RemapController::start(std::shared_ptr<const Dataset> data, double cellSize,
                            const MapperSettings& settings, double until) {
  data_ = std::move(data);
  cellSize_ = cellSize;
  settings_ = settings;
  haveSettings_ = true;
  until_ = until;
  remap();
}

void RemapController::setSettings(const MapperSettings& settings) {
  settings_ = settings;
  haveSettings_ = true;
  run(previewFactor_ > 1 && lastFullMs_ > previewAboveMs_);
}

void RemapController::setPreview(int factor, double aboveMs) {
  previewFactor_ = std::max(1, factor);
  previewAboveMs_ = aboveMs;
}

void RemapController::startPreview(quint64 generation,
                                   const std::shared_ptr<std::atomic<bool>>& cancel) {
  pool_.start([this, data = data_, settings = settings_, cellSize = cellSize_ * previewFactor_,
               until = until_, cancel, generation] {
    std::shared_ptr<const OccupancyMap> map;
    double ms = 0.0;
    try {
      const auto t0 = std::chrono::steady_clock::now();
      const auto mapper = mapperFor(*data, settings, cellSize);
      if (mapper->mapDataset(*data, until, cancel.get())) {
        map = std::make_shared<const OccupancyMap>(mapper->snapshot());
        ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                 .count();
      }
    } catch (const std::exception&) {
      // The full run reports the error.
    }
    if (!map) return;
    QMetaObject::invokeMethod(
        this,
        [this, generation, map = std::move(map), ms] {
          if (generation == generation_) emit previewed(map, ms, generation);
        },
        Qt::QueuedConnection);
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
  if (!data_ || !haveSettings_) return;
  if (cancelRunning_) cancelRunning_->store(true);
  auto cancel = std::make_shared<std::atomic<bool>>(false);
  cancelRunning_ = cancel;
  const quint64 generation = ++generation_;
  if (running_++ == 0) emit busyChanged(true);
  if (preview) startPreview(generation, cancel);  // queued first, so it runs first

  pool_.start([this, data = data_, settings = settings_, cellSize = cellSize_, until = until_,
               cancel, generation, warm = warm_] {
    std::shared_ptr<const OccupancyMap> map;
    double ms = 0.0;
    bool interrupted = false;
    bool incremental = false;
    QString error;
    try {
      if (settings.pose == PoseSource::Truth && !data->hasTruth())
        throw MapperError("the log has no true pose for every scan; map with odometry");
      const auto t0 = std::chrono::steady_clock::now();
      if (warm->data != data) {
        warm->mapper.reset();
        warm->data = data;
        warm->ordered = readingsInTimeOrder(*data);
      }
      incremental = warm->mapper && warm->ordered && warm->cellSize == cellSize &&
                    sameSettings(warm->settings, settings) && until >= warm->until;
      if (incremental) {
        Scan part;
        for (std::size_t i = warm->nextScan; i < data->scans.size() && !interrupted; ++i) {
          const Scan& scan = data->scans[i];
          if (!scan.readings.empty() && scan.readings.front().time > until) break;
          if (cancel->load(std::memory_order_relaxed)) {
            interrupted = true;
            break;
          }
          // Only the readings the mapper has not seen yet: those after the previous time.
          part.time = scan.time;
          part.odometry = scan.odometry;
          part.truth = scan.truth;
          part.readings.clear();
          for (const Reading& r : scan.readings)
            if (r.time > warm->until) part.readings.push_back(r);
          warm->mapper->integrate(part, until);
        }
      } else {
        warm->mapper.reset();
        auto mapper = mapperFor(*data, settings, cellSize);
        interrupted = !mapper->mapDataset(*data, until, cancel.get());
        warm->mapper = std::move(mapper);
      }
      if (interrupted) {
        warm->mapper.reset();
      } else {
        map = std::make_shared<const OccupancyMap>(warm->mapper->snapshot());
        ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                 .count();
        warm->nextScan = firstScanAfter(*data, until, incremental ? warm->nextScan : 0);
        warm->settings = settings;
        warm->cellSize = cellSize;
        warm->until = until;
      }
    } catch (const std::exception& e) {
      warm->mapper.reset();
      error = QString::fromStdString(e.what());
    }
    QMetaObject::invokeMethod(
        this,
        [this, generation, map = std::move(map), ms, interrupted, incremental, error] {
          finish(generation, map, ms, interrupted, incremental, error);
        },
        Qt::QueuedConnection);
  });
}

void RemapController::finish(quint64 generation, std::shared_ptr<const OccupancyMap> map, double ms,
                             bool interrupted, bool incremental, const QString& error) {
  if (--running_ == 0) emit busyChanged(false);
  const bool stale = generation != generation_;
  if (!error.isEmpty() && !stale) {
    emit failed(error, generation);
  } else if (stale || interrupted || !map) {
    emit cancelled(generation, interrupted);
  } else {
    if (!incremental) lastFullMs_ = ms;
    emit mapped(std::move(map), ms, generation, incremental);
  }
}

}  // namespace sg::ui
