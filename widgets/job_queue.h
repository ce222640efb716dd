// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The one way the widgets and the app run work off the GUI thread (docs/architecture.md,
// "Background jobs"). A JobQueue runs its jobs one at a time, in the order they were queued, on a
// worker thread of its own, and for each one:
//  - cancel: every job carries a flag; renew() starts a new generation and raises the flag of the
//    jobs queued before it, so that a queued job is skipped and a running one stops at its next
//    check (the core's long calls take the flag);
//  - threads: a job that maps runs holding a ThreadLease (concurrency.h), so that the jobs of every
//    queue together never run more mapping threads than the thread policy grants. The view's
//    re-map is interactive: it goes first, and the others leave it a thread (LeaseClass);
//  - hand-back: what the job returns, or the message of what it threw, reaches the function given
//    with it on the GUI thread, with its generation and whether that is still the newest;
//  - progress: a job may post() a function to the GUI thread at any time.
// Destroying a queue raises its own flag and waits for the job running; nothing is handed back
// then. Jobs queued with a flag of the caller's (run(cancel, …)) stop when the caller raises it:
// an owner that queues such jobs raises their flags in its destructor.

#include <QMetaObject>
#include <QObject>
#include <QString>
#include <QThreadPool>
#include <atomic>
#include <exception>
#include <functional>
#include <memory>
#include <optional>
#include <utility>

#include "sonargrid/base/concurrency.h"

namespace sg::ui {

template <class Result>
struct JobOutcome {
  quint64 generation = 0;
  bool current = false;         // no renew() came after it was queued
  std::optional<Result> value;  // what the job returned
  QString error;                // what it threw (then value is empty)
  bool skipped = false;         // cancelled before it began, queued or waiting for its threads
};

class JobQueue : public QObject {
  Q_OBJECT

 public:
  // The threads a job takes: the view's re-map (every free thread, before anyone else); every
  // other mapping job (the threads the re-map leaves); or none from the budget, for work that maps
  // nothing and runs on one thread (reading a log).
  enum class Share { Interactive, Background, Unleased };

  explicit JobQueue(Share share = Share::Background, QObject* parent = nullptr);
  ~JobQueue() override;  // cancels every job and waits for the running one

  // A new generation: the jobs queued so far are cancelled. Returns its number.
  quint64 renew();
  quint64 generation() const { return generation_; }
  // The flag of the newest generation, which the jobs queued from now on carry.
  const std::shared_ptr<std::atomic<bool>>& cancelFlag() const { return cancel_; }
  // Cancels the jobs queued so far, without a new generation: jobs queued after this with the
  // queue's flag are skipped too, until renew().
  void cancel() { cancel_->store(true); }

  // Queued or running jobs whose outcome has not been handed back.
  int pending() const { return pending_; }
  bool busy() const { return pending_ > 0; }
  // Waits (without handling events) until no job runs or is queued on the worker.
  void waitForDone() { pool_.waitForDone(); }

  // Queues `work`, a callable Result(const std::atomic<bool>* cancel), and `done`, a callable
  // void(JobOutcome<Result>) run on the GUI thread, with the newest generation's flag.
  template <class Result, class Work, class Done>
  void run(Work work, Done done) {
    run<Result>(cancel_, std::move(work), std::move(done));
  }
  // The same with a flag of the caller's (e.g. work that must stop with the job running now).
  template <class Result, class Work, class Done>
  void run(std::shared_ptr<std::atomic<bool>> cancel, Work work, Done done) {
    run<Result>(
        std::move(cancel), [] {}, std::move(work), std::move(done));
  }
  // The same, calling `turn` (a callable void()) on the worker when the job's turn comes, before
  // it waits for threads or is skipped.
  template <class Result, class Turn, class Work, class Done>
  void run(std::shared_ptr<std::atomic<bool>> cancel, Turn turn, Work work, Done done);

  // Runs `fn` on the GUI thread soon; callable from a job.
  void post(std::function<void()> fn) {
    QMetaObject::invokeMethod(this, std::move(fn), Qt::QueuedConnection);
  }

 signals:
  void busyChanged(bool busy);

 private:
  void enqueue(std::function<void()> task);
  void handedBack();

  Share share_;
  quint64 generation_ = 0;
  std::shared_ptr<std::atomic<bool>> cancel_;
  int pending_ = 0;
  QThreadPool pool_;
};

template <class Result, class Turn, class Work, class Done>
void JobQueue::run(std::shared_ptr<std::atomic<bool>> cancel, Turn turn, Work work, Done done) {
  enqueue([this, cancel = std::move(cancel), generation = generation_, turn = std::move(turn),
           work = std::move(work), done = std::move(done)]() mutable {
    turn();
    auto outcome = std::make_shared<JobOutcome<Result>>();
    outcome->generation = generation;
    {
      std::optional<ThreadLease> lease;
      if (share_ != Share::Unleased)
        lease.emplace(
            0, cancel.get(),
            share_ == Share::Interactive ? LeaseClass::Interactive : LeaseClass::Background);
      if ((lease && lease->threads() == 0) || cancel->load()) {
        outcome->skipped = true;
      } else {
        try {
          outcome->value.emplace(work(static_cast<const std::atomic<bool>*>(cancel.get())));
        } catch (const std::exception& e) {
          outcome->error = QString::fromUtf8(e.what());
        } catch (...) {
          outcome->error = tr("an unknown error");
        }
      }
    }
    post([this, outcome, done = std::move(done)]() mutable {
      outcome->current = outcome->generation == generation_;
      handedBack();
      done(std::move(*outcome));
    });
  });
}

}  // namespace sg::ui
