// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Loads a log as a job of a JobQueue (job_queue.h), one at a time: a new load cancels the one
// running and starts when it has stopped (at its next block). The outcome
// reaches the GUI thread as a signal; a cancelled or replaced load's outcome is dropped. The worker
// also refuses a log no grid can hold (a pose at 1e12 m), so that the document open before stays.

#include <QObject>
#include <QString>
#include <memory>

#include "job_queue.h"
#include "project.h"
#include "sonargrid/data/dataset.h"
#include "sonargrid/engine/scan_source.h"
#include "sonargrid/io/log_options.h"

namespace sg::app {

class LogLoader : public QObject {
  Q_OBJECT

 public:
  explicit LogLoader(QObject* parent = nullptr);
  // Cancels the running load and waits for it to stop (at its next block).
  ~LogLoader() override;

  // `pose` and `cellSize`: the grid the log will be mapped on, checked on the worker.
  void start(const QString& path, const LogOptions& options, PoseSource pose, double cellSize,
             bool quiet);
  // Abandons the running load at once; returns its path (empty when none ran). No signal.
  QString cancel();
  bool busy() const { return job_ != nullptr; }
  // The running load's path and quiet flag.
  QString path() const;

 signals:
  // Percent of the file's bytes read (throttled: once per whole percent).
  void progress(int percent);
  // The log as a complete source (openLog(), io/log_reader.h), and how it was read.
  void loaded(const QString& path, std::shared_ptr<const sg::ScanSource> source,
              const sg::app::LogReading& reading, bool quiet);
  void failed(const QString& path, const QString& message, bool quiet);
  // The worker stopped on its cancel flag while the loader still waited for it.
  void cancelled(const QString& path);

 private:
  struct Job;
  void finish(const std::shared_ptr<Job>& job, std::shared_ptr<const ScanSource> source,
              const QString& error, bool cancelled);

  std::shared_ptr<Job> job_;  // the running load, if any
  // Reading maps nothing: no share of the thread budget. Last: destroyed (waited for) first.
  ui::JobQueue jobs_{ui::JobQueue::Share::Unleased};
};

}  // namespace sg::app
