// SPDX-License-Identifier: GPL-3.0-or-later
#include "log_loader.h"

#include <QDir>
#include <atomic>

#include "sonargrid/data/scan_poses.h"
#include "sonargrid/io/log_reader.h"

namespace sg::app {

// One load. The loader forgets a job it cancelled or replaced; the worker still holds it until it
// notices `cancel`.
struct LogLoader::Job {
  QString path;
  LogReading reading;  // the options, without the hooks
  bool quiet = false;
  std::atomic<bool> cancel{false};
  std::atomic<int> lastPercent{-1};
};

LogLoader::LogLoader(QObject* parent) : QObject(parent) {}

LogLoader::~LogLoader() {
  if (job_) job_->cancel = true;
}

QString LogLoader::path() const {
  return job_ ? job_->path : QString();
}

void LogLoader::start(const QString& path, const LogOptions& options, PoseSource pose,
                      double cellSize, bool quiet) {
  cancel();
  auto job = std::make_shared<Job>();
  job->path = path;
  job->reading = readingOf(options);
  job->quiet = quiet;
  job_ = job;
  LogOptions o = options;
  o.cancel = &job->cancel;
  // The Document places the odometry at the start pose (Document::setStartPose), so that a new
  // one needs no new load.
  o.startPose.reset();
  // Called on the worker after each block: post a whole-percent change to the GUI thread.
  o.progress = [this, job](std::uint64_t done, std::uint64_t total) {
    if (total == 0) return;
    const int percent = static_cast<int>(done * 100 / total);
    if (job->lastPercent.exchange(percent) == percent) return;
    jobs_.post([this, job, percent] {
      if (job == job_) emit progress(percent);
    });
  };
  struct Loaded {
    std::shared_ptr<const ScanSource> source;
    bool cancelled = false;
  };
  // The job's flag is the load's own (LogOptions::cancel): cancel() raises it.
  jobs_.run<Loaded>(
      std::shared_ptr<std::atomic<bool>>(job, &job->cancel),
      [o, file = QDir::toNativeSeparators(path), pose, cell = cellSize](const std::atomic<bool>*) {
        Loaded out;
        try {
          auto source = openLog(file.toStdString(), o);
          const std::shared_ptr<const Dataset> dataset = source->view();
          // The pose source is the one the window will map with.
          try {
            dataset->fittingGrid(pose == PoseSource::Truth && anyScanHasPose(*dataset, pose)
                                     ? PoseSource::Truth
                                     : PoseSource::Odometry,
                                 cell);
          } catch (const GridLimitError& e) {
            throw e.inFile(file.toStdString());
          }
          out.source = std::move(source);
        } catch (const LoadCancelled&) {
          out.cancelled = true;
        }
        return out;
      },
      [this, job](ui::JobOutcome<Loaded> outcome) {
        const bool cancelled = outcome.skipped || (outcome.value && outcome.value->cancelled);
        finish(job, outcome.value ? outcome.value->source : nullptr, outcome.error, cancelled);
      });
}

QString LogLoader::cancel() {
  if (!job_) return {};
  const QString path = job_->path;
  job_->cancel = true;
  job_.reset();
  return path;
}

void LogLoader::finish(const std::shared_ptr<Job>& job, std::shared_ptr<const ScanSource> source,
                       const QString& error, bool cancelled) {
  if (job != job_) return;  // cancelled or replaced: its outcome no longer matters
  job_.reset();
  if (cancelled) {
    emit this->cancelled(job->path);
    return;
  }
  QString message = error;
  if (message.isEmpty() && source->size() == 0)
    message = job->path + tr(": the log holds no scans");
  if (!message.isEmpty())
    emit failed(job->path, message, job->quiet);
  else
    emit loaded(job->path, std::move(source), job->reading, job->quiet);
}

}  // namespace sg::app
