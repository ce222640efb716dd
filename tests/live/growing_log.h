// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A log that `sonargrid-cli record` is still writing, watched from a test: how many scans it has
// so far, and waiting (running the event loop) until it has enough.

#include <QElapsedTimer>
#include <QFile>
#include <QString>
#include <QTest>

namespace live_test {

// The number of complete scan lines a log file has so far.
inline int scanLines(const QString& path) {
  QFile f(path);
  if (!f.open(QIODevice::ReadOnly)) return 0;
  return static_cast<int>(f.readAll().count("\nscan "));
}

inline bool waitForScans(const QString& path, int scans, int timeoutMs) {
  QElapsedTimer t;
  t.start();
  while (t.elapsed() < timeoutMs) {
    if (scanLines(path) >= scans) return true;
    QTest::qWait(20);
  }
  return false;
}

}  // namespace live_test
