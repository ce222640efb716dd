// SPDX-License-Identifier: BSD-3-Clause
// Player writelog logs: a 2.x/3.x fixture with geometry, position2d, sonar and an ignored laser; a
// 1.x fixture (no type/subtype fields) whose geometry comes from a robot preset; ranger data; the
// logs written with writelog's own format strings (writer_fixtures.h); numbers it cannot hold.

#include <QtTest>
#include <string>

#include "log_fixtures.h"
#include "sonargrid/io/log_reader.h"
#include "writer_fixtures.h"

namespace {

constexpr double kInf = sg::Reading::kNoEcho;

sg::Dataset parsePlayer(const std::string& text, const sg::LogOptions& base = {}) {
  sg::LogOptions o = base;
  o.format = sg::LogFormat::Player;
  return sg::parseLog(text, "t.log", o);
}

}  // namespace

class TstPlayer : public QObject {
  Q_OBJECT
 private slots:
  void player2Fixture();
  void player2GeometryBeatsPreset();
  void player1FixtureWithPreset();
  void rangerStampedWithGeometry();
  void rangerGeometryComposesTheDevicePose();
  void rangerErrors_data();
  void rangerErrors();
  void secondDeviceIsIgnored();
  void writelogSonarFixture();
  void writelogRangerFixture();
  void printfNumbers();
  void numbersThatAreNotFinite_data();
  void numbersThatAreNotFinite();
};

void TstPlayer::player2Fixture() {
  sg::LoadReport report;
  const sg::Dataset d = sg::readLog(logtest::fixture("small_p2.playerlog"), {}, &report);
  QCOMPARE(report.format, sg::LogFormat::Player);  // detected from "## Player version"
  // Geometry from the sonar type 4 subtype 1 line: count, then x y yaw of each sonar.
  QCOMPARE(d.ring.size(), std::size_t{4});
  QCOMPARE(d.ring.sonars[1].pose, sg::Pose2D(0.0, 0.1, 1.5708));
  QCOMPARE(d.ring.sonars[2].pose, sg::Pose2D(-0.1, 0.0, 3.1416));
  // The sonar data at .020 precedes the first position2d: counted, not a scan.
  QCOMPARE(d.scans.size(), std::size_t{2});
  QCOMPARE(d.scans[0].time, 1166644800.100);
  QCOMPARE(d.scans[0].odometry, sg::Pose2D(1.0, 2.0, 0.0));
  QVERIFY(!d.scans[0].truth.has_value());
  const double r0[] = {1.5, 2.0, kInf, 0.8};  // 5.000 is the default maximum range: no echo
  for (std::size_t i = 0; i < 4; ++i) QCOMPARE(d.scans[0].readings[i].range, r0[i]);
  QCOMPARE(d.scans[1].odometry, sg::Pose2D(1.5, 2.0, 0.0));
  QCOMPARE(d.scans[1].readings[3].range, 4.999);
  QCOMPARE(d.scans[1].readings[3].time, 1166644800.200);
  using Count = std::pair<std::string, std::size_t>;
  const std::vector<Count> ignored{{"sonar data before the first position2d", 1}, {"laser 1:1", 1}};
  QCOMPARE(report.ignoredMessages, ignored);
}

void TstPlayer::player2GeometryBeatsPreset() {
  sg::LogOptions o;
  o.ring = sg::SonarRing::pioneer3dx();
  const sg::Dataset d = sg::readLog(logtest::fixture("small_p2.playerlog"), o);
  // The log's four sonars win over the preset's sixteen.
  QCOMPARE(d.ring.size(), std::size_t{4});
  QCOMPARE(d.ring.sonars[0].pose, sg::Pose2D(0.1, 0.0, 0.0));
}

void TstPlayer::player1FixtureWithPreset() {
  sg::LogOptions o;
  o.ring = sg::SonarRing::amigobot();
  sg::LoadReport report;
  const sg::Dataset d = sg::readLog(logtest::fixture("small_p1.playerlog"), o, &report);
  QCOMPARE(report.format, sg::LogFormat::Player);
  QCOMPARE(d.ring, sg::SonarRing::amigobot());
  QCOMPARE(d.scans.size(), std::size_t{2});
  // Player 1.x: `time host robot interface index payload`, position as px py pa vx vy va stall.
  QCOMPARE(d.scans[1].odometry, sg::Pose2D(0.1, 0.0, 0.05));
  QCOMPARE(d.scans[0].readings.size(), std::size_t{8});
  QCOMPARE(d.scans[0].readings[0].range, 0.5);
  QCOMPARE(d.scans[0].readings[7].range, kInf);  // 5.0 = max range
  QCOMPARE(d.scans[1].readings[7].range, 4.0);
}

void TstPlayer::rangerStampedWithGeometry() {
  // ranger 1:2 (PLAYER_RANGER_DATA_RANGESTAMPED) as Player 3's writelog writes it: count, the
  // ranges, have_geom 1, the device pose and size (9), the element count and x y z roll pitch yaw
  // of each, the size count and w l h of each; then the 7 configuration numbers.
  const sg::Dataset d = parsePlayer(
      "1.0 h 6665 position2d 0 1 1 0.5 0 0 0 0 0 0\n"
      "1.5 h 6665 ranger 0 1 2 0002 1.250 3.500 1 0 0 0 0 0 0 0.4 0.4 0 "
      "0002 +00.200 +00.000 0 0 0 +00.000 -00.200 +00.000 0 0 0 +03.140 0000 "
      "0.0 0.0 0.0 0.0 5.0 0.0 10.0\n");
  QCOMPARE(d.ring.size(), std::size_t{2});
  // The device sits at the robot's origin: the element poses are the sonar poses as logged.
  QCOMPARE(d.ring.sonars[0].pose, sg::Pose2D(0.2, 0.0, 0.0));
  QCOMPARE(d.ring.sonars[1].pose, sg::Pose2D(-0.2, 0.0, 3.14));
  QCOMPARE(d.scans[0].readings[1].range, 3.5);
  QCOMPARE(d.scans[0].odometry, sg::Pose2D(0.5, 0.0, 0.0));
}

void TstPlayer::rangerGeometryComposesTheDevicePose() {
  // The PLAYER_RANGER_REQ_GET_GEOM reply (4:1): element poses are in the device's frame. Device
  // at (1, 2) turned by 3.142 rad; element at (0.2, 0.1) turned by 0.5. Hand computation with
  // cos 3.142 = -0.99999992, sin 3.142 = -0.00040735: x = 1 - 0.19999998 + 0.00004073,
  // y = 2 - 0.00008147 - 0.09999999, yaw = 3.642.
  sg::LoadReport report;
  sg::LogOptions o;
  o.format = sg::LogFormat::Player;
  const sg::Dataset d = sg::parseLog(
      "0.5 h 6665 ranger 0 4 1 +01.000 +02.000 +00.000 +00.000 +00.000 +03.142 +00.000 +00.000 "
      "+00.000 0001 +00.200 +00.100 +00.000 +00.000 +00.000 +00.500 0000\n"
      "1.0 h 6665 position2d 0 1 1 0 0 0 0 0 0 0\n"
      "1.5 h 6665 ranger 0 1 1 0001 1.000\n",
      "t.log", o, &report);
  QCOMPARE(d.ring.size(), std::size_t{1});
  QVERIFY(
      logtest::near(d.ring.sonars[0].pose, sg::Pose2D(0.80004075123300, 1.89991853901677, 3.642)));
  QVERIFY(report.ignoredMessages.empty());
}

void TstPlayer::rangerErrors_data() {
  QTest::addColumn<QByteArray>("scan");  // the line after a position2d line
  QTest::addColumn<QByteArray>("message");
  QTest::newRow("stamped: neither nothing nor a configuration after have_geom")
      << QByteArray("1.5 h 6665 ranger 0 1 2 2 1.25 3.5 0 1 2 3\n")
      << QByteArray(
             "t.log:2: ranger: expected 4 or 11 payload fields (count, the ranges, have_geom, the "
             "geometry when have_geom is not 0, then nothing or the 7 configuration numbers), "
             "found 7");
  QTest::newRow("stamped: no have_geom")
      << QByteArray("1.5 h 6665 ranger 0 1 2 2 1.25 3.5\n")
      << QByteArray(
             "t.log:2: ranger: expected at least 4 payload fields (count, the ranges, "
             "have_geom...), found 3");
  QTest::newRow("stamped: have_geom a word")
      << QByteArray("1.5 h 6665 ranger 0 1 2 1 1.25 yes\n")
      << QByteArray("t.log:2: ranger have_geom: expected 0 or 1, found 'yes'");
  // count 1, a range, have_geom, 9 device fields, the element count and 4 of its 6 fields: 17 of
  // the 20 one element needs before the size count.
  QTest::newRow("stamped: geometry cut short")
      << QByteArray("1.5 h 6665 ranger 0 1 2 1 1.25 1 0 0 0 0 0 0 0.4 0.4 0 0001 0.2 0 0 0\n")
      << QByteArray(
             "t.log:2: ranger: expected at least 20 payload fields (px py pz proll ppitch pyaw sw "
             "sl sh, a count, x y z roll pitch yaw of each element, a count, w l h of each "
             "element), found 17");
  QTest::newRow("stamped: configuration not finite")
      << QByteArray("1.5 h 6665 ranger 0 1 2 1 1.25 0 -inf 0 0 0 5 0 10\n")
      << QByteArray(
             "t.log:2: ranger config[0]: expected a number, found '-inf', which is not finite");
  QTest::newRow("geometry: element count a word")
      << QByteArray("0.5 h 6665 ranger 0 4 1 0 0 0 0 0 0 0 0 0 two\n")
      << QByteArray("t.log:2: ranger element count: expected a count 0..65536, found 'two'");
  // 9 device fields, a count, one element of 6, a size count of 0: 17, and a stray 18th.
  QTest::newRow("geometry: a field too many")
      << QByteArray("0.5 h 6665 ranger 0 4 1 0 0 0 0 0 0 0 0 0 0001 0.2 0 0 0 0 0 0000 7\n")
      << QByteArray(
             "t.log:2: ranger: expected 17 payload fields (px py pz proll ppitch pyaw sw sl sh, a "
             "count, x y z roll pitch yaw of each element, a count, w l h of each element), "
             "found 18");
  QTest::newRow("geometry: yaw nan")
      << QByteArray("0.5 h 6665 ranger 0 4 1 0 0 0 0 0 0 0 0 0 0001 0.2 0 0 0 0 -nan 0000\n")
      << QByteArray(
             "t.log:2: ranger yaw[0]: expected an angle in radians, found '-nan', which is not "
             "finite");
}

void TstPlayer::rangerErrors() {
  QFETCH(QByteArray, scan);
  QFETCH(QByteArray, message);
  sg::LogOptions o;
  o.format = sg::LogFormat::Player;
  o.ring = sg::SonarRing::circular(2, 0.2);
  const std::string text = "1.0 h 6665 position2d 0 1 1 0.5 0 0 0 0 0 0\n" + scan.toStdString();
  try {
    sg::parseLog(text, "t.log", o);
    QFAIL("no error");
  } catch (const sg::LogError& e) {
    QCOMPARE(QByteArray(e.what()), message);
  }
}

void TstPlayer::secondDeviceIsIgnored() {
  sg::LogOptions o;
  o.ring = sg::SonarRing::circular(2, 0.2);
  sg::LoadReport report;
  o.format = sg::LogFormat::Player;
  const sg::Dataset d = sg::parseLog(
      "1.0 h 6665 position2d 0 1 1 0.5 0 0 0 0 0 0\n"
      "1.1 h 6665 position2d 1 1 1 9 9 9 0 0 0 0\n"
      "1.5 h 6665 sonar 0 1 1 2 1 2\n",
      "t.log", o, &report);
  // position2d:1 is another device (e.g. a second robot): its pose is not the odometry.
  QCOMPARE(d.scans[0].odometry, sg::Pose2D(0.5, 0.0, 0.0));
  QCOMPARE(report.ignoredMessages.size(), std::size_t{1});
  QCOMPARE(report.ignoredMessages[0].first, std::string("position2d 1:1"));
}

// A Player 3.0 log of a sonar device written with writelog's own format strings.
void TstPlayer::writelogSonarFixture() {
  sg::LoadReport report;
  const sg::Dataset d = sg::readLog(logtest::fixture("writelog_p3_sonar.playerlog"), {}, &report);
  QCOMPARE(report.format, sg::LogFormat::Player);
  const sg::Dataset expected = writer_fixtures::dataset();
  // The sonar 4:1 geometry, "%+07.3f %+07.3f %+07.4f": +00.125 +00.000 +0.0000 and so on.
  QCOMPARE(d.ring.sonars, expected.ring.sonars);
  QCOMPARE(d.scans.size(), expected.scans.size());
  for (std::size_t i = 0; i < d.scans.size(); ++i) {
    QCOMPARE(d.scans[i].time, expected.scans[i].time);
    // position2d "%+07.3f %+07.3f %+04.3f": e.g. -02.125 +03.000 +2.356.
    QCOMPARE(d.scans[i].odometry, expected.scans[i].odometry);
    QCOMPARE(d.scans[i].readings, expected.scans[i].readings);
  }
  // The position2d geometry reply (4:1) is not used.
  using Count = std::pair<std::string, std::size_t>;
  const std::vector<Count> ignored{{"position2d 4:1", 1}};
  QCOMPARE(report.ignoredMessages, ignored);
}

// A Player 3.0 log of a ranger device (how Stage 4 offers a sonar array), written with writelog's
// format strings: geometry and configuration replies, plain and stamped scans.
void TstPlayer::writelogRangerFixture() {
  sg::LoadReport report;
  const sg::Dataset d = sg::readLog(logtest::fixture("writelog_p3_ranger.playerlog"), {}, &report);
  const sg::Dataset expected = writer_fixtures::dataset();
  QCOMPARE(d.ring.size(), std::size_t{4});
  for (std::size_t i = 0; i < 4; ++i) {
    // The device at (-0.05, 0) plus the element at (x + 0.05, y) gives the ring's (x, y), within
    // rounding; the yaw is the element's, "%+07.3f": 3 decimals (1.5708 is logged as +01.571).
    const sg::Pose2D ring = expected.ring.sonars[i].pose;
    const double yaw = std::round(ring.heading * 1000.0) / 1000.0;
    QVERIFY2(logtest::near(d.ring.sonars[i].pose, sg::Pose2D(ring.x(), ring.y(), yaw)),
             qPrintable(QString::number(i)));
  }
  QCOMPARE(d.scans.size(), expected.scans.size());
  for (std::size_t i = 0; i < d.scans.size(); ++i) {
    QCOMPARE(d.scans[i].odometry, expected.scans[i].odometry);
    QCOMPARE(d.scans[i].readings, expected.scans[i].readings);
  }
  // The configuration reply (4:5) is not used: the aperture and range limits come from --robot.
  using Count = std::pair<std::string, std::size_t>;
  const std::vector<Count> ignored{{"ranger 4:5", 1}};
  QCOMPARE(report.ignoredMessages, ignored);
}

// The first position line of a real Player log, which the reader once refused
// ("position2d px: expected a number of metres, found '+00.000'").
void TstPlayer::printfNumbers() {
  const sg::Dataset d = parsePlayer(
      "1166644800.000 16777343 6665 sonar 00 004 001 2 +00.100 -00.000 +0.0000 -00.100 +00.000 "
      "+3.1416 \n"
      "1166644800.050 16777343 6665 position2d 00 001 001 +00.000 -01.500 +0.785 +00.000 -00.000 "
      "+00.000 0\n"
      "1166644800.100 16777343 6665 sonar 00 001 001 2 1.500 0.000 \n");
  QCOMPARE(d.ring.sonars[1].pose, sg::Pose2D(-0.1, 0.0, 3.1416));
  QCOMPARE(d.scans[0].odometry, sg::Pose2D(0.0, -1.5, 0.785));
  QCOMPARE(d.scans[0].readings[1].range, 0.0);
}

void TstPlayer::numbersThatAreNotFinite_data() {
  QTest::addColumn<QByteArray>("text");
  QTest::addColumn<QByteArray>("message");
  // What "%+07.3f" and "%.3f" print for an infinite or undefined value.
  const QByteArray geometry = "0.5 h 6665 sonar 0 4 1 1 0 0 0\n";
  QTest::newRow("px +inf") << geometry + "1.0 h 6665 position2d 0 1 1 +inf 0 0 0 0 0 0\n"
                           << QByteArray(
                                  "t.log:2: position2d px: expected a number of metres, found "
                                  "'+inf', which is not finite");
  QTest::newRow("pa -nan") << geometry + "1.0 h 6665 position2d 0 1 1 0 0 -nan 0 0 0 0\n"
                           << QByteArray(
                                  "t.log:2: position2d pa: expected an angle in radians, found "
                                  "'-nan', which is not finite");
  QTest::newRow("range nan") << geometry +
                                    "1.0 h 6665 position2d 0 1 1 0 0 0 0 0 0 0\n"
                                    "1.5 h 6665 sonar 0 1 1 1 nan\n"
                             << QByteArray(
                                    "t.log:3: sonar r[0]: expected a range in metres >= 0, "
                                    "found 'nan', which is not finite");
  QTest::newRow("time INF") << geometry + "INF h 6665 position2d 0 1 1 0 0 0 0 0 0 0\n"
                            << QByteArray(
                                   "t.log:2: time: expected a time in seconds, found 'INF', which "
                                   "is not finite");
  QTest::newRow("sonar yaw -inf") << QByteArray("0.5 h 6665 sonar 0 4 1 1 0 0 -inf\n")
                                  << QByteArray(
                                         "t.log:1: sonar yaw[0]: expected an angle in radians, "
                                         "found '-inf', which is not finite");
}

void TstPlayer::numbersThatAreNotFinite() {
  QFETCH(QByteArray, text);
  QFETCH(QByteArray, message);
  sg::LogOptions o;
  o.format = sg::LogFormat::Player;
  try {
    sg::parseLog(text.toStdString(), "t.log", o);
    QFAIL("no error");
  } catch (const sg::LogError& e) {
    QCOMPARE(QByteArray(e.what()), message);
  }
}

QTEST_GUILESS_MAIN(TstPlayer)
#include "tst_player.moc"
