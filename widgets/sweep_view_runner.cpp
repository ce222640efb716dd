// SPDX-License-Identifier: GPL-3.0-or-later
#include "sweep_view_runner.h"

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

SweepRunner::~SweepRunner() = default;

bool SweepRunner::start(std::shared_ptr<const SweepJob> job) {
  if (isRunning()) return false;
  jobs_.renew();
  // Each finished set travels to the GUI thread as a call posted to the queue; those still posted
  // when it is destroyed are dropped, and its destructor waits for the job before.
  jobs_.run<bool>(
      [this, job = std::move(job)](const std::atomic<bool>* cancel) {
        std::vector<std::size_t> indices(job->sets.size());
        std::iota(indices.begin(), indices.end(), std::size_t{0});
        const SetEvaluationInput input = job->input();
        return evaluateSets(
            input, job->sets, indices,
            [this, &job](std::size_t k, const SetEvaluation& e) {
              std::vector<std::optional<double>> values = metricValues(job->metrics, e);
              jobs_.post([this, k, values = std::move(values)] { emit setFinished(k, values); });
            },
            cancel);
      },
      [this](JobOutcome<bool> outcome) {
        emit finished(outcome.value.value_or(false), outcome.error);
      });
  return true;
}

void SweepRunner::cancel() {
  jobs_.cancel();
}

}  // namespace sg::ui
