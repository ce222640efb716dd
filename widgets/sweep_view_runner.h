// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The sweep view's worker: runs one sweep (the core's evaluateSets(), set_evaluation.h) as a job of
// a JobQueue (job_queue.h), on every thread of the policy but one (the view's re-maps keep one),
// and hands each finished set back on the GUI thread. Cancel stops it between scans; destroying
// the runner cancels and waits for the threads, so closing a window mid-sweep neither crashes nor
// hangs.

#include <QObject>
#include <QString>
#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "job_queue.h"
#include "sonargrid/data/dataset.h"
#include "sonargrid/params/parameters.h"
#include "sonargrid/reference/reference_map.h"
#include "sonargrid/sweep/set_evaluation.h"

namespace sg::ui {

// Everything one sweep reads, owned (shared) so that the worker never looks at the GUI's state.
struct SweepJob {
  std::shared_ptr<const Dataset> run;
  std::shared_ptr<const Dataset> secondRun;       // for the two-run metric
  std::shared_ptr<const ReferenceMap> reference;  // for the reference metrics
  SweepSettings settings;                         // model, rule, pose, grid
  std::vector<std::string> metrics;               // canonical (parseSweepMetrics)
  std::vector<ParameterSet> sets;
  // What evaluateSet() reads for this job (pointers into the job).
  SetEvaluationInput input() const;
};

class SweepRunner : public QObject {
  Q_OBJECT

 public:
  explicit SweepRunner(QObject* parent = nullptr);
  ~SweepRunner() override;  // cancels and waits

  // Starts `job`; false when one is still running.
  bool start(std::shared_ptr<const SweepJob> job);
  // Asks the running sweep to stop; finished(false, {}) follows once its threads have stopped.
  void cancel();
  bool isRunning() const { return jobs_.busy(); }

 signals:
  // On the GUI thread, once per finished set (any order): one value per metricColumns() column.
  void setFinished(std::size_t index, const std::vector<std::optional<double>>& values);
  // On the GUI thread after the last setFinished: every set done, or stopped by cancel() (error
  // empty) or by an error of the mapper or a metric (its message).
  void finished(bool completed, const QString& error);

 private:
  JobQueue jobs_;
};

}  // namespace sg::ui
