// SPDX-License-Identifier: BSD-3-Clause
// The native .sglog log: round trips, the exact error messages of docs/formats.md, the writer's
// atomic replacement and robustness against garbage input.

#include <QDir>
#include <QFile>
#include <QTemporaryDir>
#include <QtTest>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <sstream>
#include <string>

#include "sonargrid/base/log_error.h"
#include "sonargrid/data/dataset.h"
#include "sonargrid/io/sglog.h"

Q_DECLARE_METATYPE(sg::Dataset)

namespace {

constexpr double kInf = sg::Reading::kNoEcho;

sg::Dataset parseText(const QByteArray& text, const std::string& name = "t.sglog") {
  std::istringstream in(std::string(text.constData(), static_cast<std::size_t>(text.size())));
  return sg::parseSglog(in, name);
}

// what() of the LogError the text raises, or a description of what happened instead.
QByteArray errorOf(const QByteArray& text) {
  try {
    parseText(text);
  } catch (const sg::LogError& e) {
    return QByteArray(e.what());
  } catch (const std::exception& e) {
    return QByteArray("unexpected exception: ") + e.what();
  }
  return "no error";
}

std::string writeToString(const sg::Dataset& d) {
  std::ostringstream out;
  sg::writeSglog(d, out);
  return out.str();
}

QByteArray readAll(const QString& path) {
  QFile f(path);
  if (!f.open(QIODevice::ReadOnly)) return "cannot open";
  return f.readAll();
}

// Nine header lines, so a body record in the tests below is on line 10.
const QByteArray kHeader =
    "sglog 1\n"
    "name \"t\"\n"
    "robot custom\n"
    "aperture 0.5\n"
    "min_range 0.1\n"
    "max_range 4\n"
    "sonar 0 0.1 0 0\n"
    "sonar 1 0 0.1 1.5\n"
    "end_header\n";

sg::SonarRing smallRing() {
  sg::SonarRing ring;
  ring.robot = "custom";
  ring.apertureRad = 0.5;
  ring.minRange = 0.1;
  ring.maxRange = 4.0;
  ring.sonars = {sg::SonarMount{sg::Pose2D(0.1, 0, 0)}, sg::SonarMount{sg::Pose2D(0, 0.1, 1.5)}};
  return ring;
}

sg::Scan makeScan(double t, sg::Pose2D odo, std::optional<sg::Pose2D> truth,
                  std::vector<sg::Reading> readings) {
  sg::Scan s;
  s.time = t;
  s.odometry = odo;
  s.truth = truth;
  s.readings = std::move(readings);
  return s;
}

}  // namespace

class TstSglog : public QObject {
  Q_OBJECT

 private slots:
  void logErrorFormat();
  void roundTrip_data();
  void roundTrip();
  void writerOutput();
  void rangeAtMaxIsNoEcho();
  void parseAccepted();
  void malformed_data();
  void malformed();
  void endRecord_data();
  void endRecord();
  void everyCutIsDetected();
  void writerRejects_data();
  void writerRejects();
  void readFixture();
  void readErrorsNameThePath();
  void atomicWriteMissingDirectory();
  void atomicWriteKeepsOldFile();
  void atomicWriteReplaces();
  void atomicWriteOverDirectory();
  void garbageNeverCrashes();
  void mutatedLogsNeverCrash();
};

void TstSglog::logErrorFormat() {
  // The three shapes documented in log_error.h and docs/formats.md.
  QCOMPARE(QByteArray(sg::LogError("f.sglog", 0, "", "empty file").what()),
           QByteArray("f.sglog: empty file"));
  QCOMPARE(QByteArray(sg::LogError("f.sglog", 7, "", "bad line").what()),
           QByteArray("f.sglog:7: bad line"));
  const sg::LogError e("f.sglog", 14, "range", "expected x, found 'y'");
  QCOMPARE(QByteArray(e.what()), QByteArray("f.sglog:14: range: expected x, found 'y'"));
  QCOMPARE(e.file(), std::string("f.sglog"));
  QCOMPARE(e.line(), std::size_t{14});
  QCOMPARE(e.field(), std::string("range"));
  QCOMPARE(e.message(), std::string("expected x, found 'y'"));
}

void TstSglog::roundTrip_data() {
  QTest::addColumn<sg::Dataset>("dataset");

  {
    sg::Dataset d;
    d.name = "circle with truth";
    d.ring = sg::SonarRing::circular(6, 0.25);  // robot "custom"
    for (int i = 0; i < 5; ++i) {
      const double t = 0.1 * i;
      std::vector<sg::Reading> rs;
      for (std::uint16_t k = 0; k < 6; ++k)
        rs.push_back({k, 0.3 + 0.7 * k + 0.01 * i, t + 0.001 * k});
      d.scans.push_back(makeScan(t, sg::Pose2D(0.05 * i, -0.02 * i, 0.03 * i),
                                 sg::Pose2D(0.051 * i, -0.019 * i, 0.029 * i), rs));
    }
    QTest::addRow("truth, custom ring") << d;
  }
  {
    sg::Dataset d;
    d.name = "p3dx, odometry only";
    d.ring = sg::SonarRing::pioneer3dx();
    d.scans.push_back(
        makeScan(1.0, sg::Pose2D(1, 2, 3), std::nullopt, {{0, 1.0, 1.0}, {15, 2.5, 1.0}}));
    d.scans.push_back(makeScan(2.0, sg::Pose2D(1.5, 2, -3), std::nullopt, {{7, 0.2, 2.0}}));
    QTest::addRow("no truth, preset ring") << d;
  }
  {
    sg::Dataset d;
    d.name = "amigobot mixed";
    d.ring = sg::SonarRing::amigobot();
    d.scans.push_back(makeScan(0, sg::Pose2D(0, 0, 0), sg::Pose2D(0, 0, 0),
                               {{0, kInf, 0}, {1, 4.99, 0.01}, {2, kInf, 0.02}}));
    d.scans.push_back(makeScan(0.1, sg::Pose2D(0.1, 0, 0), std::nullopt, {{3, kInf, 0.1}}));
    d.scans.push_back(
        makeScan(0.2, sg::Pose2D(0.2, 0, 0), sg::Pose2D(0.21, 0, 0), {{7, 0.15, 0.2}}));
    QTest::addRow("no echo, mixed truth") << d;
  }
  {
    // Values whose shortest decimal form is long or unusual.
    sg::Dataset d;
    d.name = "awkward numbers";
    d.ring = smallRing();
    d.ring.minRange = 0.0;
    d.ring.maxRange = 1e300;
    d.ring.apertureRad = std::numbers::pi;  // the largest aperture allowed
    d.ring.sonars[0].pose = sg::Pose2D(1.0 / 3.0, -0.0, 5e-324);
    d.scans.push_back(makeScan(-1e-9, sg::Pose2D(0.1 + 0.2, 123456789.123456789, -std::numbers::pi),
                               sg::Pose2D(1e-300, -1e300, 2.0 / 3.0),
                               {{1, 5e-324, -7.25}, {0, 9.999999999999999e299, 1e15}}));
    QTest::addRow("awkward numbers") << d;
  }
  {
    sg::Dataset d;
    d.name =
        std::string("Salle \xC3\xA0 manger \xE2\x80\x93 \"2\" \\ #1\n\ttab\rcr \x01 \xFF end ") +
        std::string(1, '\0') + " ";
    d.ring = smallRing();
    QTest::addRow("odd name, no scans") << d;
  }
  {
    sg::Dataset d;
    d.name = "";
    d.ring = smallRing();
    d.ring.robot = "k2a-v2.1_test";
    d.scans.push_back(makeScan(3, sg::Pose2D(0, 0, 0), std::nullopt, {}));
    d.scans.push_back(makeScan(3, sg::Pose2D(0, 0, 0.5), sg::Pose2D(0, 0, 0.5), {}));
    d.scans.push_back(makeScan(3, sg::Pose2D(0, 0, 1), std::nullopt, {{1, 0, 3}}));
    QTest::addRow("empty name, empty scans, equal times") << d;
  }
  {
    sg::Dataset d;
    d.name = "big ring";
    d.ring = sg::SonarRing::circular(300, 1.0);
    d.scans.push_back(makeScan(0, sg::Pose2D(0, 0, 0), std::nullopt, {{299, 1, 0}, {256, 2, 0}}));
    QTest::addRow("300 sonars") << d;
  }
}

void TstSglog::roundTrip() {
  QFETCH(sg::Dataset, dataset);

  const std::string text = writeToString(dataset);
  std::istringstream in(text);
  const sg::Dataset back = sg::parseSglog(in, "memory");
  QVERIFY(back == dataset);
  QCOMPARE(back.name, dataset.name);  // says which part differs if the line above fails
  QVERIFY(back.ring == dataset.ring);
  QCOMPARE(back.scans.size(), dataset.scans.size());

  // Writing is deterministic, and the file path goes through the same code.
  QCOMPARE(writeToString(back), text);
  QTemporaryDir dir;
  QVERIFY(dir.isValid());
  const std::string path = dir.filePath("a.sglog").toStdString();
  sg::writeSglog(dataset, path);
  QVERIFY(sg::readSglog(path) == dataset);
  QCOMPARE(readAll(dir.filePath("a.sglog")).toStdString(), text);
}

void TstSglog::writerOutput() {
  sg::Dataset d;
  d.name = "a \"b\"\n";
  d.ring.robot = "custom";
  d.ring.apertureRad = 0.5;
  d.ring.minRange = 0.1;
  d.ring.maxRange = 4;
  d.ring.sonars = {sg::SonarMount{sg::Pose2D(0.1, 0, 0)}};
  d.scans.push_back(
      makeScan(0.25, sg::Pose2D(1, -2, 0.5), std::nullopt, {{0, 1.5, 0.25}, {0, kInf, 0.3}}));
  d.scans.push_back(makeScan(1, sg::Pose2D(0, 0, 0), sg::Pose2D(0.1, 0.2, -3), {}));

  // Written out by hand from docs/formats.md, "What the writer produces".
  const std::string expected =
      "sglog 1\n"
      "# SonarGrid log; units: metres, radians, seconds; see docs/formats.md\n"
      "name \"a \\\"b\\\"\\n\"\n"
      "robot custom\n"
      "aperture 0.5\n"
      "min_range 0.1\n"
      "max_range 4\n"
      "sonar 0 0.1 0 0\n"
      "end_header\n"
      "scan 0.25 1 -2 0.5 none\n"
      "r 0 1.5 0.25\n"
      "r 0 none 0.3\n"
      "scan 1 0 0 0 0.1 0.2 -3\n"
      "end\n";
  QCOMPARE(writeToString(d), expected);
}

void TstSglog::rangeAtMaxIsNoEcho() {
  // docs/formats.md, "No echo": finite ranges at or beyond max_range (4 here) read as kNoEcho.
  const sg::Dataset d =
      parseText(kHeader + "scan 0 0 0 0 none\nr 0 4 0\nr 1 1e6 0\nr 0 3.999 0\nend\n");
  QCOMPARE(d.scans.at(0).readings.size(), std::size_t{3});
  QVERIFY(!d.scans[0].readings[0].echo());
  QVERIFY(!d.scans[0].readings[1].echo());
  QCOMPARE(d.scans[0].readings[2].range, 3.999);

  // So a dataset holding such a finite range does not come back equal: it comes back as no echo.
  sg::Dataset mem;
  mem.ring = smallRing();
  mem.scans.push_back(makeScan(0, sg::Pose2D(), std::nullopt, {{0, 4.5, 0}}));
  const std::string text = writeToString(mem);
  QVERIFY(text.find("r 0 4.5 0\n") != std::string::npos);  // the file keeps the logged number
  std::istringstream in(text);
  QCOMPARE(sg::parseSglog(in, "m").scans[0].readings[0].range, kInf);
}

void TstSglog::parseAccepted() {
  // Everything docs/formats.md allows but the writer never produces: BOM, CRLF, comments and
  // blank lines everywhere (after 'end' too), tabs, header records out of order, number
  // spellings (printf's "+00.000", "-00.000" and "5.0E+00" among them), no final LF.
  const QByteArray text =
      "\xEF\xBB\xBFsglog 1   # first line\r\n"
      "# comment\n"
      "\n"
      "max_range\t4\n"
      "  sonar 0 0.1 0 0 # trailing comment\n"
      "robot p3dx\n"
      "sonar 1 -0 .1e0 1.5\n"
      "name  \"R\\x6Fom #1 \\t\\\\\"   # a comment after the name\n"
      "aperture 0.5\n"
      "min_range 1e-1\n"
      "   \t  \n"
      "end_header\n"
      "# body\n"
      "scan -2. 1 2 3 none\r\n"
      "r 1 none -2\n"
      "r 0 0.05 -1.5\n"
      "scan -2 +00.000 -00.000 +0.000e+00 +04.000 5.0E+00 +6\n"
      "r\t1\t2.5\t7\n"
      "\t end\t# closing record, indented\r\n"
      "\n"
      "# only comments and blank lines after it\n"
      "   # no final LF";
  sg::Dataset expected;
  expected.name = "Room #1 \t\\";  // \x6F is 'o'
  expected.ring = smallRing();
  expected.ring.robot = "p3dx";  // a label only: the sonars come from the file
  expected.scans.push_back(makeScan(-2, sg::Pose2D(1, 2, 3), std::nullopt,
                                    {{1, kInf, -2}, {0, 0.05, -1.5}}));  // below min_range: kept
  expected.scans.push_back(makeScan(-2, sg::Pose2D(0, 0, 0), sg::Pose2D(4, 5, 6), {{1, 2.5, 7}}));
  const sg::Dataset got = parseText(text);
  QCOMPARE(got.name, expected.name);
  QVERIFY(got.ring == expected.ring);
  QVERIFY(got == expected);
}

void TstSglog::malformed_data() {
  QTest::addColumn<QByteArray>("text");
  QTest::addColumn<QByteArray>("expected");

  // Expected strings are written by hand from docs/formats.md ("Errors"); line numbers are counted
  // in the input (kHeader has nine lines).
  auto header = [](const QByteArray& middle) {
    return "sglog 1\nname \"t\"\nrobot custom\n" + middle + "end_header\n";
  };
  const QByteArray ranges = "aperture 0.5\nmin_range 0.1\nmax_range 4\n";  // lines 4-6

  QTest::addRow("empty file") << QByteArray()
                              << QByteArray(
                                     "t.sglog: empty file (expected 'sglog 1' on the first line)");
  QTest::addRow("other format")
      << QByteArray("ODOM 0 0 0\n")
      << QByteArray("t.sglog:1: magic: expected 'sglog 1' as the first line, found 'ODOM 0 0 0'");
  QTest::addRow("comment before magic")
      << QByteArray("# hi\nsglog 1\n")
      << QByteArray("t.sglog:1: magic: expected 'sglog 1' as the first line, found '# hi'");
  QTest::addRow("blank first line")
      << QByteArray("\nsglog 1\n")
      << QByteArray("t.sglog:1: magic: expected 'sglog 1' as the first line, found an empty line");
  QTest::addRow("version 2") << QByteArray("sglog 2\n")
                             << QByteArray(
                                    "t.sglog:1: version: expected version 1 (the only version this "
                                    "reader supports), found '2'");
  QTest::addRow("no version")
      << QByteArray("sglog\n")
      << QByteArray("t.sglog:1: version: expected a version number after 'sglog', found nothing");
  QTest::addRow("version word")
      << QByteArray("sglog one\n")
      << QByteArray("t.sglog:1: version: expected a version number after 'sglog', found 'one'");
  QTest::addRow("extra on first line")
      << QByteArray("sglog 1 x\n")
      << QByteArray("t.sglog:1: sglog: expected 1 field after 'sglog' (version), found 2");
  QTest::addRow("truncated header")
      << QByteArray("sglog 1\nname \"t\"\nrobot custom\n")
      << QByteArray(
             "t.sglog: truncated: the file ends inside the header (expected an 'end_header' line)");
  QTest::addRow("missing aperture")
      << header("min_range 0.1\nmax_range 4\nsonar 0 0 0 0\n")
      << QByteArray(
             "t.sglog:7: aperture: expected one 'aperture' line before 'end_header', found none");
  QTest::addRow("no sonars") << header(ranges)
                             << QByteArray(
                                    "t.sglog:7: sonar: expected at least one 'sonar' line before "
                                    "'end_header', found none");
  QTest::addRow("duplicate sonar")
      << header(ranges + "sonar 0 0 0 0\nsonar 0 1 0 0\n")
      << QByteArray("t.sglog:8: index: expected sonar index 1, found '0', a duplicate of line 7");
  QTest::addRow("sonar gap") << header(ranges + "sonar 0 0 0 0\nsonar 2 1 0 0\n")
                             << QByteArray(
                                    "t.sglog:8: index: expected sonar index 1 (sonars are listed "
                                    "0, 1, 2, ... in order), found '2'");
  QTest::addRow("sonar from 1") << header(ranges + "sonar 1 0 0 0\n")
                                << QByteArray(
                                       "t.sglog:7: index: expected sonar index 0 (sonars are "
                                       "listed 0, 1, 2, ... in order), found '1'");
  QTest::addRow("sonar fields")
      << header(ranges + "sonar 0 0 0\n")
      << QByteArray(
             "t.sglog:7: sonar: expected 4 fields after 'sonar' (index x y heading), found 3");
  QTest::addRow("sonar heading inf")
      << header(ranges + "sonar 0 0 0 inf\n")
      << QByteArray(
             "t.sglog:7: heading: expected an angle in radians, found 'inf', which is not finite");
  QTest::addRow("aperture twice") << header("aperture 0.5\naperture 0.6\n")
                                  << QByteArray(
                                         "t.sglog:5: aperture: expected one 'aperture' line, found "
                                         "a second (the first is line 4)");
  QTest::addRow("unknown header record")
      << header("foo 1\n")
      << QByteArray(
             "t.sglog:4: expected a header record (name, robot, "
             "aperture, min_range, max_range, sonar, start_pose or "
             "end_header), found 'foo'");
  QTest::addRow("aperture nan") << header("aperture nan\n")
                                << QByteArray(
                                       "t.sglog:4: aperture: expected an angle in radians > 0 and "
                                       "<= pi, found 'nan', which is not finite");
  QTest::addRow("aperture too wide")
      << header("aperture 4\n")
      << QByteArray("t.sglog:4: aperture: expected an angle in radians > 0 and <= pi, found '4'");
  QTest::addRow("min_range negative")
      << header("min_range -0.1\n")
      << QByteArray("t.sglog:4: min_range: expected a number of metres >= 0, found '-0.1'");
  QTest::addRow("max_range not above min")
      << header("min_range 0.1\nmax_range 0.1\n")
      << QByteArray(
             "t.sglog:5: max_range: expected a number of metres > min_range 0.1, found '0.1'");
  QTest::addRow("min_range above max")
      << header("max_range 4\nmin_range 5\n")
      << QByteArray(
             "t.sglog:5: min_range: expected a number of metres >= 0 and < max_range 4, found '5'");
  QTest::addRow("robot bad character") << QByteArray("sglog 1\nrobot my/robot\n")
                                       << QByteArray(
                                              "t.sglog:2: robot: expected a preset name or "
                                              "'custom' (1 to 64 characters from A-Z a-z 0-9 _ "
                                              ". -), found 'my/robot'");
  QTest::addRow("robot two words") << QByteArray("sglog 1\nrobot my robot\n")
                                   << QByteArray(
                                          "t.sglog:2: robot: expected 1 field after 'robot' (a "
                                          "preset name or 'custom'), found 2");
  QTest::addRow("name unquoted")
      << QByteArray("sglog 1\nname Room 3\n")
      << QByteArray("t.sglog:2: name: expected a quoted string such as \"Room 3\", found 'Room 3'");
  QTest::addRow("name unterminated")
      << QByteArray("sglog 1\nname \"Room\n")
      << QByteArray("t.sglog:2: name: expected a closing '\"', found the end of the line");
  QTest::addRow("name bad escape")
      << QByteArray("sglog 1\nname \"a\\qb\"\n")
      << QByteArray(
             R"(t.sglog:2: name: expected an escape \\, \", \n, \r, \t or \xHH after '\', found 'q')");
  QTest::addRow("name bad hex")
      << QByteArray("sglog 1\nname \"\\xZ1\"\n")
      << QByteArray(R"(t.sglog:2: name: expected two hex digits after '\x', found 'Z1')");
  QTest::addRow("name trailing text")
      << QByteArray("sglog 1\nname \"a\" b\n")
      << QByteArray("t.sglog:2: name: expected nothing after the closing '\"', found 'b'");
  QTest::addRow("end_header with a field")
      << QByteArray(kHeader).replace("end_header", "end_header now")
      << QByteArray("t.sglog:9: end_header: expected 0 fields after 'end_header', found 1");

  QTest::addRow("reading before scan")
      << kHeader + "r 0 1 0\n"
      << QByteArray("t.sglog:10: expected a 'scan' line before the first reading, found 'r'");
  QTest::addRow("range word")
      << kHeader + "scan 0 0 0 0 none\nr 0 abc 0\n"
      << QByteArray("t.sglog:11: range: expected a number of metres >= 0 or 'none', found 'abc'");
  QTest::addRow("range negative")
      << kHeader + "scan 0 0 0 0 none\nr 0 -1 0\n"
      << QByteArray("t.sglog:11: range: expected a number of metres >= 0 or 'none', found '-1'");
  QTest::addRow("range nan") << kHeader + "scan 0 0 0 0 none\nr 0 nan 0\n"
                             << QByteArray(
                                    "t.sglog:11: range: expected a number of metres >= 0 or "
                                    "'none', found 'nan', which is not finite");
  QTest::addRow("range inf") << kHeader + "scan 0 0 0 0 none\nr 0 inf 0\n"
                             << QByteArray(
                                    "t.sglog:11: range: expected a number of metres >= 0 or "
                                    "'none', found 'inf', which is not finite");
  QTest::addRow("sonar not in ring")
      << kHeader + "scan 0 0 0 0 none\nr 2 1 0\n"
      << QByteArray("t.sglog:11: sonar: expected a sonar index 0..1, found '2'");
  QTest::addRow("sonar negative")
      << kHeader + "scan 0 0 0 0 none\nr -1 1 0\n"
      << QByteArray("t.sglog:11: sonar: expected a sonar index 0..1, found '-1'");
  QTest::addRow("reading extra field")
      << kHeader + "scan 0 0 0 0 none\nr 0 1 0 7\n"
      << QByteArray("t.sglog:11: r: expected 3 fields after 'r' (sonar range time), found 4");
  QTest::addRow("reading missing field")
      << kHeader + "scan 0 0 0 0 none\nr 0 1\n"
      << QByteArray("t.sglog:11: r: expected 3 fields after 'r' (sonar range time), found 2");
  QTest::addRow("reading time nan")
      << kHeader + "scan 0 0 0 0 none\nr 0 1 nan\n"
      << QByteArray(
             "t.sglog:11: time: expected a time in seconds, found 'nan', which is not finite");
  QTest::addRow("time backwards") << kHeader + "scan 2.5 0 0 0 none\nscan 2 0 0 0 none\n"
                                  << QByteArray(
                                         "t.sglog:11: time: expected a time >= 2.5 (the previous "
                                         "scan's; scans are in time order), "
                                         "found '2'");
  QTest::addRow("scan 6 fields") << kHeader + "scan 0 0 0 0 1 2\n"
                                 << QByteArray(
                                        "t.sglog:10: scan: expected 5 fields after 'scan' (time x "
                                        "y theta none) or 7 (time x y theta "
                                        "true_x true_y true_theta), found 6");
  QTest::addRow("scan truth half") << kHeader + "scan 0 0 0 0 1\n"
                                   << QByteArray(
                                          "t.sglog:10: scan: expected 'none' or a true pose "
                                          "(true_x true_y true_theta) after theta, "
                                          "found '1' alone");
  QTest::addRow("truth nan")
      << kHeader + "scan 0 0 0 0 1 nan 0\n"
      << QByteArray(
             "t.sglog:10: true_y: expected a number of metres, found 'nan', which is not finite");
  QTest::addRow("leftmost bad field")
      << kHeader + "scan 0 x y 0 none\n"
      << QByteArray("t.sglog:10: x: expected a number of metres, found 'x'");
  QTest::addRow("number with unit")
      << kHeader + "scan 0 1.5m 0 0 none\n"
      << QByteArray("t.sglog:10: x: expected a number of metres, found '1.5m'");
  // printf's '+' flag writes "+1.000"; a second sign is no number.
  QTest::addRow("two signs") << kHeader + "scan +-1 0 0 0 none\n"
                             << QByteArray(
                                    "t.sglog:10: time: expected a time in seconds, found '+-1'");
  QTest::addRow("lone plus") << kHeader + "scan 0 + 0 0 none\n"
                             << QByteArray("t.sglog:10: x: expected a number of metres, found '+'");
  QTest::addRow("signed inf") << kHeader + "scan 0 0 -INF 0 none\n"
                              << QByteArray(
                                     "t.sglog:10: y: expected a number of metres, found '-INF', "
                                     "which is not finite");
  QTest::addRow("number overflow")
      << kHeader + "scan 0 0 0 1e400 none\n"
      << QByteArray(
             "t.sglog:10: theta: expected an angle in radians, found '1e400', which is out of the "
             "range of a double");
  QTest::addRow("unknown body record")
      << kHeader + "odom 1 2 3\n"
      << QByteArray("t.sglog:10: expected a body record ('scan', 'r' or 'end'), found 'odom'");
  QTest::addRow("header record in body")
      << kHeader + "sonar 2 0 0 0\n"
      << QByteArray("t.sglog:10: expected a body record ('scan', 'r' or 'end'), found 'sonar'");
  QTest::addRow("long token shortened")
      << kHeader + QByteArray(50, 'k') + "\n"
      << QByteArray("t.sglog:10: expected a body record ('scan', 'r' or 'end'), found '" +
                    QByteArray(40, 'k') + "...'");
  // Columns count bytes from 1: "scan 0" is columns 1-6.
  QTest::addRow("NUL byte") << kHeader + QByteArray("scan 0\0 0 0 0 none\n", 19)
                            << QByteArray(
                                   "t.sglog:10: expected UTF-8 text, found byte 0x00 at column 7");
  QTest::addRow("invalid UTF-8")
      << kHeader + "# caf\xC3(\n"
      << QByteArray("t.sglog:10: expected UTF-8 text, found byte 0xc3 at column 6");
  QTest::addRow("lone CR") << kHeader + "r 0\r1 0\n"
                           << QByteArray(
                                  "t.sglog:10: expected UTF-8 text, found byte 0x0d at column 4");
  QTest::addRow("line too long")
      << kHeader + "# " + QByteArray(70000, 'x') + "\nscan 0 0 0 0 none\n"
      << QByteArray("t.sglog:10: expected a line of at most 65536 bytes, found a longer one");

  // Truncation (docs/formats.md, "Truncation"): a body cut at a line ending used to read as a
  // valid, shorter log; without its closing 'end' line it is now reported on the file as a whole.
  const QByteArray truncated(
      "t.sglog: truncated: the file ends inside the body (expected a closing 'end' line)");
  const QByteArray scan0 = "scan 0 0 0 0 none\n";  // line 10 after kHeader
  QTest::addRow("cut after end_header") << kHeader << truncated;
  QTest::addRow("cut after a scan line") << kHeader + scan0 << truncated;
  QTest::addRow("cut after a reading") << kHeader + scan0 + "r 0 1 0\n" << truncated;
  QTest::addRow("cut after the second scan's reading")
      << kHeader + scan0 + "r 0 1 0\nr 1 none 0\nscan 1 0 0 0 0 0 0\nr 0 2 1\n"
      << truncated;
  // A cut inside the last line that leaves it readable ("r 0 1.25 0.06" cut to "r 0 1.25 0.0").
  QTest::addRow("cut inside a number") << kHeader + scan0 + "r 0 1.25 0.0" << truncated;
  QTest::addRow("cut, CRLF") << kHeader + "scan 0 0 0 0 none\r\n" << truncated;
  QTest::addRow("cut, comments and blanks after") << kHeader + scan0 + "# more\n\n \t\n"
                                                  << truncated;
  QTest::addRow("end commented out") << kHeader + scan0 + "# end\n" << truncated;
  // A cut inside 'end' itself leaves a record that is not one.
  QTest::addRow("cut inside end")
      << kHeader + scan0 + "en"
      << QByteArray("t.sglog:11: expected a body record ('scan', 'r' or 'end'), found 'en'");
  QTest::addRow("END in capitals")
      << kHeader + "END\n"
      << QByteArray("t.sglog:10: expected a body record ('scan', 'r' or 'end'), found 'END'");
  QTest::addRow("end with a field")
      << kHeader + "end now\n"
      << QByteArray("t.sglog:10: end: expected 0 fields after 'end', found 1");
  // Lines 10 end, 11 blank, 12 comment, 13 scan.
  QTest::addRow("scan after end") << kHeader + "end\n\n# c\n" + scan0
                                  << QByteArray(
                                         "t.sglog:13: expected nothing but comments and blank "
                                         "lines after 'end' (line 10), found 'scan'");
  QTest::addRow("reading after end") << kHeader + scan0 + "end\nr 0 1 0\n"
                                     << QByteArray(
                                            "t.sglog:12: expected nothing but comments and blank "
                                            "lines after 'end' (line 11), found 'r'");
  QTest::addRow("second end") << kHeader + scan0 + "end\nend\n"
                              << QByteArray(
                                     "t.sglog:12: expected nothing but comments and blank lines "
                                     "after 'end' (line 11), found 'end'");
  QTest::addRow("bad byte after end")
      << kHeader + "end\n# \xFF\n"
      << QByteArray("t.sglog:11: expected UTF-8 text, found byte 0xff at column 3");
  QTest::addRow("end in the header") << QByteArray("sglog 1\nend\n")
                                     << QByteArray(
                                            "t.sglog:2: expected a header record (name, robot, "
                                            "aperture, min_range, max_range, sonar, start_pose or "
                                            "end_header), found 'end'");
}

void TstSglog::malformed() {
  QFETCH(QByteArray, text);
  QFETCH(QByteArray, expected);
  QCOMPARE(errorOf(text), expected);
}

void TstSglog::endRecord_data() {
  QTest::addColumn<QByteArray>("text");
  QTest::addColumn<int>("scans");
  QTest::addColumn<int>("readings");

  // Counts read off the text of each row.
  QTest::addRow("no scans") << kHeader + "end\n" << 0 << 0;
  QTest::addRow("no final LF") << kHeader + "scan 0 0 0 0 none\nr 0 1 0\nend" << 1 << 1;
  QTest::addRow("CRLF") << kHeader + "scan 0 0 0 0 none\r\nend\r\n" << 1 << 0;
  QTest::addRow("trailing comment") << kHeader + "scan 0 0 0 0 none\nend # done\n" << 1 << 0;
  QTest::addRow("blanks and comments after")
      << kHeader + "scan 0 0 0 0 none\nr 1 none 0\nr 0 2 0\nend\n\n\t\n# trailer\n  # x" << 1 << 2;
}

void TstSglog::endRecord() {
  QFETCH(QByteArray, text);
  QFETCH(int, scans);
  QFETCH(int, readings);
  const sg::Dataset d = parseText(text);
  QCOMPARE(d.scans.size(), static_cast<std::size_t>(scans));
  QCOMPARE(d.readingCount(), static_cast<std::size_t>(readings));
}

void TstSglog::everyCutIsDetected() {
  // Every proper prefix of a written log is refused, except the one that only drops the final LF
  // (the last line may lack its line ending); a prefix that ends at a line ending inside the body
  // is refused as truncated, on the file as a whole (line 0).
  sg::Dataset d;
  d.name = "cut";
  d.ring = smallRing();
  d.scans.push_back(makeScan(0, sg::Pose2D(0, 0, 0), std::nullopt, {{0, 1.5, 0}, {1, kInf, 0.01}}));
  d.scans.push_back(makeScan(0.1, sg::Pose2D(0.1, 0, 0), sg::Pose2D(0.1, 0.01, 0), {}));
  d.scans.push_back(makeScan(0.2, sg::Pose2D(0.2, 0, 0.1), std::nullopt, {{1, 2.25, 0.2}}));
  const QByteArray text = QByteArray::fromStdString(writeToString(d));
  QVERIFY(text.endsWith("\nr 1 2.25 0.2\nend\n"));
  const qsizetype bodyStart = text.indexOf("end_header\n") + 11;
  const qsizetype endStart = text.size() - 4;  // "end\n"

  QCOMPARE(parseText(text.left(text.size() - 1)), d);
  int atLineEnding = 0;
  for (qsizetype n = 0; n < text.size() - 1; ++n) {
    const QByteArray cut = text.left(n);
    try {
      parseText(cut);
      QFAIL(qPrintable(QString("a log cut after %1 bytes was accepted").arg(n)));
    } catch (const sg::LogError& e) {
      if (n >= bodyStart && n <= endStart && text[n - 1] == '\n') {
        ++atLineEnding;
        QCOMPARE(e.line(), std::size_t{0});
        QCOMPARE(QByteArray(e.what()),
                 QByteArray("t.sglog: truncated: the file ends inside the body (expected a "
                            "closing 'end' line)"));
      }
    }
  }
  QCOMPARE(atLineEnding, 7);  // after end_header, 3 scan lines and 3 reading lines
}

void TstSglog::writerRejects_data() {
  QTest::addColumn<sg::Dataset>("dataset");
  QTest::addColumn<QByteArray>("expected");

  sg::Dataset ok;
  ok.ring = smallRing();
  ok.scans.push_back(makeScan(1, sg::Pose2D(), std::nullopt, {{0, 1, 1}}));

  // Messages from checkWritable() in sglog.cpp, one per rule the reader enforces.
  sg::Dataset d = ok;
  d.ring.robot = "my robot";
  QTest::addRow("robot name") << d
                              << QByteArray(
                                     "cannot write the sglog: robot name 'my robot' is not 1 to 64 "
                                     "characters from A-Z a-z 0-9 _ . -");
  d = ok;
  d.ring.sonars.clear();
  QTest::addRow("empty ring") << d << QByteArray("cannot write the sglog: the ring has no sonars");
  d = ok;
  d.ring.apertureRad = 0;
  QTest::addRow("aperture")
      << d << QByteArray("cannot write the sglog: aperture is not an angle > 0 and <= pi");
  d = ok;
  d.scans.push_back(makeScan(0.5, sg::Pose2D(), std::nullopt, {}));
  QTest::addRow("time order")
      << d << QByteArray("cannot write the sglog: scan 1 is earlier than the scan before it");
  d = ok;
  d.scans[0].readings.push_back({2, 1, 1});
  QTest::addRow("sonar outside ring")
      << d << QByteArray("cannot write the sglog: scan 0 reading 1 names sonar 2, not in the ring");
  d = ok;
  d.scans[0].readings[0].range = std::nan("");
  QTest::addRow("nan range")
      << d << QByteArray("cannot write the sglog: scan 0 reading 0 has a range that is not >= 0");
  d = ok;
  d.scans[0].readings[0].range = -kInf;
  QTest::addRow("-inf range")
      << d << QByteArray("cannot write the sglog: scan 0 reading 0 has a range that is not >= 0");
  d = ok;
  d.scans[0].truth = sg::Pose2D(0, kInf, 0);
  QTest::addRow("infinite truth")
      << d << QByteArray("cannot write the sglog: scan 0 has a non-finite true pose");
}

void TstSglog::writerRejects() {
  QFETCH(sg::Dataset, dataset);
  QFETCH(QByteArray, expected);
  std::ostringstream out;
  QVERIFY_THROWS_EXCEPTION(std::runtime_error, sg::writeSglog(dataset, out));
  try {
    sg::writeSglog(dataset, out);
  } catch (const std::runtime_error& e) {
    QCOMPARE(QByteArray(e.what()), expected);
  }
  QVERIFY(out.str().empty());  // checked before a single byte goes out
}

void TstSglog::readFixture() {
  const std::string path = SONARGRID_TEST_DATA "/sglog/small.sglog";
  const sg::Dataset d = sg::readSglog(path);

  // The dataset described at the end of docs/formats.md, built from the fixture's numbers.
  sg::Dataset expected;
  expected.name = "Hallway \"B\", run 1";
  expected.ring.robot = "custom";
  expected.ring.apertureRad = 0.4363323129985824;
  expected.ring.minRange = 0.15;
  expected.ring.maxRange = 5;
  expected.ring.sonars = {sg::SonarMount{sg::Pose2D(0.2, 0, 0)},
                          sg::SonarMount{sg::Pose2D(0, 0.2, 1.5707963267948966)},
                          sg::SonarMount{sg::Pose2D(-0.2, 0, 3.141592653589793)},
                          sg::SonarMount{sg::Pose2D(0, -0.2, -1.5707963267948966)}};
  expected.scans.push_back(
      makeScan(0, sg::Pose2D(0, 0, 0), sg::Pose2D(0.01, -0.02, 0.005),
               {{0, 1.25, 0}, {1, kInf, 0.02}, {2, 0.5, 0.04}, {3, kInf, 0.06}}));
  expected.scans.push_back(makeScan(0.5, sg::Pose2D(0.25, 0, 0), std::nullopt, {{0, 1, 0.5}}));
  expected.scans.push_back(
      makeScan(0.5, sg::Pose2D(0.25, 0, 0.1), sg::Pose2D(0.26, 0.01, 0.1), {}));
  QVERIFY(d == expected);
  QCOMPARE(d.readingCount(), std::size_t{5});
  QVERIFY(!d.hasTruth());  // the second scan has none

  // The sample's aperture is 25 degrees and its headings are the usual multiples of pi/2.
  QCOMPARE(d.ring.apertureRad, sg::degToRad(25.0));
  QCOMPARE(d.ring.sonars[3].pose.heading, -std::numbers::pi / 2);
}

void TstSglog::readErrorsNameThePath() {
  // docs/formats.md: FILE is the path exactly as given.
  const std::string bad = SONARGRID_TEST_DATA "/sglog/bad_range.sglog";
  try {
    sg::readSglog(bad);
    QFAIL("bad_range.sglog was accepted");
  } catch (const sg::LogError& e) {
    QCOMPARE(
        QByteArray(e.what()),
        QByteArray(
            (bad + ":10: range: expected a number of metres >= 0 or 'none', found '-1'").c_str()));
    QCOMPARE(e.line(), std::size_t{10});
  }

  QTemporaryDir dir;
  QVERIFY(dir.isValid());
  const std::string missing = dir.filePath("missing.sglog").toStdString();
  try {
    sg::readSglog(missing);
    QFAIL("a missing file was read");
  } catch (const sg::LogError& e) {
    QCOMPARE(QByteArray(e.what()),
             QByteArray((missing + ": cannot open: No such file or directory").c_str()));
    QCOMPARE(e.line(), std::size_t{0});
  }

  const std::string directory = dir.path().toStdString();
  try {
    sg::readSglog(directory);
    QFAIL("a directory was read");
  } catch (const sg::LogError& e) {
    QCOMPARE(QByteArray(e.what()),
             QByteArray((directory + ": cannot read: Is a directory").c_str()));
  }
}

void TstSglog::atomicWriteMissingDirectory() {
  QTemporaryDir dir;
  QVERIFY(dir.isValid());
  const std::string path = dir.filePath("no/such/dir/out.sglog").toStdString();
  sg::Dataset d;
  d.ring = smallRing();
  try {
    sg::writeSglog(d, path);
    QFAIL("writing into a missing directory succeeded");
  } catch (const std::runtime_error& e) {
    // The folder is named: the system's "No such file or directory" would read as if the log
    // itself were meant.
    QCOMPARE(std::string(e.what()), "cannot write '" + path + "': directory '" +
                                        dir.filePath("no/such/dir").toStdString() +
                                        "' does not exist");
  }
  QVERIFY(QDir(dir.path()).isEmpty());
}

void TstSglog::atomicWriteKeepsOldFile() {
  QTemporaryDir dir;
  QVERIFY(dir.isValid());
  const QString qpath = dir.filePath("old.sglog");
  {
    QFile f(qpath);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write("old contents\n");
  }
  sg::Dataset d;
  d.ring = smallRing();
  d.scans.push_back(makeScan(0, sg::Pose2D(), std::nullopt, {{9, 1, 0}}));  // sonar 9: not in ring
  QVERIFY_THROWS_EXCEPTION(std::runtime_error, sg::writeSglog(d, qpath.toStdString()));
  QCOMPARE(readAll(qpath), QByteArray("old contents\n"));
  QCOMPARE(QDir(dir.path()).entryList(QDir::Files | QDir::Hidden), QStringList{"old.sglog"});
}

void TstSglog::atomicWriteReplaces() {
  QTemporaryDir dir;
  QVERIFY(dir.isValid());
  const QString qpath = dir.filePath("log.sglog");
  {
    QFile f(qpath);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write(QByteArray(100000, 'z'));  // longer than the new file: nothing of it may survive
  }
  sg::Dataset d;
  d.ring = smallRing();
  sg::writeSglog(d, qpath.toStdString());
  QCOMPARE(readAll(qpath).toStdString(), writeToString(d));
  QCOMPARE(QDir(dir.path()).entryList(QDir::Files | QDir::Hidden), QStringList{"log.sglog"});
}

void TstSglog::atomicWriteOverDirectory() {
  QTemporaryDir dir;
  QVERIFY(dir.isValid());
  QVERIFY(QDir(dir.path()).mkdir("taken.sglog"));
  const std::string path = dir.filePath("taken.sglog").toStdString();
  sg::Dataset d;
  d.ring = smallRing();
  try {
    sg::writeSglog(d, path);
    QFAIL("a directory was overwritten");
  } catch (const std::runtime_error& e) {
    QCOMPARE(std::string(e.what()), "cannot write '" + path + "': it is a directory");
  }
  // No temporary file is left.
  QCOMPARE(QDir(dir.path()).entryList(QDir::AllEntries | QDir::NoDotAndDotDot | QDir::Hidden),
           QStringList{"taken.sglog"});
}

void TstSglog::garbageNeverCrashes() {
  std::mt19937 random(20240601);  // fixed: a failure must be reproducible
  auto byte = [&random] { return static_cast<char>(random() & 0xFFU); };
  for (int round = 0; round < 500; ++round) {
    QByteArray junk(static_cast<qsizetype>(random() % 5000), '\0');
    for (char& c : junk) c = byte();
    // Pure noise cannot start with "sglog 1", so it must be refused, and only with a LogError.
    QVERIFY_THROWS_EXCEPTION(sg::LogError, parseText(junk));
  }
  // Noise after a valid header reaches the body parser; noise made of the format's own
  // characters gets further still. Either may happen to be valid; anything else is a LogError.
  const QByteArray alphabet = "r scan none 0123456789.-e# \n\t";
  for (int round = 0; round < 1000; ++round) {
    QByteArray body(static_cast<qsizetype>(random() % 2000), '\0');
    for (char& c : body)
      c = round % 2 == 0 ? byte() : alphabet[static_cast<qsizetype>(random() % alphabet.size())];
    try {
      parseText(kHeader + body);
    } catch (const sg::LogError&) {
    }
  }
}

void TstSglog::mutatedLogsNeverCrash() {
  // Start from a valid log and flip, delete, duplicate bytes or cut it short.
  sg::Dataset d;
  d.ring = smallRing();
  for (int i = 0; i < 20; ++i) {
    d.scans.push_back(
        makeScan(i, sg::Pose2D(i, 0, 0), i % 2 ? std::optional(sg::Pose2D(i, 1, 0)) : std::nullopt,
                 {{0, 1.0 + i, static_cast<double>(i)}, {1, kInf, static_cast<double>(i)}}));
  }
  const QByteArray valid = QByteArray::fromStdString(writeToString(d));
  std::mt19937 random(7);
  int accepted = 0;
  for (int round = 0; round < 3000; ++round) {
    QByteArray text = valid;
    const int edits = 1 + static_cast<int>(random() % 4);
    for (int e = 0; e < edits && !text.isEmpty(); ++e) {
      const auto at = static_cast<qsizetype>(random() % static_cast<std::uint32_t>(text.size()));
      switch (random() % 4) {
        case 0:
          text[at] = static_cast<char>(random() & 0xFFU);
          break;
        case 1:
          text.remove(at, 1 + static_cast<qsizetype>(random() % 8));
          break;
        case 2:
          text.insert(at, text.mid(at, 1 + static_cast<qsizetype>(random() % 30)));
          break;
        default:
          text.truncate(at);
      }
    }
    try {
      parseText(text);
      ++accepted;
    } catch (const sg::LogError&) {
    }
  }
  QVERIFY(accepted < 3000);  // the mutations did reach the error paths
}

QTEST_GUILESS_MAIN(TstSglog)
#include "tst_sglog.moc"
