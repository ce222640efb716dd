// SPDX-License-Identifier: GPL-3.0-or-later
// The timeline of a live log: appended scans extend its range; a user at the end follows the live
// edge, a user anywhere else stays where they are.

#include <QSignalSpy>
#include <QSlider>
#include <QtTest>

#include "timeline.h"

using namespace sg::ui;

namespace {
// Scan k at t = 0.1 k, k in [from, to).
std::vector<double> times(int from, int to) {
  std::vector<double> t;
  for (int k = from; k < to; ++k) t.push_back(0.1 * k);
  return t;
}
}  // namespace

class TstTimeline : public QObject {
  Q_OBJECT

 private slots:
  void atTheEndFollowsTheLiveEdge();
  void elsewhereStays();
  void firstScansEnableIt();
};

void TstTimeline::atTheEndFollowsTheLiveEdge() {
  Timeline t;
  t.setScanTimes(times(0, 10), 0.95);  // scans to 0.9 s, last reading at 0.95 s
  QVERIFY(t.atEnd());
  QSignalSpy changed(&t, &Timeline::timeChanged);
  t.appendScanTimes(times(10, 20), 1.95);
  QCOMPARE(t.endTime(), 1.95);
  QCOMPARE(t.time(), 1.95);
  QCOMPARE(t.currentScan(), std::size_t{19});
  QCOMPARE(changed.count(), 1);
  QCOMPARE(changed.at(0).at(0).toDouble(), 1.95);
  QCOMPARE(changed.at(0).at(1).value<std::size_t>(), std::size_t{19});
  auto* slider = t.findChild<QSlider*>();
  QCOMPARE(slider->value(), slider->maximum());
  // Milliseconds from the first scan, rounded up (1.95 / 0.001 may be a hair above 1950).
  QVERIFY(slider->maximum() == 1950 || slider->maximum() == 1951);
  // A later last reading with no new scan still moves the edge.
  t.appendScanTimes({}, 2.0);
  QCOMPARE(t.time(), 2.0);
  QCOMPARE(changed.count(), 2);
  t.appendScanTimes({}, 1.0);  // an edge that does not move is no news
  QCOMPARE(changed.count(), 2);
}

void TstTimeline::elsewhereStays() {
  Timeline t;
  t.setScanTimes(times(0, 10), 0.95);
  t.setTime(0.42);
  QSignalSpy changed(&t, &Timeline::timeChanged);
  auto* slider = t.findChild<QSlider*>();
  const int knob = slider->value();
  t.appendScanTimes(times(10, 30), 2.95);
  QCOMPARE(t.time(), 0.42);
  QCOMPARE(t.currentScan(), std::size_t{4});
  QCOMPARE(t.endTime(), 2.95);
  QCOMPARE(slider->value(), knob);  // 420 ms from the start, as before
  QVERIFY(slider->maximum() == 2950 || slider->maximum() == 2951);
  QCOMPARE(changed.count(), 0);
  // The new scans are reachable.
  t.setTime(2.5);
  QCOMPARE(t.currentScan(), std::size_t{25});
  t.stepForward();
  QCOMPARE(t.time(), 2.6);
}

void TstTimeline::firstScansEnableIt() {
  Timeline t;
  t.setScanTimes({}, 0.0);  // a live log with nothing yet
  QVERIFY(!t.isEnabled());
  QSignalSpy changed(&t, &Timeline::timeChanged);
  t.appendScanTimes({}, 5.0);  // no scan: still nothing to show
  QVERIFY(!t.isEnabled());
  t.appendScanTimes(times(3, 6), 0.55);
  QVERIFY(t.isEnabled());
  QCOMPARE(t.startTime(), 0.3);
  QCOMPARE(t.time(), 0.55);
  QCOMPARE(changed.count(), 1);
}

QTEST_MAIN(TstTimeline)
#include "tst_timeline.moc"
