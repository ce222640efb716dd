// SPDX-License-Identifier: GPL-3.0-or-later
#include "job_queue.h"

namespace sg::ui {

JobQueue::JobQueue(Share share, QObject* parent)
    : QObject(parent), share_(share), cancel_(std::make_shared<std::atomic<bool>>(false)) {
  pool_.setMaxThreadCount(1);
}

JobQueue::~JobQueue() {
  cancel_->store(true);
  pool_.waitForDone();
}

quint64 JobQueue::renew() {
  cancel_->store(true);
  cancel_ = std::make_shared<std::atomic<bool>>(false);
  return ++generation_;
}

void JobQueue::enqueue(std::function<void()> task) {
  if (pending_++ == 0) emit busyChanged(true);
  pool_.start(std::move(task));
}

void JobQueue::handedBack() {
  if (--pending_ == 0) emit busyChanged(false);
}

}  // namespace sg::ui
