// SPDX-License-Identifier: BSD-3-Clause
// A ROS bag read as a sonar log (docs/formats.md, "ROS bags"): the bundled room log converted by
// the real writers (python3-rosbag for ROS 1; npm's @mcap/core and @foxglove/rosmsg2-serialization
// for MCAP; SQLite with those CDR bytes for rosbag2's .db3; tests/data/bags/room/README.md) maps
// to the .sglog's grid bit for bit in every container; a RosAria-style bag (PointCloud + Odometry,
// no tf) loads with the robot preset; topics are picked and reported; bad messages are named.

#include <QFile>
#include <QTemporaryDir>
#include <QTest>
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <string>

#include "sonargrid/base/log_error.h"
#include "sonargrid/engine/mapper.h"
#include "sonargrid/io/bag/bag_log.h"
#include "sonargrid/io/log_reader.h"

using namespace sg;

namespace {

const std::string kRoom = SONARGRID_DATASETS "/room/room.sglog";
const std::string kBags = SONARGRID_TEST_DATA "/bags/room/";

const Dataset& sglog() {
  static const Dataset d = readLog(kRoom);
  return d;
}

bool sameLayers(const OccupancyMap& a, const OccupancyMap& b) {
  // Bit-identical: the doubles' bytes, not their values within a tolerance.
  return a.spec == b.spec && a.level == b.level && a.filled == b.filled &&
         a.observed == b.observed && a.probability.identical(b.probability) &&
         a.native.identical(b.native) && a.evidence.identical(b.evidence);
}

OccupancyMap mapOf(const Dataset& d, const std::string& model, const std::string& rule,
                   PoseSource pose) {
  MapperSettings s;
  s.model = model;
  s.rule = rule;
  s.parameters = defaultParameters(model, rule);
  s.pose = pose;
  Mapper m(d.ring, d.fittingGrid(pose, 0.05), s);
  m.mapDataset(d);
  return m.snapshot();
}

// The .sglog's map of a pair, made once for every bag that is compared with it.
const OccupancyMap& sglogMap(const std::string& model, const std::string& rule, PoseSource pose) {
  static std::map<std::string, OccupancyMap> maps;
  const std::string key = model + "/" + rule + (pose == PoseSource::Truth ? "/truth" : "/odom");
  auto it = maps.find(key);
  if (it == maps.end()) it = maps.emplace(key, mapOf(sglog(), model, rule, pose)).first;
  return it->second;
}

QByteArray readAll(const std::string& path) {
  QFile f(QString::fromStdString(path));
  if (!f.open(QIODevice::ReadOnly)) return {};
  return f.readAll();
}

std::string errorOf(const std::string& path, const LogOptions& o = {}) {
  try {
    readLog(path, o);
  } catch (const LogError& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("unexpected exception: ") + e.what();
  }
  return "no error";
}

}  // namespace

class TstBagLog : public QObject {
  Q_OBJECT

 private slots:
  void everyContainerGivesTheSglogsLog_data();
  void everyContainerGivesTheSglogsLog();
  void everyContainerMapsToTheSglogsGrid_data();
  void everyContainerMapsToTheSglogsGrid();
  void sonarPosesComeFromTfStatic();
  void aRosAriaBagLoadsWithTheRobotsRing();
  void topicsArePickedAndReported();
  void aPreviewIsTheLogsFirstSeconds_data();
  void aPreviewIsTheLogsFirstSeconds();
  void chosenTopicsOverrideThePicks();
  void aBadMessageIsNamedByFileOffsetAndTopic();
  void aCutBagIsAnErrorOrPartOfTheLog();
  void readingsOutsideTheOdometryAreLeftOutAndReported();
  void floatFieldsWidenToTheirShortestDecimal();
};

void TstBagLog::everyContainerGivesTheSglogsLog_data() {
  QTest::addColumn<QString>("bag");
  QTest::newRow("ROS 1, uncompressed") << "room-none.bag";
  QTest::newRow("ROS 1, bz2 chunks") << "room-bz2.bag";
  QTest::newRow("ROS 1, lz4 chunks") << "room-lz4.bag";
  QTest::newRow("MCAP, zstd chunks") << "room-zstd.mcap";
  QTest::newRow("MCAP, lz4 chunks") << "room-lz4.mcap";
  QTest::newRow("rosbag2 SQLite folder") << "room-sqlite";
  QTest::newRow("rosbag2 SQLite metadata.yaml") << "room-sqlite/metadata.yaml";
}

void TstBagLog::everyContainerGivesTheSglogsLog() {
  QFETCH(QString, bag);
  LoadReport report;
  const Dataset d = readLog(kBags + bag.toStdString(), {}, &report);
  const Dataset& s = sglog();
  QCOMPARE(report.format, LogFormat::Bag);
  // The ring: every pose from /tf_static, the field of view (25 degrees in float32) and the
  // ranges from the Range messages; named p3dx because it is that preset exactly.
  QVERIFY(d.ring == s.ring);
  QCOMPARE(d.ring.robot, std::string("p3dx"));
  // 743 scans of 16 readings (room.sglog), each at its scan's time and poses.
  QCOMPARE(d.scans.size(), std::size_t{743});
  QCOMPARE(d.scans.size(), s.scans.size());
  for (std::size_t k = 0; k < s.scans.size(); ++k) {
    const Scan& a = d.scans[k];
    const Scan& b = s.scans[k];
    QCOMPARE(a.time, b.time);
    QVERIFY(a.odometry == b.odometry);
    QVERIFY(a.truth.has_value() && b.truth.has_value() && *a.truth == *b.truth);
    QCOMPARE(a.readings.size(), b.readings.size());
    for (std::size_t r = 0; r < b.readings.size(); ++r) {
      QCOMPARE(a.readings[r].sonar, b.readings[r].sonar);
      // Ranges are float32 in sensor_msgs/Range; each reads back as its decimal (widen()).
      QCOMPARE(a.readings[r].range, b.readings[r].range);
      // A Range message has one stamp, the scan's (the converter's choice, as RosAria stamps a
      // ring once): the .sglog's staggered reading times are not in the bag.
      QCOMPARE(a.readings[r].time, b.time);
    }
  }
}

void TstBagLog::everyContainerMapsToTheSglogsGrid_data() {
  // The six bags (the folder's metadata.yaml reads the same storage as the folder).
  QTest::addColumn<QString>("bag");
  for (const char* b : {"room-none.bag", "room-bz2.bag", "room-lz4.bag", "room-zstd.mcap",
                        "room-lz4.mcap", "room-sqlite"}) {
    QTest::newRow(b) << QString::fromLatin1(b);
  }
}

void TstBagLog::everyContainerMapsToTheSglogsGrid() {
  QFETCH(QString, bag);
  const Dataset d = readLog(kBags + bag.toStdString());
  // One pair per model, on odometry and on the true pose.
  const char* pairs[][2] = {{"hpf", "bayes"},
                            {"himm", "himm"},
                            {"konolige", "dempster-shafer"},
                            {"murphy", "logodds"},
                            {"parameterized", "addition"}};
  for (const auto& [model, rule] : pairs) {
    for (const PoseSource pose : {PoseSource::Odometry, PoseSource::Truth}) {
      QVERIFY2(sameLayers(mapOf(d, model, rule, pose), sglogMap(model, rule, pose)),
               (std::string(model) + " x " + rule).c_str());
    }
  }
}

void TstBagLog::sonarPosesComeFromTfStatic() {
  const Dataset d = readLog(kBags + "room-none.bag");
  QCOMPARE(d.ring.size(), std::size_t{16});
  // Sonar 0 and 11 of the Pioneer 3-DX ring as room.sglog's header lists them (x y theta):
  // "sonar 0 0.069 0.136 1.5707963267948966" and "sonar 11 -0.255 -0.027 -2.9670597283903604";
  // in the bag, base_link -> sonar_0 and sonar_11 of /tf_static.
  QCOMPARE(d.ring.sonars[0].pose.x(), 0.069);
  QCOMPARE(d.ring.sonars[0].pose.y(), 0.136);
  QCOMPARE(d.ring.sonars[0].pose.heading, std::numbers::pi / 2);
  QCOMPARE(d.ring.sonars[11].pose.x(), -0.255);
  QCOMPARE(d.ring.sonars[11].pose.y(), -0.027);
  QCOMPARE(d.ring.sonars[11].pose.heading, -2.9670597283903604);
  // sonar_10 sorts after sonar_9, not after sonar_1: the frames' natural order.
  QCOMPARE(d.ring.sonars[10].pose.x(), -0.237);
  // 25 degrees (float32 0.43633232 in field_of_view) reads as exactly degToRad(25).
  QCOMPARE(d.ring.apertureRad, degToRad(25.0));
  QCOMPARE(d.ring.minRange, 0.15);
  QCOMPARE(d.ring.maxRange, 5.0);
}

void TstBagLog::aRosAriaBagLoadsWithTheRobotsRing() {
  const std::string bag = kBags + "rosaria-room.bag";
  // The points carry no transducer: without the robot the reader says what to give.
  const std::string e = errorOf(bag);
  QVERIFY2(
      e.find("rosaria-room.bag") != std::string::npos && e.find("--robot") != std::string::npos,
      e.c_str());
  LogOptions o;
  o.ring = SonarRing::pioneer3dx();
  LoadReport report;
  const Dataset d = readLog(bag, o, &report);
  QCOMPARE(
      report.notes.at(0).rfind("sonar: /RosAria/sonar (sensor_msgs/PointCloud, 743 messages)", 0),
      std::size_t{0});
  QCOMPARE(report.notes.at(1).rfind("odometry: /RosAria/pose (nav_msgs/Odometry, 743 messages)", 0),
           std::size_t{0});
  const Dataset& s = sglog();
  QCOMPARE(d.scans.size(), s.scans.size());
  QVERIFY(!d.hasTruth());
  std::size_t echoes = 0;
  for (std::size_t k = 0; k < s.scans.size(); ++k) {
    QVERIFY(d.scans[k].odometry == s.scans[k].odometry);
    QCOMPARE(d.scans[k].readings.size(), std::size_t{16});
    for (std::size_t r = 0; r < 16; ++r) {
      const Reading& a = d.scans[k].readings[r];
      const Reading& b = s.scans[k].readings[r];
      QCOMPARE(a.sonar, b.sonar);
      QCOMPARE(a.echo(), b.echo());
      if (!b.echo()) continue;
      ++echoes;
      // The point is the sonar's position plus the range along its axis, in float32 (about 7
      // digits at a few metres: within 1e-6 m); the range is its distance from the sonar.
      QVERIFY2(std::abs(a.range - b.range) < 2e-6,
               (std::to_string(a.range) + " vs " + std::to_string(b.range)).c_str());
    }
  }
  QVERIFY(echoes > 10000);
}

void TstBagLog::aPreviewIsTheLogsFirstSeconds_data() {
  QTest::addColumn<QString>("bag");
  QTest::newRow("ROS 1, 3 uncompressed chunks") << "room-none.bag";
  QTest::newRow("MCAP, 2 zstd chunks") << "room-zstd.mcap";
  QTest::newRow("rosbag2 SQLite") << "room-sqlite";
}

// The bag import dialog's preview (bag::previewBag): the scans of the first 10 s of log time are
// the full log's first scans, unchanged. room.sglog has a scan every 0.1 s from 0 to 74.2 s and its
// bags log every message at its stamp, so the preview holds the scans at 0.0, 0.1, ..., 10.0 s:
// those of the .sglog with time <= 10 s (101).
void TstBagLog::aPreviewIsTheLogsFirstSeconds() {
  QFETCH(QString, bag);
  LogOptions o;
  LoadReport report;
  const Dataset p = bag::previewBag(kBags + bag.toStdString(), o, 10.0, report);
  const Dataset& s = sglog();
  std::size_t expected = 0;
  while (expected < s.scans.size() && s.scans[expected].time <= 10.0) ++expected;
  QCOMPARE(expected, std::size_t{101});
  QCOMPARE(p.scans.size(), expected);
  const Dataset full = readLog(kBags + bag.toStdString());
  QVERIFY(p.ring == full.ring);
  for (std::size_t k = 0; k < p.scans.size(); ++k) QVERIFY(p.scans[k] == full.scans[k]);
}

void TstBagLog::topicsArePickedAndReported() {
  const bag::Overview o = bag::inspectBag(kBags + "room-zstd.mcap");
  QCOMPARE(o.container, bag::Container::Mcap);
  // The converter's topics (tests/data/bags/room/README.md) and their counts: 1 /tf_static, one
  // /odom and one /ground_truth per scan (743), one /sonar per reading (743 x 16 = 11888).
  auto count = [&o](const std::string& name) -> std::uint64_t {
    for (const bag::Topic& t : o.topics) {
      if (t.name == name) return t.count;
    }
    return 0;
  };
  QCOMPARE(o.topics.size(), std::size_t{4});
  QCOMPARE(count("/tf_static"), std::uint64_t{1});
  QCOMPARE(count("/odom"), std::uint64_t{743});
  QCOMPARE(count("/ground_truth"), std::uint64_t{743});
  QCOMPARE(count("/sonar"), std::uint64_t{11888});
  QCOMPARE(o.picks.sonar, std::vector<std::string>{"/sonar"});
  QCOMPARE(o.picks.odometry, std::string("/odom"));
  QCOMPARE(o.picks.truth, std::string("/ground_truth"));
  LoadReport report;
  readLog(kBags + "room-zstd.mcap", {}, &report);
  QCOMPARE(report.notes.at(0),
           std::string("sonar: /sonar (sensor_msgs/Range, 11888 messages), picked"));
  QCOMPARE(report.notes.at(1),
           std::string("odometry: /odom (nav_msgs/Odometry, 743 messages), picked"));
  QCOMPARE(
      report.notes.at(2),
      std::string("true pose: /ground_truth (geometry_msgs/PoseStamped, 743 messages), picked"));
}

void TstBagLog::chosenTopicsOverrideThePicks() {
  LogOptions o;
  o.topics.truth = "-";  // no true pose
  const Dataset d = readLog(kBags + "room-lz4.mcap", o);
  QVERIFY(!d.hasTruth());
  QCOMPARE(d.scans.size(), std::size_t{743});
  o.topics.odometry = "/nope";
  const std::string e = errorOf(kBags + "room-lz4.mcap", o);
  QVERIFY2(
      e.find("room-lz4.mcap: topics: the odometry topic /nope is not in the bag; its topics: ") ==
              0 ||
          e.find("the odometry topic /nope is not in the bag") != std::string::npos,
      e.c_str());
  QVERIFY2(e.find("/sonar (sensor_msgs/Range)") != std::string::npos, e.c_str());
  o.topics.odometry.clear();
  o.topics.sonar = {"/odom"};
  const std::string e2 = errorOf(kBags + "room-lz4.mcap", o);
  QVERIFY2(e2.find("the sonar topic /odom holds") != std::string::npos, e2.c_str());
}

void TstBagLog::aBadMessageIsNamedByFileOffsetAndTopic() {
  // room-none.bag stores its messages as written: a Range of sonar 0 starts, after its seq and
  // stamp, with frame_id's length 7 and "sonar_0" (ROS 1 serialisation). The first such bytes
  // are /tf_static's child_frame_id, the second the first Range's frame_id; its length becomes
  // 0xFFFFFF07, past the end of the message.
  QByteArray bytes = readAll(kBags + "room-none.bag");
  QVERIFY(!bytes.isEmpty());
  const QByteArray needle("\x07\x00\x00\x00sonar_0", 11);
  const qsizetype at = bytes.indexOf(needle, bytes.indexOf(needle) + 1);
  QVERIFY(at > 0);
  bytes[at + 3] = '\xFF';
  bytes[at + 2] = '\xFF';
  bytes[at + 1] = '\xFF';
  QTemporaryDir dir;
  const std::string path = dir.filePath("bad.bag").toStdString();
  {
    QFile f(QString::fromStdString(path));
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write(bytes);
  }
  const std::string e = errorOf(path);
  QVERIFY2(e.find(dir.path().toStdString() + "/bad.bag: offset ") == 0, e.c_str());
  QVERIFY2(e.find("(topic /sonar): Range.header.frame_id") != std::string::npos, e.c_str());
  // Lenient: that one reading is left out and counted.
  LogOptions o;
  o.lenient = true;
  LoadReport report;
  const Dataset d = readLog(path, o, &report);
  QCOMPARE(report.skippedLines, std::size_t{1});
  QCOMPARE(d.readingCount(), std::size_t{11888 - 1});
}

void TstBagLog::aCutBagIsAnErrorOrPartOfTheLog() {
  // room-bz2.bag cut in the middle: no index, and a chunk cut short.
  const QByteArray bytes = readAll(kBags + "room-bz2.bag");
  QTemporaryDir dir;
  const std::string path = dir.filePath("cut.bag").toStdString();
  {
    QFile f(QString::fromStdString(path));
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write(bytes.left(bytes.size() / 2));
  }
  const std::string e = errorOf(path);
  QVERIFY2(e.find(dir.path().toStdString() + "/cut.bag: offset ") == 0 &&
               e.find("cut short") != std::string::npos,
           e.c_str());
  LogOptions o;
  o.lenient = true;
  LoadReport report;
  const Dataset d = readLog(path, o, &report);
  QVERIFY(report.skippedLines >= 1);
  // Scans before the cut are kept, each whole and as in the .sglog.
  QVERIFY(d.scans.size() > 100 && d.scans.size() < 743);
  for (std::size_t k = 0; k + 1 < d.scans.size(); ++k) {
    QVERIFY(d.scans[k].odometry == sglog().scans[k].odometry);
  }
}

void TstBagLog::readingsOutsideTheOdometryAreLeftOutAndReported() {
  // tests/data/bags/ros1/small_none.bag (python3-rosbag; its script's docstring): /sonar Range
  // readings 1, 2, 3, 4 m at 0, 0.1, 0.2, 0.3 s; /odom at 0.05, 0.15, 0.25 s with x = 0, 0.5, 1.
  // The frame sonar0 has no transform: without a robot the load says so.
  const std::string small = SONARGRID_TEST_DATA "/bags/ros1/small_none.bag";
  const std::string e = errorOf(small);
  QVERIFY2(e.find("no transform from base_link to the sonar frame sonar0") != std::string::npos &&
               e.find("--robot") != std::string::npos,
           e.c_str());
  LogOptions o;
  o.ring = SonarRing::circular(1, 0.2);
  LoadReport report;
  const Dataset d = readLog(small, o, &report);
  // The readings at 0 s and 0.3 s lie outside the odometry's span: left out, not extrapolated.
  QCOMPARE(d.scans.size(), std::size_t{2});
  QVERIFY2(std::find(report.notes.begin(), report.notes.end(),
                     "2 readings outside the odometry's time span (0.050000 s to 0.250000 s) left "
                     "out: a pose there would be invented") != report.notes.end(),
           report.notes.back().c_str());
  // 0.1 s is halfway from 0.05 s (x = 0) to 0.15 s (x = 0.5): x = 0.25; 0.2 s gives 0.75.
  QCOMPARE(d.scans[0].time, 0.1);
  QCOMPARE(d.scans[0].odometry.x(), 0.25);
  QCOMPARE(d.scans[0].readings.at(0).range, 2.0);
  QCOMPARE(d.scans[1].time, 0.2);
  QCOMPARE(d.scans[1].odometry.x(), 0.75);
  QCOMPARE(d.scans[1].readings.at(0).range, 3.0);
}

void TstBagLog::floatFieldsWidenToTheirShortestDecimal() {
  // float32(2.873) is 2.87299990654...; its shortest decimal is "2.873".
  QCOMPARE(bag::widen(2.873f), 2.873);
  QCOMPARE(bag::widen(5.0f), 5.0);
  QCOMPARE(bag::widen(0.15f), 0.15);
  QVERIFY(static_cast<double>(2.873f) != 2.873);
  // 25 and 30 degrees in float32 read as whole degrees; 0.3 rad (17.19 degrees) as "0.3".
  QCOMPARE(bag::widenAngle(static_cast<float>(degToRad(25.0))), degToRad(25.0));
  QCOMPARE(bag::widenAngle(static_cast<float>(degToRad(30.0))), degToRad(30.0));
  QCOMPARE(bag::widenAngle(0.3f), 0.3);
  // The yaw of the quaternion (0, 0, sin(a/2), cos(a/2)) is a, to the last bit or two.
  QVERIFY(std::abs(bag::yawOf(0, 0, std::sin(0.25), std::cos(0.25)) - 0.5) < 1e-15);
  // A quarter turn about z: (0, 0, sqrt(1/2), sqrt(1/2)) has yaw pi/2.
  QVERIFY(std::abs(bag::yawOf(0, 0, std::sqrt(0.5), std::sqrt(0.5)) - std::numbers::pi / 2) <
          1e-15);
}

QTEST_APPLESS_MAIN(TstBagLog)
#include "tst_bag_log.moc"
