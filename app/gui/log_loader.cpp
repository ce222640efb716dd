// SPDX-License-Identifier: GPL-3.0-or-later
#include "log_loader.h"

#include <QDir>
#include <QThread>
#include <algorithm>
#include <atomic>

#include "sonargrid/io/log_reader.h"

namespace sg::app {

// One load. The loader forgets a job it cancelled or replaced; the worker still holds it until it
// notices `cancel`.
struct LogLoader::Job {
  QString path;
  bool quiet = false;
  std::atomic<bool> cancel{false};
  std::atomic<int> lastPercent{-1};
};

LogLoader::LogLoader(QObject* parent) : QObject(parent) {}

LogLoader::~LogLoader() {
  if (job_) job_->cancel = true;
  for (QThread* t : workers_) {
    t->wait();
    delete t;
  }
}

QString LogLoader::path() const {
  return job_ ? job_->path : QString();
}

void LogLoader::start(const QString& path, const LogOptions& options, PoseSource pose,
                      double cellSize, bool quiet) {
  cancel();
  auto job = std::make_shared<Job>();
  job->path = path;
  job->quiet = quiet;
  job_ = job;
  LogOptions o = options;
  o.cancel = &job->cancel;
  // Called on the worker after each block: post a whole-percent change to the GUI thread.
  o.progress = [this, job](std::uint64_t done, std::uint64_t total) {
    if (total == 0) return;
    const int percent = static_cast<int>(done * 100 / total);
    if (job->lastPercent.exchange(percent) == percent) return;
    QMetaObject::invokeMethod(
        this,
        [this, job, percent] {
          if (job == job_) emit progress(percent);
        },
        Qt::QueuedConnection);
  };
  QThread* worker =
      QThread::create([this, job, o, file = QDir::toNativeSeparators(path), pose, cell = cellSize] {
        std::shared_ptr<const Dataset> dataset;
        QString error;
        bool cancelled = false;
        try {
          dataset = std::make_shared<const Dataset>(readLog(file.toStdString(), o));
          // The pose source is the one the window will map with.
          try {
            dataset->fittingGrid(pose == PoseSource::Truth && dataset->hasTruth()
                                     ? PoseSource::Truth
                                     : PoseSource::Odometry,
                                 cell);
          } catch (const GridLimitError& e) {
            throw e.inFile(file.toStdString());
          }
        } catch (const LoadCancelled&) {
          cancelled = true;
        } catch (const std::exception& e) {
          error = QString::fromStdString(e.what());
        }
        QMetaObject::invokeMethod(
            this,
            [this, job, dataset = std::move(dataset), error, cancelled]() mutable {
              finish(job, std::move(dataset), error, cancelled);
            },
            Qt::QueuedConnection);
      });
  workers_.push_back(worker);
  connect(worker, &QThread::finished, this, [this, worker] {
    workers_.erase(std::remove(workers_.begin(), workers_.end(), worker), workers_.end());
    worker->deleteLater();
  });
  worker->start();
}

QString LogLoader::cancel() {
  if (!job_) return {};
  const QString path = job_->path;
  job_->cancel = true;
  job_.reset();
  return path;
}

void LogLoader::finish(const std::shared_ptr<Job>& job, std::shared_ptr<const Dataset> dataset,
                       const QString& error, bool cancelled) {
  if (job != job_) return;  // cancelled or replaced: its outcome no longer matters
  job_.reset();
  if (cancelled) {
    emit this->cancelled(job->path);
    return;
  }
  QString message = error;
  if (message.isEmpty() && dataset->scans.empty())
    message = job->path + tr(": the log holds no scans");
  if (!message.isEmpty())
    emit failed(job->path, message, job->quiet);
  else
    emit loaded(job->path, std::move(dataset), job->quiet);
}

}  // namespace sg::app
