// SPDX-License-Identifier: BSD-3-Clause
// Generic CSV / text logs: the column spec, the mm + tenths-of-a-degree fixture with the no-echo
// value 5110, the poses file joined on time, and sonar geometry files.

#include <QtTest>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "log_fixtures.h"
#include "sonargrid/io/csv_layout.h"
#include "sonargrid/io/csv_log.h"
#include "sonargrid/io/log_reader.h"

namespace {

constexpr double kInf = sg::Reading::kNoEcho;
constexpr double kPi = std::numbers::pi;

sg::LogOptions csvOptions(const std::string& spec) {
  sg::LogOptions o;
  o.csv = sg::parseCsvLayout(spec);
  o.ring = sg::readSonarGeometry(logtest::fixture("ring4_mm.geom"));
  return o;
}

std::string layoutError(const std::string& spec) {
  try {
    sg::parseCsvLayout(spec);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

class TstCsvLog : public QObject {
  Q_OBJECT
 private slots:
  void geometryFile();
  void layoutSpec();
  void layoutSpecRoundTrips();
  void layoutErrors_data();
  void layoutErrors();
  void millimetresTenthsOfDegreeAndNoEcho();
  void withoutNoEchoValue5110IsAnEcho();
  void posesJoinedOnTime();
  void whitespaceAndSemicolons();
};

void TstCsvLog::geometryFile() {
  const sg::SonarRing ring = sg::readSonarGeometry(logtest::fixture("ring4_mm.geom"));
  QCOMPARE(ring.size(), std::size_t{4});
  // "units mm deg": 100 mm = 0.1 m, 90 degrees = pi/2, aperture 25 degrees.
  QVERIFY(logtest::near(ring.sonars[0].pose, sg::Pose2D(0.1, 0.0, 0.0)));
  QVERIFY(logtest::near(ring.sonars[1].pose, sg::Pose2D(0.0, 0.1, kPi / 2)));
  QVERIFY(logtest::near(ring.sonars[3].pose, sg::Pose2D(0.0, -0.1, -kPi / 2)));
  QCOMPARE(ring.apertureRad, 25.0 * kPi / 180.0);
  QCOMPARE(ring.minRange, 0.1);
  QCOMPARE(ring.maxRange, 6.0);
}

void TstCsvLog::layoutSpec() {
  const sg::CsvLayout l = sg::parseCsvLayout(
      "time=1,x=2,y=3,theta=4,sonars=5-7,sonars=9,length=mm,angle=ddeg,noecho=5110,noecho=0,"
      "header=1,time_unit=ms");
  QCOMPARE(l.time, std::size_t{1});
  QCOMPARE(l.sonars, (std::vector<std::size_t>{5, 6, 7, 9}));
  QCOMPARE(l.length, sg::LengthUnit::Millimetre);
  QCOMPARE(l.range, sg::LengthUnit::Millimetre);  // follows length unless range= is given
  QCOMPARE(l.angle, sg::AngleUnit::TenthDegree);
  QCOMPARE(l.noEcho, (std::vector<double>{5110.0, 0.0}));
  QCOMPARE(l.headerLines, std::size_t{1});
  QCOMPARE(l.secondsPerTimeUnit, 1e-3);
  // 900 tenths of a degree = 90 degrees.
  QCOMPARE(sg::radians(900.0, sg::AngleUnit::TenthDegree), kPi / 2);
}

// formatCsvLayout writes every key, so that a project file holds the whole layout; parsing its
// text gives back the same layout, field for field.
void TstCsvLog::layoutSpecRoundTrips() {
  const sg::CsvLayout l = sg::parseCsvLayout(
      "time=1,x=2,y=3,theta=4,sonars=5-7,sonars=9,length=mm,angle=ddeg,noecho=5110,noecho=0,"
      "header=1,time_unit=ms");
  const std::string spec = sg::formatCsvLayout(l);
  QCOMPARE(QString::fromStdString(spec),
           QStringLiteral("time=1,x=2,y=3,theta=4,sonars=5-7,sonars=9,length=mm,range=mm,"
                          "angle=ddeg,time_unit=ms,noecho=5110,noecho=0,header=1,pose_time=1,"
                          "pose_x=2,pose_y=3,pose_theta=4"));
  QVERIFY(sg::parseCsvLayout(spec) == l);

  // Columns out of order, a range unit of its own, a decimal no-echo value, a delimiter, no pose
  // columns, the pose file's columns moved, microseconds.
  sg::CsvLayout m;
  m.time = 2;
  m.sonars = {3, 5, 4};
  m.length = sg::LengthUnit::Millimetre;
  m.range = sg::LengthUnit::Centimetre;
  m.angle = sg::AngleUnit::Degree;
  m.secondsPerTimeUnit = 1e-6;
  m.noEcho = {0.1, 655.35};
  m.delimiter = ';';
  m.poseTime = 4;
  m.poseX = 3;
  m.poseY = 2;
  m.poseTheta = 1;
  const std::string mspec = sg::formatCsvLayout(m);
  QCOMPARE(QString::fromStdString(mspec),
           QStringLiteral("time=2,sonars=3,sonars=5,sonars=4,length=mm,range=cm,angle=deg,"
                          "time_unit=us,noecho=0.1,noecho=655.35,header=0,delimiter=semicolon,"
                          "pose_time=4,pose_x=3,pose_y=2,pose_theta=1"));
  QVERIFY(sg::parseCsvLayout(mspec) == m);
}

void TstCsvLog::layoutErrors_data() {
  QTest::addColumn<QString>("spec");
  QTest::addColumn<QString>("message");
  QTest::newRow("no time") << "sonars=2-5"
                           << "--columns item 'sonars=2-5': expected a time column (time=N)";
  QTest::newRow("no sonars") << "time=1"
                             << "--columns item 'time=1': expected sonar columns "
                                "(sonars=FIRST-LAST)";
  QTest::newRow("column 0") << "time=0,sonars=2"
                            << "--columns item 'time=0': expected a column number 1..65536";
  QTest::newRow("reversed range") << "time=1,sonars=5-2"
                                  << "--columns item 'sonars=5-2': expected a column range "
                                     "FIRST-LAST with FIRST <= LAST";
  QTest::newRow("unit") << "time=1,sonars=2,length=km"
                        << "--columns item 'length=km': expected m, cm or mm";
  QTest::newRow("angle") << "time=1,sonars=2,angle=grad"
                         << "--columns item 'angle=grad': expected rad, deg or ddeg (tenths of "
                            "a degree)";
  QTest::newRow("no value") << "time=1,sonars"
                            << "--columns item 'sonars': expected KEY=VALUE";
  QTest::newRow("unknown key")
      << "time=1,sonars=2,speed=3"
      << "--columns item 'speed=3': expected a key time, x, y, theta, sonars, length, range, "
         "angle, time_unit, noecho, header, delimiter, pose_time, pose_x, pose_y or pose_theta";
}

void TstCsvLog::layoutErrors() {
  QFETCH(QString, spec);
  QFETCH(QString, message);
  QCOMPARE(QString::fromStdString(layoutError(spec.toStdString())), message);
}

void TstCsvLog::millimetresTenthsOfDegreeAndNoEcho() {
  sg::LoadReport report;
  const sg::Dataset d = sg::readLog(
      logtest::fixture("mm_ddeg.csv"),
      csvOptions("header=1,time=1,x=2,y=3,theta=4,sonars=5-8,length=mm,angle=ddeg,noecho=5110"),
      &report);
  QCOMPARE(report.format, sg::LogFormat::Csv);  // rows of numbers after the header line
  QCOMPARE(d.scans.size(), std::size_t{3});
  // Row 1: 1000 mm, 2000 mm, 0 tenths; 5110 is the no-echo value.
  QVERIFY(logtest::near(d.scans[0].odometry, sg::Pose2D(1.0, 2.0, 0.0)));
  const double r0[] = {1.5, kInf, 0.8, kInf};
  for (std::size_t i = 0; i < 4; ++i) QCOMPARE(d.scans[0].readings[i].range, r0[i]);
  // Row 2: 450 tenths of a degree = pi/4; 6000 mm is the ring's max_range: no echo.
  QCOMPARE(d.scans[1].time, 0.5);
  QVERIFY(logtest::near(d.scans[1].odometry, sg::Pose2D(1.1, 2.0, kPi / 4)));
  const double r1[] = {1.4, 2.5, kInf, kInf};
  for (std::size_t i = 0; i < 4; ++i) QCOMPARE(d.scans[1].readings[i].range, r1[i]);
  // Row 3: 900 tenths = pi/2, 2050 mm = 2.05 m.
  QVERIFY(logtest::near(d.scans[2].odometry, sg::Pose2D(1.2, 2.05, kPi / 2)));
  QCOMPARE(d.scans[2].readings[2].range, 0.7);
  QCOMPARE(d.scans[2].readings[3].time, 1.0);
}

void TstCsvLog::withoutNoEchoValue5110IsAnEcho() {
  const sg::Dataset d =
      sg::readLog(logtest::fixture("mm_ddeg.csv"),
                  csvOptions("header=1,time=1,x=2,y=3,theta=4,sonars=5-8,length=mm,angle=ddeg"));
  // The ring hears up to 6 m, so 5110 mm is an echo at 5.11 m unless declared "no echo".
  QCOMPARE(d.scans[0].readings[1].range, 5.11);
}

void TstCsvLog::posesJoinedOnTime() {
  sg::LogOptions o = csvOptions("time=1,sonars=2-5");
  o.posesPath = logtest::fixture("poses.txt");
  const sg::Dataset d = sg::readLog(logtest::fixture("ranges_only.txt"), o);
  QCOMPARE(d.scans.size(), std::size_t{3});
  // t = 0.25, halfway between (0, 0, 0) at 0 and (1, 0, 0.5) at 0.5.
  QVERIFY(logtest::near(d.scans[0].odometry, sg::Pose2D(0.5, 0.0, 0.25)));
  // t = 0.75, halfway between (1, 0, 0.5) and (2, 1, 3.0).
  QVERIFY(logtest::near(d.scans[1].odometry, sg::Pose2D(1.5, 0.5, 1.75)));
  // t = 1.25, halfway between headings 3.0 and -2.9 along the shorter arc through pi:
  // 3.0 + 0.5 (2 pi - 5.9) = 3.19159..., wrapped to 3.19159... - 2 pi.
  const sg::Pose2D p = d.scans[2].odometry;
  QCOMPARE(p.position, sg::Position(2.0, 1.0));
  QVERIFY(std::abs(p.heading - (3.0 + 0.5 * (2 * kPi - 5.9) - 2 * kPi)) < 1e-12);
  QCOMPARE(d.scans[2].readings[3].range, 3.3);
}

void TstCsvLog::whitespaceAndSemicolons() {
  sg::LogOptions o;
  o.format = sg::LogFormat::Csv;
  o.csv = sg::parseCsvLayout("time=1,x=2,y=3,theta=4,sonars=5-6,angle=deg");
  o.ring = sg::SonarRing::circular(2, 0.2);
  const sg::Dataset a = sg::parseLog("0.5 1 2 90 1.5 2.5\n", "t.txt", o);
  const sg::Dataset b = sg::parseLog("0.5; 1; 2; 90; 1.5; 2.5\n", "t.csv", o);
  QCOMPARE(a, b);
  QVERIFY(logtest::near(a.scans[0].odometry, sg::Pose2D(1.0, 2.0, kPi / 2)));
  QCOMPARE(a.scans[0].readings[1].range, 2.5);
}

QTEST_GUILESS_MAIN(TstCsvLog)
#include "tst_csv_log.moc"
