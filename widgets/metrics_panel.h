// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The metrics panel (a dock of the window): IOP and every metric of `sonargrid-cli score` for the
// map the window shows, against the document's reference; without a reference, paper 002's
// goodness (VSDNS, derivative noise); with a second run, the two-run comparison. Each number shows
// its name, its unit and, in a tooltip, what it is and which paper defines it.
//
// The numbers come from computeMetrics() (metrics_compute.h: the core calls the CLI makes) on a
// JobQueue (job_queue.h), off the GUI thread. A new map, reference or run cancels the stale
// computation, which stops at its next check and is never shown; the destructor cancels the running
// one and waits for it, so the window may close mid-computation.

#include <QTimer>
#include <QWidget>
#include <atomic>
#include <memory>
#include <optional>

#include "job_queue.h"
#include "metrics_compute.h"

class QLabel;
class QTableWidget;

namespace sg::ui {

class MetricsPanel : public QWidget {
  Q_OBJECT

 public:
  explicit MetricsPanel(QWidget* parent = nullptr);
  ~MetricsPanel() override;

  // Each schedules a recomputation (coalesced: several changes in one event-loop turn compute
  // once).
  void setMap(std::shared_ptr<const OccupancyMap> map);
  void setReference(std::shared_ptr<const ReferenceMap> reference);
  // The runs and what the shown map was built with (for the goodness measures, which map the run
  // again with an observer).
  void setRuns(std::shared_ptr<const Dataset> run, std::shared_ptr<const Dataset> secondRun,
               const MapperSettings& settings, double cellSize);
  // Options of the reference metrics (path pairs, seed); the CLI's defaults unless set.
  void setScoreOptions(const ScoreOptions& options);
  // A newer map is on its way (a re-map began): the computation for the shown map stops now rather
  // than take the CPU the re-map needs (a dragged slider would otherwise score every step's map
  // while the next one is built), and nothing is computed until setMap() brings the new map or
  // resume() says none is coming. The numbers shown stay meanwhile. The map that comes is scored
  // once kSettleMs pass without another awaitMap(): while a slider moves or the timeline plays,
  // nothing is scored.
  static constexpr int kSettleMs = 100;
  void awaitMap();
  void resume();
  // The change that began the awaited re-map is a single one (a parameter set by a key, the
  // wheel, a click on the groove or the spin box, not by a held slider): its map is scored as soon
  // as it arrives, without the settle. Call it after awaitMap(), which forgets it.
  void scoreAtOnce();
  // The changes are over (a held slider was let go): a map waiting for the settle is scored now.
  void endSettle();
  bool settling() const { return settle_.isActive(); }

  // The numbers shown (null before the first result).
  const MetricsResult* result() const { return result_ ? &*result_ : nullptr; }
  // True while a computation is scheduled or running, or a new map is awaited.
  bool busy() const { return pending_ || jobs_.busy() || awaitingMap_; }
  // Blocks (running the event loop) until the newest inputs' numbers are shown; false on timeout.
  bool waitForResult(int timeoutMs);
  // Requests made / results shown (a result is shown for the newest request only).
  quint64 generation() const { return jobs_.generation(); }
  quint64 shownGeneration() const { return shownGeneration_; }

 signals:
  // New numbers are shown (the D_min tint of the scored map comes with them).
  void updated();
  void dminTintChanged(std::shared_ptr<const QImage> tint, const sg::GridSpec& spec);

 private:
  void schedule();
  void start();
  void show(quint64 generation, const std::optional<MetricsResult>& result);
  void fill();

  QLabel* status_;
  QTableWidget* table_;
  MetricsInput input_;
  std::optional<MetricsResult> result_;
  // Goodness depends on the runs and the settings, not on the map shown (it maps the whole log
  // again): kept while they stay, so that the timeline playing does not re-map the log each step.
  struct GoodnessKey {
    std::shared_ptr<const Dataset> run, secondRun;
    MapperSettings settings;
    double cellSize = 0.0;
    bool goodness = false;
    bool operator==(const GoodnessKey& o) const;
  };
  std::optional<GoodnessKey> goodnessKey_;
  std::optional<SetEvaluation> goodness_;
  quint64 shownGeneration_ = 0;
  bool pending_ = false;
  bool awaitingMap_ = false;
  bool atOnce_ = false;  // scoreAtOnce(), until the next awaitMap()
  QTimer settle_;        // awaitMap()'s map waits for it
  JobQueue jobs_;        // last: destroyed (cancelled and waited for) first
};

}  // namespace sg::ui
