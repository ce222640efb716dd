// SPDX-License-Identifier: GPL-3.0-or-later
#include "sweep_view_runner.h"

#include <QMetaObject>
#include <QPointer>
#include <exception>
#include <numeric>

#include "sonargrid/sweep/sweep_metrics.h"

namespace sg::ui {

SetEvaluationInput SweepJob::input() const {
  SetEvaluationInput in;
  in.run = run.get();
  in.secondRun = secondRun.get();
  in.reference = reference.get();
  in.settings = settings;
  in.measures = measuresOf(metrics);
  return in;
}

SweepRunner::SweepRunner(QObject* parent) : QObject(parent) {}

SweepRunner::~SweepRunner() {
  cancel();
  join();
}

bool SweepRunner::start(std::shared_ptr<const SweepJob> job) {
  if (isRunning()) return false;
  cancel_ = std::make_shared<std::atomic<bool>>(false);
  auto cancel = cancel_;
  // Results travel to the GUI thread as queued calls on this object: Qt drops those still queued
  // when it is destroyed, and the destructor joins the worker before, so none comes late.
  worker_ = std::thread([this, job = std::move(job), cancel] {
    bool completed = false;
    QString error;
    try {
      std::vector<std::size_t> indices(job->sets.size());
      std::iota(indices.begin(), indices.end(), std::size_t{0});
      const SetEvaluationInput input = job->input();
      completed = evaluateSets(
          input, job->sets, indices,
          [this, &job](std::size_t k, const SetEvaluation& e) {
            std::vector<std::optional<double>> values = metricValues(job->metrics, e);
            QMetaObject::invokeMethod(
                this, [this, k, values = std::move(values)] { emit setFinished(k, values); },
                Qt::QueuedConnection);
          },
          cancel.get());
    } catch (const std::exception& e) {
      error = QString::fromUtf8(e.what());
    }
    QMetaObject::invokeMethod(
        this,
        [this, completed, error] {
          join();
          emit finished(completed, error);
        },
        Qt::QueuedConnection);
  });
  return true;
}

void SweepRunner::cancel() {
  if (cancel_) cancel_->store(true);
}

void SweepRunner::join() {
  if (worker_.joinable()) worker_.join();
}

}  // namespace sg::ui
