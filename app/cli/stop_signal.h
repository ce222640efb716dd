// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// SIGINT and SIGTERM as a stop flag, for commands that run without an event loop (`sweep`,
// `optimize`): the handler only stores the signal number in a lock-free atomic, which the work
// polls between scans (a POSIX signal handler may do nothing more). The handler is reset by the
// first signal, so a second Ctrl-C ends the process at once. SignalWatcher (signal_watcher.h) is
// the form for commands with a Qt event loop.

#include <atomic>

namespace sg::cli {

class StopOnSignal {
 public:
  // Installs the handlers; one at a time per process. Restores the default ones when destroyed.
  StopOnSignal();
  ~StopOnSignal();
  StopOnSignal(const StopOnSignal&) = delete;
  StopOnSignal& operator=(const StopOnSignal&) = delete;

  const std::atomic<bool>& flag() const;  // true once a signal came
  int signalNumber() const;               // 0 until then
};

}  // namespace sg::cli
