// SPDX-License-Identifier: BSD-3-Clause
// CARMEN logs: the hand-written fixture (ODOM, TRUEPOS, SONAR with the ring on the line, skipped
// message types, a SONAR line with extra fields), a log written with the logger's own format
// strings (writer_fixtures.h), numbers that are not finite, and the writer's round trip.

#include <QtTest>
#include <cmath>
#include <sstream>
#include <string>

#include "log_fixtures.h"
#include "sonargrid/io/carmen.h"
#include "sonargrid/io/log_reader.h"
#include "writer_fixtures.h"

namespace {

constexpr double kInf = sg::Reading::kNoEcho;

sg::Dataset parseCarmen(const std::string& text, sg::LoadReport* report = nullptr) {
  sg::LogOptions o;
  o.format = sg::LogFormat::Carmen;
  return sg::parseLog(text, "t.clf", o, report);
}

}  // namespace

class TstCarmen : public QObject {
  Q_OBJECT
 private slots:
  void readFixture();
  void ignoredMessagesAreCounted();
  void truthComesFromTheLatestTruepos();
  void odometryFromTrueposWhenNoOdom();
  void loggerFixture();
  void numbersThatAreNotFinite_data();
  void numbersThatAreNotFinite();
  void roundTrip();
  void writerFillsMissingSonarsAndSplitsRepeats();
  void writerRejects();
};

void TstCarmen::readFixture() {
  sg::LoadReport report;
  const sg::Dataset d = sg::readLog(logtest::fixture("small.clf"), {}, &report);
  QCOMPARE(report.format, sg::LogFormat::Carmen);  // detected from the "# CARMEN" comment
  QCOMPARE(report.lines, std::size_t{12});         // every line, comments included
  // The ring: the first SONAR line's cone angle and the four (x y theta) triples.
  QCOMPARE(d.ring.apertureRad, 0.4363);
  QCOMPARE(d.ring.size(), std::size_t{4});
  QCOMPARE(d.ring.sonars[1].pose, sg::Pose2D(0.0, 0.1, 1.5708));
  QCOMPARE(d.ring.sonars[3].pose, sg::Pose2D(0.0, -0.1, -1.5708));
  QCOMPARE(d.ring.maxRange, 5.0);  // the SonarRing default: CARMEN does not carry it
  QCOMPARE(d.scans.size(), std::size_t{2});
  const sg::Scan& a = d.scans[0];
  QCOMPARE(a.time, 1000.1);  // the SONAR line's ipc_timestamp
  QCOMPARE(a.odometry, sg::Pose2D(1.0, 2.0, 0.0));
  QVERIFY(a.truth.has_value());
  QCOMPARE(*a.truth, sg::Pose2D(1.05, 2.0, 0.01));
  // 5.0 is the maximum range: no echo.
  const double ranges0[] = {1.5, 2.0, kInf, 0.8};
  QCOMPARE(a.readings.size(), std::size_t{4});
  for (std::size_t i = 0; i < 4; ++i) {
    QCOMPARE(a.readings[i].sonar, static_cast<std::uint16_t>(i));
    QCOMPARE(a.readings[i].range, ranges0[i]);
    QCOMPARE(a.readings[i].time, 1000.1);
  }
  // The second SONAR line has five extra fields (CARMEN 0.7's robot pose, tv, rv) before the
  // timestamps: they are skipped, the pose is the latest ODOM.
  const sg::Scan& b = d.scans[1];
  QCOMPARE(b.time, 1005.2);
  QCOMPARE(b.odometry, sg::Pose2D(1.5, 2.0, 0.0));
  QCOMPARE(b.readings[3].range, 4.999);
  QCOMPARE(b.readings[2].range, 0.5);
}

void TstCarmen::ignoredMessagesAreCounted() {
  sg::LoadReport report;
  sg::readLog(logtest::fixture("small.clf"), {}, &report);
  using Count = std::pair<std::string, std::size_t>;
  const std::vector<Count> expected{{"PARAM", 1}, {"SYNC", 1}, {"FLASER", 1}};
  QCOMPARE(report.ignoredMessages, expected);
  QCOMPARE(report.skippedLines, std::size_t{0});
}

void TstCarmen::truthComesFromTheLatestTruepos() {
  const sg::Dataset d = sg::readLog(logtest::fixture("small.clf"));
  // No TRUEPOS between the two SONAR lines: the second scan keeps the latest one.
  QCOMPARE(*d.scans[1].truth, sg::Pose2D(1.05, 2.0, 0.01));
  QVERIFY(d.hasTruth());
}

void TstCarmen::odometryFromTrueposWhenNoOdom() {
  const sg::Dataset d = parseCarmen(
      "TRUEPOS 1 2 0.5 1.1 2.1 0.4 7.0 h 7.0\n"
      "SONAR 0.5 1 2.5 0 0 0 7.5 h 7.5\n");
  QCOMPARE(d.scans.size(), std::size_t{1});
  // TRUEPOS carries odom_x odom_y odom_theta after the true pose.
  QCOMPARE(d.scans[0].odometry, sg::Pose2D(1.1, 2.1, 0.4));
  QCOMPARE(*d.scans[0].truth, sg::Pose2D(1.0, 2.0, 0.5));
  QCOMPARE(d.scans[0].readings[0].range, 2.5);
}

// CARMEN 0.7's logger: ODOM and TRUEPOS "%f", SONAR "%f %d", ranges "%.2lf", offsets
// "%.3f %.3f %f", "%lf %s %lf" at the end; PARAM and SYNC lines around them.
void TstCarmen::loggerFixture() {
  sg::LoadReport report;
  const sg::Dataset d = sg::readLog(logtest::fixture("logger_07.clf"), {}, &report);
  QCOMPARE(report.format, sg::LogFormat::Carmen);  // "# CARMEN Logfile"
  // Every value of the table, negative, zero and positive, as the logger printed it: e.g. ODOM
  // -2.125000 3.000000 2.356000, TRUEPOS -2.100000 2.950000 2.400000, SONAR 0.436300 and ranges
  // 3.33 0.25 1.00 5.00 (5.00 is the default maximum range: no echo).
  QVERIFY(d == writer_fixtures::dataset());
  using Count = std::pair<std::string, std::size_t>;
  const std::vector<Count> ignored{{"PARAM", 1}, {"SYNC", 1}};
  QCOMPARE(report.ignoredMessages, ignored);
}

void TstCarmen::numbersThatAreNotFinite_data() {
  QTest::addColumn<QByteArray>("text");
  QTest::addColumn<QByteArray>("message");
  // What "%f" and "%lf" print for an infinite or undefined value.
  QTest::newRow("ODOM x inf") << QByteArray("ODOM inf 0 0 0 0 0 1 h 1\n")
                              << QByteArray(
                                     "t.clf:1: ODOM x: expected a number of metres, found 'inf', "
                                     "which is not finite");
  QTest::newRow("TRUEPOS odom_theta -nan")
      << QByteArray("TRUEPOS 0 0 0 0 0 -nan 1 h 1\n")
      << QByteArray(
             "t.clf:1: TRUEPOS odom_theta: expected an angle in radians, found '-nan', which is "
             "not finite");
  QTest::newRow("SONAR range nan")
      << QByteArray("ODOM 0 0 0 0 0 0 1 h 1\nSONAR 0.436300 1 nan 0 0 0 2 h 2\n")
      << QByteArray(
             "t.clf:2: SONAR r[0]: expected a range in metres >= 0, found 'nan', which is not "
             "finite");
  QTest::newRow("SONAR timestamp -inf")
      << QByteArray("ODOM 0 0 0 0 0 0 1 h 1\nSONAR 0.436300 1 1.00 0 0 0 -inf h 2\n")
      << QByteArray(
             "t.clf:2: SONAR ipc_timestamp: expected a time in seconds, found '-inf', which is "
             "not finite");
  QTest::newRow("SONAR cone out of range")
      << QByteArray("ODOM 0 0 0 0 0 0 1 h 1\nSONAR 1e400 1 1.00 0 0 0 2 h 2\n")
      << QByteArray(
             "t.clf:2: SONAR cone_angle: expected a full cone angle in radians > 0 and <= pi, "
             "found '1e400', which is out of the range of a double");
}

void TstCarmen::numbersThatAreNotFinite() {
  QFETCH(QByteArray, text);
  QFETCH(QByteArray, message);
  try {
    parseCarmen(text.toStdString());
    QFAIL("no error");
  } catch (const sg::LogError& e) {
    QCOMPARE(QByteArray(e.what()), message);
  }
}

void TstCarmen::roundTrip() {
  sg::Dataset d;
  d.name = "CARMEN log";
  d.ring = sg::SonarRing::amigobot();
  d.ring.robot = "custom";  // CARMEN does not carry the preset name
  for (int k = 0; k < 3; ++k) {
    sg::Scan& s = d.scans.emplace_back();
    s.time = 10.0 + 0.1 * k;
    s.odometry = sg::Pose2D(0.1 * k, -0.2, 0.3 * k);
    if (k != 1) s.truth = sg::Pose2D(0.1 * k + 0.01, -0.21, 0.3 * k + 0.02);
    for (std::uint16_t i = 0; i < 8; ++i) {
      const double r = (i + k) % 3 == 0 ? kInf : 0.25 + 0.5 * i + 0.01 * k;
      s.readings.push_back(sg::Reading{i, r, s.time});
    }
  }
  std::ostringstream out;
  sg::writeCarmen(d, out);
  sg::Dataset back = parseCarmen(out.str());
  // Scan 1 has no TRUEPOS of its own, so it reads back with scan 0's (the latest).
  QCOMPARE(*back.scans[1].truth, *d.scans[0].truth);
  back.scans[1].truth.reset();
  QCOMPARE(back, d);
}

void TstCarmen::writerFillsMissingSonarsAndSplitsRepeats() {
  sg::Dataset d;
  d.ring = sg::SonarRing::circular(2, 0.5);  // sonars at (0.5, 0, 0) and (-0.5, 0, -pi)
  d.ring.apertureRad = 0.5;
  d.ring.maxRange = 4.0;
  sg::Scan& s = d.scans.emplace_back();
  s.time = 2.0;
  s.odometry = sg::Pose2D(1, 2, 0);
  s.readings = {sg::Reading{1, 1.5, 2.0}, sg::Reading{1, 2.5, 2.0}};
  std::ostringstream out;
  sg::writeCarmen(d, out);
  const std::string text = out.str();
  // Sonar 0 has no reading: written at max_range (4). Sonar 1 twice: two SONAR lines.
  QVERIFY(text.find("ODOM 1 2 0 0 0 0 2 sonargrid 2\n") != std::string::npos);
  QVERIFY(text.find("SONAR 0.5 2 4 1.5 0.5 0 0 -0.5 ") != std::string::npos);
  QVERIFY(text.find("SONAR 0.5 2 4 2.5 0.5 0 0 -0.5 ") != std::string::npos);
}

void TstCarmen::writerRejects() {
  sg::Dataset d;  // a ring without sonars cannot be written
  std::ostringstream out;
  QVERIFY_THROWS_EXCEPTION(std::runtime_error, sg::writeCarmen(d, out));
}

QTEST_GUILESS_MAIN(TstCarmen)
#include "tst_carmen.moc"
