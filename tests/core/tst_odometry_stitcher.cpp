// SPDX-License-Identifier: BSD-3-Clause
// Odometry across reconnects (arcos/odometry_stitcher.h, docs/live-robot.md "Reconnects"): the
// first connection's scans pass unchanged; a later connection whose controller restarted its
// odometry is placed rigidly onto the last pose, moved by what the true poses say the robot drove
// while the link was down. Every expected pose below is worked by hand in its comment.

#include <QtTest>
#include <cmath>
#include <numbers>
#include <vector>

#include "sonargrid/arcos/odometry_stitcher.h"

using sg::Pose2D;
using sg::Scan;
using sg::arcos::OdometryStitcher;

namespace {

Scan scanAt(double time, const Pose2D& odometry, std::optional<Pose2D> truth = std::nullopt) {
  Scan s;
  s.time = time;
  s.odometry = odometry;
  s.truth = truth;
  s.readings.push_back({0, 1.0, time});
  return s;
}

bool near(const Pose2D& a, const Pose2D& b) {
  return (a.position - b.position).norm() < 1e-12 && std::abs(a.heading - b.heading) < 1e-12;
}

QByteArray text(const Pose2D& p) {
  return QByteArray::number(p.x(), 'g', 17) + ", " + QByteArray::number(p.y(), 'g', 17) + ", " +
         QByteArray::number(p.heading, 'g', 17);
}

constexpr double kQuarter = std::numbers::pi / 2;

}  // namespace

class TstOdometryStitcher : public QObject {
  Q_OBJECT

 private slots:
  void firstSegmentPassesUnchanged() {
    OdometryStitcher s;
    std::vector<Scan> out;
    s.newSegment();
    const Scan a = scanAt(0.1, Pose2D(0.3, -0.7, 2.9));
    const Scan b = scanAt(0.2, Pose2D(0.4, -0.7, 3.1));
    s.add(a, false, out);
    s.add(b, false, out);
    QCOMPARE(out.size(), std::size_t{2});
    QCOMPARE(out[0], a);  // bit for bit
    QCOMPARE(out[1], b);
    QCOMPARE(s.segments(), std::uint64_t{1});
    QCOMPARE(s.stitched(), std::uint64_t{0});
  }

  // Segment 1 ends at (2, 1) m facing +y. The robot is switched back on where it stands: its
  // odometry says (0, 0, 0), then (1, 0, 0), one metre ahead. Stitched, the first is (2, 1, 90°)
  // and the second one metre ahead of it along +y: (2, 2, 90°).
  void aRestartedOdometryContinuesFromTheLastPose() {
    OdometryStitcher s;
    std::vector<Scan> out;
    s.newSegment();
    s.add(scanAt(1.0, Pose2D(2.0, 1.0, kQuarter)), false, out);
    s.newSegment();
    s.add(scanAt(3.0, Pose2D(0.0, 0.0, 0.0)), false, out);
    s.add(scanAt(3.1, Pose2D(1.0, 0.0, 0.0)), false, out);
    QCOMPARE(out.size(), std::size_t{3});
    QVERIFY2(near(out[1].odometry, Pose2D(2.0, 1.0, kQuarter)), text(out[1].odometry));
    QVERIFY2(near(out[2].odometry, Pose2D(2.0, 2.0, kQuarter)), text(out[2].odometry));
    QCOMPARE(out[2].readings, scanAt(3.1, Pose2D()).readings);
    QCOMPARE(s.segments(), std::uint64_t{2});
    QCOMPARE(s.stitched(), std::uint64_t{1});
  }

  // The robot drove 0.1 m between its controller's restart and the first SIP: the odometry's
  // origin, not that first scan, is the last pose, (2, 1, 90°): the scans at odometry (0.1, 0, 0)
  // and (0.6, 0, 0) land 0.1 and 0.6 m along +y from it. Odometry that restarted far from 0
  // (7, 7, 0) puts its first scan at the last pose, the next, 1 m ahead, at (2, 2, 90°).
  void theRestartedOriginIsTheLastPose() {
    for (const bool nearZero : {true, false}) {
      OdometryStitcher s;
      std::vector<Scan> out;
      s.newSegment();
      s.add(scanAt(1.0, Pose2D(2.0, 1.0, kQuarter)), false, out);
      s.newSegment();
      const Pose2D first = nearZero ? Pose2D(0.1, 0.0, 0.0) : Pose2D(7.0, 7.0, 0.0);
      const Pose2D second = nearZero ? Pose2D(0.6, 0.0, 0.0) : Pose2D(8.0, 7.0, 0.0);
      s.add(scanAt(3.0, first), false, out);
      s.add(scanAt(3.1, second), false, out);
      const Pose2D want1 = nearZero ? Pose2D(2.0, 1.1, kQuarter) : Pose2D(2.0, 1.0, kQuarter);
      const Pose2D want2 = nearZero ? Pose2D(2.0, 1.6, kQuarter) : Pose2D(2.0, 2.0, kQuarter);
      QVERIFY2(near(out[1].odometry, want1), text(out[1].odometry));
      QVERIFY2(near(out[2].odometry, want2), text(out[2].odometry));
    }
  }

  // A controller that kept its odometry across the reconnect: the new segment starts 1 cm from
  // where the last ended (within kSamePlaceM) and is left as it is.
  void aKeptOdometryIsNotStitched() {
    OdometryStitcher s;
    std::vector<Scan> out;
    s.newSegment();
    s.add(scanAt(1.0, Pose2D(2.0, 1.0, kQuarter)), false, out);
    s.newSegment();
    const Scan next = scanAt(3.0, Pose2D(2.01, 1.0, kQuarter));
    s.add(next, false, out);
    QCOMPARE(out.back(), next);
    QCOMPARE(s.stitched(), std::uint64_t{0});
  }

  // A simulator: segment 1 ends at odometry (2, 1, 0), true pose (5, 5, 0). While the link was
  // down the robot drove on along +x. The new segment's first scan has no true pose (a SIP before
  // the first SIMSTAT) and waits; its second, at odometry (0.5, 0, 0), has the true pose
  // (6.5, 5, 0): the robot moved (1.5, 0, 0) since the last scan, so that scan is placed at
  // (2, 1, 0) + 1.5 m = (3.5, 1, 0), and the segment's frame is offset by (3, 1, 0): the first
  // scan, at odometry (0, 0, 0), lands at (3, 1, 0).
  void trueMotionWhileDownIsKept() {
    OdometryStitcher s;
    std::vector<Scan> out;
    s.newSegment();
    s.add(scanAt(1.0, Pose2D(2.0, 1.0, 0.0), Pose2D(5.0, 5.0, 0.0)), true, out);
    s.newSegment();
    s.add(scanAt(4.0, Pose2D(0.0, 0.0, 0.0)), true, out);
    QCOMPARE(out.size(), std::size_t{1});  // held for a true pose
    s.add(scanAt(4.1, Pose2D(0.5, 0.0, 0.0), Pose2D(6.5, 5.0, 0.0)), true, out);
    QCOMPARE(out.size(), std::size_t{3});
    QVERIFY2(near(out[1].odometry, Pose2D(3.0, 1.0, 0.0)), text(out[1].odometry));
    QVERIFY2(near(out[2].odometry, Pose2D(3.5, 1.0, 0.0)), text(out[2].odometry));
    QVERIFY(out[1].time < out[2].time);
    QCOMPARE(*out[2].truth, Pose2D(6.5, 5.0, 0.0));  // true poses are not touched
    QCOMPARE(s.stitched(), std::uint64_t{1});
  }

  // No true pose comes: after kMaxHeld scans the segment is placed as if the robot had not moved;
  // scans still held when the connection ends are delivered the same way.
  void heldScansAreNeverLost() {
    for (const std::size_t n : {OdometryStitcher::kMaxHeld, std::size_t{3}}) {
      OdometryStitcher s;
      std::vector<Scan> out;
      s.newSegment();
      s.add(scanAt(1.0, Pose2D(2.0, 1.0, 0.0), Pose2D(5.0, 5.0, 0.0)), true, out);
      s.newSegment();
      for (std::size_t i = 0; i < n; ++i)
        s.add(scanAt(2.0 + 0.1 * double(i), Pose2D(0.1 * double(i), 0.0, 0.0)), true, out);
      if (n < OdometryStitcher::kMaxHeld) {
        QCOMPARE(out.size(), std::size_t{1});
        s.flush(out);
      }
      QCOMPARE(out.size(), 1 + n);
      // Not moved: the first is at the last pose, the rest 0.1 m apart along +x.
      for (std::size_t i = 0; i < n; ++i)
        QVERIFY2(near(out[1 + i].odometry, Pose2D(2.0 + 0.1 * double(i), 1.0, 0.0)),
                 text(out[1 + i].odometry));
    }
  }
};

QTEST_GUILESS_MAIN(TstOdometryStitcher)
#include "tst_odometry_stitcher.moc"
