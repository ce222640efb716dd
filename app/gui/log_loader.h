// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Loads a log on a worker thread, one at a time: a new load cancels the one running. The outcome
// reaches the GUI thread as a signal; a cancelled or replaced load's outcome is dropped. The worker
// also refuses a log no grid can hold (a pose at 1e12 m), so that the document open before stays.

#include <QObject>
#include <QString>
#include <memory>
#include <vector>

#include "sonargrid/data/dataset.h"
#include "sonargrid/io/log_options.h"

class QThread;

namespace sg::app {

class LogLoader : public QObject {
  Q_OBJECT

 public:
  explicit LogLoader(QObject* parent = nullptr);
  // Lets every worker end (at its next block) before the loader goes: each posts to it.
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
  void loaded(const QString& path, std::shared_ptr<const sg::Dataset> dataset, bool quiet);
  void failed(const QString& path, const QString& message, bool quiet);
  // The worker stopped on its cancel flag while the loader still waited for it.
  void cancelled(const QString& path);

 private:
  struct Job;
  void finish(const std::shared_ptr<Job>& job, std::shared_ptr<const Dataset> dataset,
              const QString& error, bool cancelled);

  std::shared_ptr<Job> job_;       // the running load, if any
  std::vector<QThread*> workers_;  // still running (a cancelled one ends soon)
};

}  // namespace sg::app
