// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Re-maps a dataset off the GUI thread (DESIGN.md, "Threading"). Each request gets a generation
// number; a newer request raises the cancel flag of the running one, which stops within a few
// hundred readings (Mapper::mapDataset) and is reported cancelled. Only the newest run's map is
// delivered, as an immutable snapshot. Runs go one at a time through a JobQueue (job_queue.h), so a
// cancelled run never competes with its successor for the cores Mapper already uses.
//
// Moving the time forward with unchanged settings continues the last map with the readings in
// between instead of starting over (the timeline playing). For a log whose readings are in time
// order that gives the same bits as a batch run to the new time (Mapper: batch and incremental
// mapping are identical); other logs always start over. A continued map's snapshot recomputes only
// the rows the new readings wrote (Mapper::liveMap).
//
// A live log (startLive) is a ScanSource that a link appends to while it is mapped, on a grid
// that grows with the robot (Mapper::append). scansAppended() folds the new scans into the warm
// mapper and delivers the map, with no re-map; appends never cancel a run, and while one append
// run waits its turn further appends join it. A change of settings (or of the cell size, or a move
// of the time backwards) re-maps every scan received so far, from the grid's present limits.
//
// Optionally (setPreview), a change of settings whose last full re-map was slow is first mapped on
// cells `factor` times larger and, with a time budget (setPreviewBudget), from one scan in
// `stride` only, the stride chosen from what the last preview cost so that a preview takes about
// the budget; it is delivered as previewed(); the full map follows as mapped(). A dragged slider
// then moves the picture within a frame or two on any log; the full map arrives when the slider
// rests long enough for it (a newer change cancels both). Previews are never cancelled() or
// failed().
//
// The forward model (forward/forward_em.h) is a batch method: each change runs EM over the whole
// loaded log, with emProgress() after each iteration, and no preview; a live link is refused.

#include <QObject>
#include <QString>
#include <atomic>
#include <limits>
#include <memory>

#include "job_queue.h"
#include "sonargrid/data/dataset.h"
#include "sonargrid/engine/mapper.h"
#include "sonargrid/engine/occupancy_map.h"
#include "sonargrid/engine/scan_source.h"

namespace sg::ui {

class RemapController : public QObject {
  Q_OBJECT

 public:
  explicit RemapController(QObject* parent = nullptr);
  ~RemapController() override;  // cancels the running job and waits for it

  // Every log reaches the controller as a ScanSource (scan_source.h), the one road for scans. A
  // source complete when it is given (a loaded log, openLog()) is mapped on its fitting grid, as
  // the CLI maps it; one still filling (a robot link's) on a grid that grows with it. Each of
  // these starts a run at once: everything for a newly opened log.
  void start(std::shared_ptr<const ScanSource> source, double cellSize,
             const MapperSettings& settings, double until);
  // A new source, or a new cell size, with the settings given before (none: no run).
  void setSource(std::shared_ptr<const ScanSource> source, double cellSize = 0.05);
  // The live road for any source, complete or not: scans appended to `source` after this are
  // mapped by scansAppended(). Maps what the source holds now, up to `until` (+infinity: every
  // scan, following the live edge), on a grid that starts at the first pose and grows.
  void startLive(std::shared_ptr<const ScanSource> source, double cellSize,
                 const MapperSettings& settings,
                 double until = std::numeric_limits<double>::infinity());
  // A log in memory: its complete source (start(), setSource()).
  void setDataset(std::shared_ptr<const Dataset> data, double cellSize = 0.05);
  void start(std::shared_ptr<const Dataset> data, double cellSize, const MapperSettings& settings,
             double until);
  // The source's log on its fitting grid; null for a live one.
  std::shared_ptr<const Dataset> dataset() const {
    return source_ && !live_ ? source_->view() : nullptr;
  }
  std::shared_ptr<const ScanSource> source() const { return source_; }
  bool live() const { return live_; }
  double cellSize() const { return cellSize_; }
  const MapperSettings& settings() const { return settings_; }
  double until() const { return until_; }
  bool busy() const { return jobs_.busy(); }
  quint64 latestGeneration() const { return generation_; }
  // The map of the last mapped() (never a preview), or null.
  const std::shared_ptr<const OccupancyMap>& lastMap() const { return lastMap_; }
  // Preview a settings change on cells `factor` times as large when the last full re-map of the
  // log took more than `aboveMs`; factor 1 (the default) turns previews off.
  void setPreview(int factor, double aboveMs);
  int previewFactor() const { return previewFactor_; }
  // The engine every run maps with, whatever the settings given say (MapperSettings::precision),
  // for the pairs whose cells differ under it (hasFastCells(); the others map with Exact, their
  // same cells): a change re-maps the log where it changes the cells.
  void setPrecision(Precision precision);
  Precision precision() const { return precision_; }
  // Whether setSettings(settings) would map what is mapped now (the engine as above).
  bool mapsWith(const MapperSettings& settings) const;
  // A preview maps one scan in `stride` so that its readings take about `ms` (0, the default: every
  // scan), the stride estimated from the last preview's cost per reading (before the first, and
  // after a change of log, cells, model or rule, from the last full re-map's), from 1 to
  // kMaxPreviewStride: a log too long for the budget at that stride takes longer.
  void setPreviewBudget(double ms);
  static constexpr int kMaxPreviewStride = 64;
  // The stride the next preview would take.
  int previewStride() const;

 public slots:
  // Each of these starts a new run and cancels the stale one. Returns nothing; the outcome arrives
  // as mapped(), cancelled() or failed().
  void setSettings(const sg::MapperSettings& settings);
  void setUntil(double until);  // +infinity: the whole log
  void remap();
  // The live source has new scans: fold them into the map and deliver it (mapped(), incremental).
  void scansAppended();
  // Stops the running re-map (the forward model's EM, which takes seconds to a minute): it is
  // reported cancelled() and the map shown stays.
  void stop();

 signals:
  // The newest run finished: its map, the mapping time in ms, its generation and whether it
  // continued the previous map rather than starting over. (A live log's append runs are all
  // delivered, in order, unless a re-map was asked for after them.)
  void mapped(std::shared_ptr<const sg::OccupancyMap> map, double elapsedMs, quint64 generation,
              bool incremental);
  // A re-map from the start of the log (or live source) began, for new settings, cells, log or
  // end time (never a live map's append): mapped(), failed() or cancelled() of this generation
  // follows.
  void started(quint64 generation);
  // A run was superseded; `interrupted` says it stopped before the end of the log.
  void cancelled(quint64 generation, bool interrupted);
  void failed(const QString& message, quint64 generation);
  // A quick map of the newest settings on coarser cells from one scan in `scanStride`, ahead of
  // its mapped() (setPreview).
  void previewed(std::shared_ptr<const sg::OccupancyMap> map, double elapsedMs, quint64 generation,
                 int scanStride);
  void busyChanged(bool busy);
  // The forward model's EM (docs/forward-model.md) finished an iteration of this generation's run:
  // `iteration` of at most `cap`, and the log-likelihood of the map so far. A slider change starts
  // a new EM run; the map shown stays until mapped() brings the new one.
  void emProgress(int iteration, int cap, double logLikelihood, quint64 generation);

 private:
  struct WarmMapper;
  struct Request;
  struct Outcome;
  static Outcome mapLoaded(WarmMapper& warm, const Request& request);
  static Outcome mapForward(WarmMapper& warm, const Request& request);
  static Outcome mapLive(WarmMapper& warm, const Request& request);
  void finish(quint64 generation, const Outcome& outcome);
  void run(bool preview);
  void enqueue(Request request);
  void startPreview(quint64 generation, const std::shared_ptr<std::atomic<bool>>& cancel);
  void adopt(std::shared_ptr<const ScanSource> source, bool live, double cellSize);
  MapperSettings effective(const MapperSettings& settings) const;

  std::shared_ptr<const ScanSource> source_;
  bool live_ = false;  // mapped on a growing grid (startLive(), or a source not yet complete)
  double cellSize_ = 0.05;
  MapperSettings settings_;
  bool haveSettings_ = false;
  Precision precision_ = Precision::Exact;
  double until_ = std::numeric_limits<double>::infinity();
  quint64 generation_ = 0;
  quint64 lastRemapGeneration_ = 0;         // the newest request that was not an append
  std::atomic<bool> appendWaiting_{false};  // an append run is queued and has not started
  std::shared_ptr<std::atomic<bool>> cancelRunning_;
  int previewFactor_ = 1;
  double previewAboveMs_ = 0.0;
  double previewBudgetMs_ = 0.0;
  double previewMsPerReading_ = 0.0;  // what the last preview's readings cost (0: none yet)
  // The preview's grid, the log's fitting grid at its cell size; touched only by preview jobs.
  struct PreviewGround {
    std::shared_ptr<const Dataset> data;
    double cellSize = 0.0;
    PoseSource pose = PoseSource::Odometry;
    GridSpec spec;
  };
  std::shared_ptr<PreviewGround> previewGround_ = std::make_shared<PreviewGround>();
  double lastFullMs_ = 0.0;  // the last full re-map from scratch (not a continuation)
  std::shared_ptr<const OccupancyMap> lastMap_;
  // Touched only by jobs, and jobs run one at a time.
  std::shared_ptr<WarmMapper> warm_;
  // The view's re-map goes before every other job. Last: destroyed (waited for) first.
  JobQueue jobs_{JobQueue::Share::Interactive};
};

}  // namespace sg::ui
