// SPDX-License-Identifier: BSD-3-Clause
// Choosing a reader (auto-detection), the exact error of every malformed fixture, lenient loading,
// progress and cancel, and robustness of every reader against garbage.

#include <QtTest>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "log_fixtures.h"
#include "sonargrid/engine/mapper.h"
#include "sonargrid/io/csv_layout.h"
#include "sonargrid/io/csv_log.h"
#include "sonargrid/io/log_reader.h"
#include "sonargrid/io/text_lines.h"
#include "writer_fixtures.h"

Q_DECLARE_METATYPE(sg::LogFormat)

namespace {

const char* kCsvSpec =
    "header=1,time=1,x=2,y=3,theta=4,sonars=5-8,length=mm,angle=ddeg,noecho=5110";

std::string readFile(const std::string& path) {
  QFile f(QString::fromStdString(path));
  if (!f.open(QIODevice::ReadOnly)) return {};
  const QByteArray b = f.readAll();
  return std::string(b.constData(), static_cast<std::size_t>(b.size()));
}

template <class T>
QByteArray bytesOf(const std::vector<T>& v) {
  return QByteArray(reinterpret_cast<const char*>(v.data()), qsizetype(v.size() * sizeof(T)));
}

// A CARMEN log of `scans` SONAR lines of 16 sonars.
std::string bigCarmen(int scans) {
  std::string out;
  for (int k = 0; k < scans; ++k) {
    const std::string t = std::to_string(k) + ".5";
    out += "ODOM " + std::to_string(k) + " 0 0 0 0 0 " + t + " h " + t + "\n";
    out += "SONAR 0.4 16";
    for (int i = 0; i < 16; ++i) out += " 1.25";
    for (int i = 0; i < 16; ++i) out += " 0.1 0.2 0.3";
    out += " " + t + " h " + t + "\n";
  }
  return out;
}

}  // namespace

class TstLogFormat : public QObject {
  Q_OBJECT
 private slots:
  void detect_data();
  void detect();
  void formatNames();
  void undetectable();
  void malformedFixtures_data();
  void malformedFixtures();
  void lenientSkipsAndCounts();
  void lenientSglogSkipsTheReadingsOfABadScan();
  void lenientAcceptsAMissingEnd();
  void lenientStillStopsOnWholeFileErrors();
  void progressReachesTheTotal();
  void cancelStopsTheLoad();
  void lineReaderGrowsPastASizeHint();
  void garbageNeverCrashes_data();
  void garbageNeverCrashes();
  void printfNumbers_data();
  void printfNumbers();
  void refusedNumbers_data();
  void refusedNumbers();
  void writerFixturesAreCommitted_data();
  void writerFixturesAreCommitted();
  void everyLoggerGivesTheSameReadings();
};

void TstLogFormat::detect_data() {
  QTest::addColumn<QByteArray>("head");
  QTest::addColumn<sg::LogFormat>("format");
  QTest::newRow("sglog") << QByteArray("sglog 1\nname \"x\"\n") << sg::LogFormat::Sglog;
  QTest::newRow("sglog with BOM") << QByteArray("\xEF\xBB\xBFsglog 1\n") << sg::LogFormat::Sglog;
  QTest::newRow("carmen comment") << QByteArray("# CARMEN Logfile\n") << sg::LogFormat::Carmen;
  QTest::newRow("carmen message") << QByteArray("# x\n\nPARAM a b 0 h 0\n")
                                  << sg::LogFormat::Carmen;
  QTest::newRow("player header") << QByteArray("## Player version 3.0.2\n")
                                 << sg::LogFormat::Player;
  QTest::newRow("player line") << QByteArray("1.0 16777343 6665 sonar 00 001 001 1 2.0\n")
                               << sg::LogFormat::Player;
  QTest::newRow("csv") << QByteArray("t,x,y\n1,2,3\n") << sg::LogFormat::Csv;
  QTest::newRow("blank columns") << QByteArray("1 2 3 4\n") << sg::LogFormat::Csv;
  QTest::newRow("prose") << QByteArray("hello world\n") << sg::LogFormat::Auto;
  QTest::newRow("empty") << QByteArray("") << sg::LogFormat::Auto;
}

void TstLogFormat::detect() {
  QFETCH(QByteArray, head);
  QFETCH(sg::LogFormat, format);
  QCOMPARE(sg::detectLogFormat(std::string_view(head.constData(), head.size())), format);
}

void TstLogFormat::formatNames() {
  for (const char* name : {"auto", "sglog", "carmen", "player", "csv"}) {
    sg::LogFormat f{};
    QVERIFY(sg::parseLogFormat(name, f));
    QCOMPARE(sg::logFormatName(f), std::string_view(name));
  }
  sg::LogFormat f{};
  QVERIFY(!sg::parseLogFormat("clf", f));
}

void TstLogFormat::undetectable() {
  QCOMPARE(QByteArray(logtest::errorOf(logtest::fixture("ring4_mm.geom"), {}).c_str()),
           QByteArray((logtest::fixture("ring4_mm.geom") +
                       ": format: expected an sglog header, CARMEN messages, Player writelog "
                       "lines or CSV rows; cannot tell the format from the content (give "
                       "--format)")
                          .c_str()));
}

void TstLogFormat::malformedFixtures_data() {
  QTest::addColumn<QString>("file");
  QTest::addColumn<QString>("robot");    // "", a preset name, or "geom" for ring4_mm.geom
  QTest::addColumn<bool>("csv");         // use kCsvSpec
  QTest::addColumn<QString>("message");  // what() after "<path>"
  QTest::newRow("carmen range") << "range.clf"
                                << "" << false
                                << ":3: SONAR r[1]: expected a range in metres >= 0, found 'x'";
  QTest::newRow("carmen short line")
      << "short_odom.clf"
      << "" << false
      << ":2: ODOM: expected 9 fields after 'ODOM' (x y theta tv rv accel ipc_timestamp "
         "ipc_hostname logger_timestamp), found 2";
  QTest::newRow("carmen ring change") << "ring_change.clf"
                                      << "" << false
                                      << ":3: SONAR num: expected 2 sonars (as on line 2), "
                                         "found '3'";
  QTest::newRow("carmen time order")
      << "time_order.clf"
      << "" << false
      << ":3: SONAR ipc_timestamp: expected a time >= 2 (the previous SONAR's; scans are in "
         "time order), found '1.5'";
  QTest::newRow("carmen sonar first")
      << "sonar_first.clf"
      << "" << false
      << ":1: SONAR: expected an ODOM or TRUEPOS message before the first SONAR, found none";
  QTest::newRow("carmen no sonar") << "no_sonar.clf"
                                   << "" << false
                                   << ": SONAR: expected at least one valid SONAR message, "
                                      "found none";
  QTest::newRow("player count") << "count.playerlog"
                                << "" << false
                                << ":3: sonar count: expected a count 0..65536, found 'four'";
  QTest::newRow("player too many ranges")
      << "too_many_ranges.playerlog"
      << "" << false
      << ":4: sonar count: expected at most 2 ranges (the sonars of the geometry of line 2), "
         "found 3";
  QTest::newRow("player no geometry")
      << "no_geometry.playerlog"
      << "" << false
      << ": geometry: expected sonar geometry messages or a robot preset (--robot), found "
         "neither";
  QTest::newRow("player pose") << "pose.playerlog"
                               << "" << false
                               << ":2: position2d pa: expected an angle in radians, found 'zero'";
  QTest::newRow("player 1.x with type fields")
      << "v1_with_type.playerlog"
      << "amigobot" << false
      << ":3: sonar: expected 2 payload fields (count, the ranges), found 10";
  QTest::newRow("csv cell") << "cell.csv"
                            << "geom" << true
                            << ":3: sonar 1 (column 6): expected a range >= 0 or a no-echo "
                               "value, found 'n/a'";
  QTest::newRow("csv negative") << "negative.csv"
                                << "geom" << true
                                << ":2: sonar 1 (column 6): expected a range >= 0 or a no-echo "
                                   "value, found '-20'";
  QTest::newRow("csv columns") << "columns.csv"
                               << "geom" << true
                               << ":3: columns: expected at least 8 columns, found 6";
  QTest::newRow("csv time order")
      << "time_order.csv"
      << "geom" << true
      << ":3: time (column 1): expected a time >= 1 (rows are in time order), found '0.5'";
  QTest::newRow("csv no ring") << "cell.csv"
                               << "" << true
                               << ": geometry: expected a robot preset or a geometry file "
                                  "(--robot), found neither";
}

void TstLogFormat::malformedFixtures() {
  QFETCH(QString, file);
  QFETCH(QString, robot);
  QFETCH(bool, csv);
  QFETCH(QString, message);
  sg::LogOptions o;
  if (robot == "geom") {
    o.ring = sg::readSonarGeometry(logtest::fixture("ring4_mm.geom"));
  } else if (!robot.isEmpty()) {
    sg::SonarRing ring;
    QVERIFY(sg::SonarRing::preset(robot.toStdString(), ring));
    o.ring = ring;
  }
  if (csv) o.csv = sg::parseCsvLayout(kCsvSpec);
  const std::string path = logtest::fixture("bad/" + file.toStdString());
  QCOMPARE(QString::fromStdString(logtest::errorOf(path, o)),
           QString::fromStdString(path) + message);
}

void TstLogFormat::lenientSkipsAndCounts() {
  sg::LogOptions o;
  o.lenient = true;
  sg::LoadReport report;
  const std::string path = logtest::fixture("bad/range.clf");
  const sg::Dataset d = sg::readLog(path, o, &report);
  // Line 2 is a good SONAR, line 3 the bad one.
  QCOMPARE(d.scans.size(), std::size_t{1});
  QCOMPARE(report.skippedLines, std::size_t{1});
  QCOMPARE(report.skipped.size(), std::size_t{1});
  QCOMPARE(report.skipped[0].field, std::string("SONAR r[1]"));
  QCOMPARE(report.skipped[0].count, std::size_t{1});
  QCOMPARE(report.summary(),
           "1 line: " + path + ":3: SONAR r[1]: expected a range in metres >= 0, found 'x'\n");
}

void TstLogFormat::lenientSglogSkipsTheReadingsOfABadScan() {
  const std::string text =
      "sglog 1\nname \"t\"\nrobot custom\naperture 0.5\nmin_range 0.1\nmax_range 4\n"
      "sonar 0 0.1 0 0\nsonar 1 0 0.1 1.5\nend_header\n"
      "scan 0 0 0 0 none\nr 0 1 0\n"           // lines 10-11
      "scan x 0 0 0 none\nr 0 1 1\nr 1 2 1\n"  // lines 12-14: a bad scan and its readings
      "scan 2 0 0 0 none\nr 1 1.5 2\nend\n";
  sg::LogOptions o;
  o.lenient = true;
  sg::LoadReport report;
  const sg::Dataset d = sg::parseLog(text, "t.sglog", o, &report);
  QCOMPARE(d.scans.size(), std::size_t{2});
  QCOMPARE(d.scans[0].readings.size(), std::size_t{1});  // nothing of lines 13-14 landed here
  QCOMPARE(d.scans[1].readings[0].range, 1.5);
  QCOMPARE(report.skippedLines, std::size_t{3});
  QCOMPARE(report.summary(),
           std::string("1 line: t.sglog:12: time: expected a time in seconds, found 'x'\n"
                       "2 lines: t.sglog:13: expected a reading of a valid scan, found one of "
                       "the scan skipped on line 12 (the first of them)\n"));
  o.lenient = false;
  QVERIFY_THROWS_EXCEPTION(sg::LogError, sg::parseLog(text, "t.sglog", o));
}

void TstLogFormat::lenientAcceptsAMissingEnd() {
  const std::string text =
      "sglog 1\nname \"t\"\nrobot custom\naperture 0.5\nmin_range 0.1\nmax_range 4\n"
      "sonar 0 0.1 0 0\nend_header\nscan 0 0 0 0 none\nr 0 1 0\n";
  sg::LogOptions o;
  o.lenient = true;
  sg::LoadReport report;
  const sg::Dataset d = sg::parseLog(text, "t.sglog", o, &report);
  QCOMPARE(d.scans.size(), std::size_t{1});
  QCOMPARE(report.skipped.size(), std::size_t{1});
  QCOMPARE(report.skipped[0].firstError,
           std::string("t.sglog: truncated: the file ends inside the body (expected a closing "
                       "'end' line)"));
}

void TstLogFormat::lenientStillStopsOnWholeFileErrors() {
  sg::LogOptions o;
  o.lenient = true;
  const std::string path = logtest::fixture("bad/no_sonar.clf");
  QCOMPARE(logtest::errorOf(path, o),
           path + ": SONAR: expected at least one valid SONAR message, found none");
}

void TstLogFormat::progressReachesTheTotal() {
  const std::string text = bigCarmen(4000);  // about 1.6 MB: several 256 KiB blocks
  std::vector<std::pair<std::uint64_t, std::uint64_t>> calls;
  sg::LogOptions o;
  o.progress = [&calls](std::uint64_t done, std::uint64_t total) {
    calls.emplace_back(done, total);
  };
  const sg::Dataset d = sg::parseLog(text, "big.clf", o);
  QCOMPARE(d.scans.size(), std::size_t{4000});
  QVERIFY(calls.size() >= 6);
  for (std::size_t i = 0; i < calls.size(); ++i) {
    QCOMPARE(calls[i].second, std::uint64_t{text.size()});
    if (i > 0) QVERIFY(calls[i].first >= calls[i - 1].first);
  }
  QCOMPARE(calls.back().first, std::uint64_t{text.size()});
}

void TstLogFormat::cancelStopsTheLoad() {
  const std::string text = bigCarmen(4000);
  std::atomic<bool> cancel{false};
  int calls = 0;
  sg::LogOptions o;
  o.cancel = &cancel;
  o.progress = [&](std::uint64_t, std::uint64_t) {
    if (++calls == 2) cancel = true;  // as a GUI's Cancel button would, mid-load
  };
  QVERIFY_THROWS_EXCEPTION(sg::LoadCancelled, sg::parseLog(text, "big.clf", o));
  QCOMPARE(calls, 2);  // the block read after the flag turned true is the last
}

// A file may grow between the size check and the read: the small buffer sized from the hint grows.
void TstLogFormat::lineReaderGrowsPastASizeHint() {
  class ShortHint : public sg::text::MemorySource {
   public:
    using MemorySource::MemorySource;
    std::uint64_t size() const override { return 4; }
  };
  const std::string text = "first line\n" + std::string(100000, 'x') + "\nlast";
  ShortHint source(text);
  const std::string name = "grow";
  sg::text::LineReader lines(source, name);
  std::string_view line;
  QVERIFY(lines.next(line));
  QCOMPARE(line, std::string_view("first line"));
  // 100000 bytes > the 65536-byte line limit: the limit, not the buffer, stops it.
  QVERIFY_THROWS_EXCEPTION(sg::LogError, lines.next(line));
  ShortHint shorter(std::string_view(text).substr(0, 60000));
  sg::text::LineReader again(shorter, name);
  QVERIFY(again.next(line));
  QVERIFY(again.next(line));
  QCOMPARE(line.size(), std::size_t{60000 - 11});
  QVERIFY(!again.next(line));
}

void TstLogFormat::garbageNeverCrashes_data() {
  QTest::addColumn<QString>("fixture");
  QTest::addColumn<sg::LogFormat>("format");
  QTest::newRow("sglog") << "../sglog/small.sglog" << sg::LogFormat::Sglog;
  QTest::newRow("carmen") << "small.clf" << sg::LogFormat::Carmen;
  QTest::newRow("player 2") << "small_p2.playerlog" << sg::LogFormat::Player;
  QTest::newRow("player 1") << "small_p1.playerlog" << sg::LogFormat::Player;
  QTest::newRow("csv") << "mm_ddeg.csv" << sg::LogFormat::Csv;
  QTest::newRow("player 3 writelog") << "writelog_p3_sonar.playerlog" << sg::LogFormat::Player;
  QTest::newRow("player 3 ranger") << "writelog_p3_ranger.playerlog" << sg::LogFormat::Player;
  QTest::newRow("carmen 0.7 logger") << "logger_07.clf" << sg::LogFormat::Carmen;
}

// Byte flips, cuts and repeats of a good fixture, strict and lenient, auto and forced: the only
// acceptable outcomes are a Dataset or a LogError.
void TstLogFormat::garbageNeverCrashes() {
  QFETCH(QString, fixture);
  QFETCH(sg::LogFormat, format);
  const std::string good = readFile(logtest::fixture(fixture.toStdString()));
  QVERIFY(!good.empty());
  std::mt19937 rng(12345);
  const char alphabet[] = "0123456789 .-+e\n#,xSONARODMinf\t\r\x80\xff";
  for (int round = 0; round < 600; ++round) {
    std::string text = good;
    const int edits = 1 + round % 4;
    for (int e = 0; e < edits; ++e) {
      const std::size_t at = rng() % (text.size() + 1);
      switch (rng() % 3) {
        case 0:
          if (at < text.size()) text[at] = alphabet[rng() % (sizeof alphabet - 1)];
          break;
        case 1:
          text.erase(at, rng() % 20);
          break;
        default:
          text.insert(at, text.substr(rng() % text.size(), rng() % 40));
          break;
      }
    }
    sg::LogOptions o;
    o.format = round % 2 == 0 ? format : sg::LogFormat::Auto;
    o.lenient = round % 3 == 0;
    o.ring = sg::SonarRing::amigobot();
    o.ring->sonars.resize(4);
    o.csv = sg::parseCsvLayout(kCsvSpec);
    try {
      const sg::Dataset d = sg::parseLog(text, "g", o);
      QVERIFY(d.ring.size() > 0);
      for (const sg::Scan& s : d.scans) {
        for (const sg::Reading& r : s.readings) QVERIFY(r.sonar < d.ring.size());
      }
    } catch (const sg::LogError&) {
    }
  }
}

// Every number the loggers' formats print (writer_fixtures.h: Player's "%+07.3f" family, CARMEN's
// "%f", "%lf", "%.2lf") and printf's other float conversions, for values of every sign and size:
// a finite one reads back as C's strtod reads the same text, an infinite or undefined one is
// recognised as a number that is not finite.
void TstLogFormat::printfNumbers_data() {
  QTest::addColumn<QByteArray>("text");
  QTest::addColumn<bool>("finite");
  const writer_fixtures::CLocale c;
  const char* formats[] = {"%+07.3f", "%+04.3f", "%+07.4f", "%.3f", "%014.3f", "%f", "%lf",
                           "%.2lf",   "%+.8f",   "%e",      "%E",   "%g",      "%G", "%F"};
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double values[] = {-1234.5678,   -1.5,   -0.0004, -0.0, 0.0,  0.0004, 1.5,
                           1166644800.1, 1e-300, 1e300,   inf,  -inf, nan,    -nan};
  for (const char* f : formats) {
    for (const double v : values) {
      char buf[400];
      std::snprintf(buf, sizeof buf, f, v);
      // printf pads inf and nan with blanks, not zeros ("%+07.3f" gives "   +inf"): in a log line
      // they separate fields, so the reader's token is the rest.
      const QByteArray token = QByteArray(buf).trimmed();
      QTest::addRow("%s %s", f, token.constData()) << token << std::isfinite(v);
    }
  }
}

void TstLogFormat::printfNumbers() {
  QFETCH(QByteArray, text);
  QFETCH(bool, finite);
  double v = 0.0;
  const sg::text::NumberText got =
      sg::text::parseNumber(std::string_view(text.constData(), std::size_t(text.size())), v);
  if (!finite) {
    QCOMPARE(int(got), int(sg::text::NumberText::kNotFinite));
    return;
  }
  QCOMPARE(int(got), int(sg::text::NumberText::kFinite));
  const writer_fixtures::CLocale c;
  QCOMPARE(v, std::strtod(text.constData(), nullptr));
}

void TstLogFormat::refusedNumbers_data() {
  QTest::addColumn<QByteArray>("text");
  QTest::addColumn<int>("kind");
  const int notANumber = int(sg::text::NumberText::kNotANumber);
  const int outOfRange = int(sg::text::NumberText::kOutOfRange);
  // printf never writes these: no digits, two signs, a unit, hexadecimal, blanks, a comma.
  for (const char* t : {"", "+", "-", ".", "+-1", "-+1", "++1", "--1", "1.5m", "0x10", " 1", "1 ",
                        "1,5", "e5", "1e", "+ 1", "inf1"}) {
    QTest::addRow("'%s'", t) << QByteArray(t) << notANumber;
  }
  // Numbers, but none a double can hold.
  for (const char* t : {"1e400", "-1e400", "+1e400", "1e-400"}) {
    QTest::addRow("'%s'", t) << QByteArray(t) << outOfRange;
  }
}

void TstLogFormat::refusedNumbers() {
  QFETCH(QByteArray, text);
  QFETCH(int, kind);
  double v = 42.0;
  QCOMPARE(
      int(sg::text::parseNumber(std::string_view(text.constData(), std::size_t(text.size())), v)),
      kind);
  QCOMPARE(v, 42.0);  // left as it was
}

// The fixtures in tests/data/logs/ and the fuzz seeds are what make_writer_fixtures writes from
// writer_fixtures.h today (regenerate them with `make_writer_fixtures tests` after a change).
void TstLogFormat::writerFixturesAreCommitted_data() {
  QTest::addColumn<QString>("path");
  QTest::addColumn<QByteArray>("text");
  const QString tests = QStringLiteral(SONARGRID_TEST_DATA "/..");
  for (const writer_fixtures::File& f : writer_fixtures::files()) {
    const std::string text = f.make();
    const QString name = QString::fromStdString(f.name);
    QTest::addRow("data/logs/%s", f.name.c_str())
        << tests + "/data/logs/" + name << QByteArray::fromStdString(text);
    for (const std::string& target : f.corpora) {
      QTest::addRow("fuzz/corpus/%s/%s", target.c_str(), f.name.c_str())
          << tests + "/fuzz/corpus/" + QString::fromStdString(target) + "/" + name
          << QByteArray::fromStdString(text);
    }
  }
}

void TstLogFormat::writerFixturesAreCommitted() {
  QFETCH(QString, path);
  QFETCH(QByteArray, text);
  QCOMPARE(QByteArray::fromStdString(readFile(path.toStdString())), text);
}

// The same ring, poses and ranges written by Player 3's writelog, CARMEN's logger and SonarGrid's
// own writer load as the same readings and map to the same bytes.
void TstLogFormat::everyLoggerGivesTheSameReadings() {
  const sg::Dataset expected = writer_fixtures::dataset();
  sg::LoadReport carmenReport;
  const sg::Dataset carmen = sg::readLog(logtest::fixture("logger_07.clf"), {}, &carmenReport);
  QCOMPARE(carmenReport.format, sg::LogFormat::Carmen);
  QVERIFY(carmen == expected);  // ring, poses with truth, ranges; 5.00 and 7.25 are no echo
  const sg::Dataset sglog = sg::readLog(logtest::fixture("writer.sglog"));
  QCOMPARE(sglog.ring, expected.ring);
  QCOMPARE(sglog.scans, expected.scans);

  // Player logs no cone angle: the preset (here the default ring with CARMEN's cone) lends it.
  sg::LogOptions withCone;
  withCone.ring = sg::SonarRing{};
  withCone.ring->apertureRad = writer_fixtures::kConeAngle;
  sg::LoadReport playerReport;
  const sg::Dataset player =
      sg::readLog(logtest::fixture("writelog_p3_sonar.playerlog"), withCone, &playerReport);
  QCOMPARE(playerReport.format, sg::LogFormat::Player);  // "## Player version 3.0.2"
  QCOMPARE(player.ring, carmen.ring);
  QCOMPARE(player.scans.size(), carmen.scans.size());
  for (std::size_t i = 0; i < player.scans.size(); ++i) {
    QCOMPARE(player.scans[i].time, carmen.scans[i].time);
    QCOMPARE(player.scans[i].odometry, carmen.scans[i].odometry);
    QVERIFY(!player.scans[i].truth.has_value());  // writelog has no true pose
    QCOMPARE(player.scans[i].readings, carmen.scans[i].readings);
  }

  sg::MapperSettings settings;  // HPF and addition, the defaults; odometry poses
  const sg::GridSpec grid = carmen.fittingGrid(sg::PoseSource::Odometry, 0.05);
  sg::Mapper fromCarmen(carmen.ring, grid, settings);
  sg::Mapper fromPlayer(player.ring, grid, settings);
  QVERIFY(fromCarmen.mapDataset(carmen));
  QVERIFY(fromPlayer.mapDataset(player));
  QCOMPARE(fromPlayer.readingsIntegrated(), std::size_t{16});
  const sg::OccupancyMap a = fromCarmen.snapshot();
  const sg::OccupancyMap b = fromPlayer.snapshot();
  QVERIFY(a.filledCount() > 0);
  QCOMPARE(bytesOf(b.probability.values()), bytesOf(a.probability.values()));
  QCOMPARE(bytesOf(b.native.values()), bytesOf(a.native.values()));
  QCOMPARE(bytesOf(b.level), bytesOf(a.level));
  QCOMPARE(bytesOf(b.filled.values()), bytesOf(a.filled.values()));
  QCOMPARE(bytesOf(b.observed), bytesOf(a.observed));
}

QTEST_GUILESS_MAIN(TstLogFormat)
#include "tst_log_format.moc"
