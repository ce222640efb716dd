// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// SIGINT and SIGTERM as a Qt signal: the handler only writes the signal number to a pipe, and a
// QSocketNotifier on the other end delivers it to the event loop, where the long-running commands
// (`robot`, `record`) stop cleanly (a POSIX signal handler may do nothing more).

#include <QObject>
#include <QSocketNotifier>
#include <memory>

namespace sg::cli {

class SignalWatcher : public QObject {
  Q_OBJECT

 public:
  // Installs the handlers; one watcher per process. Throws std::runtime_error when it cannot.
  explicit SignalWatcher(QObject* parent = nullptr);
  ~SignalWatcher() override;

 signals:
  void received(int signalNumber);

 private:
  std::unique_ptr<QSocketNotifier> notifier_;
};

}  // namespace sg::cli
