// Player writelog logs: a 2.x/3.x fixture with geometry, position2d, sonar and an ignored laser; a
// 1.x fixture (no type/subtype fields) whose geometry comes from a robot preset; ranger data.

#include <QtTest>
#include <string>

#include "log_fixtures.h"
#include "sonargrid/io/log_reader.h"

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
  void rangerWithPoses();
  void secondDeviceIsIgnored();
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

void TstPlayer::rangerWithPoses() {
  // ranger type 1 subtype 2: count, the ranges, then x y yaw of each element.
  const sg::Dataset d = parsePlayer(
      "1.0 h 6665 position2d 0 1 1 0.5 0 0 0 0 0 0\n"
      "1.5 h 6665 ranger 0 1 2 2 1.25 3.5 0.2 0 0 -0.2 0 3.14\n");
  QCOMPARE(d.ring.size(), std::size_t{2});
  QCOMPARE(d.ring.sonars[1].pose, sg::Pose2D(-0.2, 0.0, 3.14));
  QCOMPARE(d.scans[0].readings[1].range, 3.5);
  QCOMPARE(d.scans[0].odometry, sg::Pose2D(0.5, 0.0, 0.0));
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

QTEST_GUILESS_MAIN(TstPlayer)
#include "tst_player.moc"
