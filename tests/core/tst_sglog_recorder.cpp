// SPDX-License-Identifier: BSD-3-Clause
// The streamed .sglog (docs/formats.md, "Streamed logs"): the recorder writes the same scan lines
// as writeSglog; a streamed log cut after any complete line loads with every scan up to the cut;
// a last line cut short is left out and reported, never read as a shorter number; a finished one
// loads as the complete log.

#include <QFile>
#include <QTemporaryDir>
#include <QtTest>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "sonargrid/io/log_options.h"
#include "sonargrid/io/sglog.h"
#include "sonargrid/io/sglog_recorder.h"
#include "sonargrid/io/start_pose.h"
#include "sonargrid/io/text_lines.h"

namespace {

sg::Dataset sample() {
  sg::Dataset d;
  d.name = "recorded \"live\"";
  d.ring = sg::SonarRing::amigobot();
  d.ring.maxRange = 5.0;
  for (int k = 0; k < 12; ++k) {
    sg::Scan s;
    s.time = 0.1 * k;
    s.odometry = sg::Pose2D(0.01 * k, -0.002 * k, 0.05 * k);
    if (k % 3 != 0) s.truth = sg::Pose2D(0.01 * k + 0.001, 0.0, 0.05 * k);
    for (int i = 0; i < k % 4; ++i) {
      const auto sonar = static_cast<std::uint16_t>((k + i) % 8);
      s.readings.push_back({sonar, i == 2 ? sg::Reading::kNoEcho : 0.5 + 0.001 * k, s.time});
    }
    d.scans.push_back(s);
  }
  return d;
}

std::string readFile(const QString& path) {
  QFile f(path);
  if (!f.open(QIODevice::ReadOnly)) return {};
  const QByteArray b = f.readAll();
  return std::string(b.constData(), static_cast<std::size_t>(b.size()));
}

sg::Dataset parse(const std::string& text, sg::LoadReport& report) {
  sg::text::MemorySource source(text);
  return sg::readSglog(source, "t.sglog", sg::LogOptions{}, report);
}

}  // namespace

class TstSglogRecorder : public QObject {
  Q_OBJECT

 private slots:
  // One formatter: writeSglog's text is the header, each scan's text and 'end', piece by piece.
  void piecesMakeTheWholeLog() {
    const sg::Dataset d = sample();
    std::ostringstream whole;
    sg::writeSglog(d, whole);
    std::string pieces = sg::sglogHeaderText(d, false);
    double last = -INFINITY;
    for (const sg::Scan& s : d.scans) {
      sg::appendSglogScan(pieces, s, d.ring, last);
      last = s.time;
    }
    pieces += sg::kSglogEndLine;
    QCOMPARE(QString::fromStdString(pieces), QString::fromStdString(whole.str()));
  }

  // Finished, the streamed log reads back as the dataset, exactly.
  void finishedLogRoundTrips() {
    QTemporaryDir dir;
    const QString path = dir.filePath("live.sglog");
    const sg::Dataset d = sample();
    {
      sg::SglogRecorder rec(path.toStdString(), d);
      for (const sg::Scan& s : d.scans) rec.append(s);
      QCOMPARE(rec.scans(), d.scans.size());
      QCOMPARE(rec.readings(), d.readingCount());
      rec.finish();
      QVERIFY(rec.finished());
    }
    const std::string text = readFile(path);
    QVERIFY(text.ends_with("\nend\n"));
    QVERIFY(text.find("\nstreamed\nend_header\n") != std::string::npos);
    QCOMPARE(sg::readSglog(path.toStdString()), d);
  }

  // The file on disk is a valid log after every append, before finish(): what a SIGKILL leaves.
  void loadableAfterEveryAppend() {
    QTemporaryDir dir;
    const QString path = dir.filePath("live.sglog");
    const sg::Dataset d = sample();
    sg::SglogRecorder rec(path.toStdString(), d);
    for (std::size_t k = 0; k < d.scans.size(); ++k) {
      rec.append(d.scans[k]);
      const sg::Dataset got = sg::readSglog(path.toStdString());
      QCOMPARE(got.scans.size(), k + 1);
      QCOMPARE(got.scans.back(), d.scans[k]);
    }
  }

  // Cut after any complete line: every scan line up to the cut is there, and its readings up to
  // the cut; nothing is reported.
  void cutAfterAnyLine() {
    const sg::Dataset d = sample();
    std::string text = sg::sglogHeaderText(d, true);
    const std::size_t bodyStart = text.size();
    double last = -INFINITY;
    for (const sg::Scan& s : d.scans) {
      sg::appendSglogScan(text, s, d.ring, last);
      last = s.time;
    }
    for (std::size_t cut = text.find('\n', bodyStart); cut != std::string::npos;
         cut = text.find('\n', cut + 1)) {
      const std::string head = text.substr(0, cut + 1);
      std::size_t scans = 0;
      std::size_t readings = 0;
      for (std::size_t p = bodyStart; p < head.size(); p = head.find('\n', p) + 1) {
        if (head.compare(p, 5, "scan ") == 0) ++scans;
        if (head.compare(p, 2, "r ") == 0) ++readings;
      }
      sg::LoadReport report;
      const sg::Dataset got = parse(head, report);
      QCOMPARE(got.scans.size(), scans);
      QCOMPARE(got.readingCount(), readings);
      QCOMPARE(report.skippedLines, std::size_t{0});
    }
  }

  // Cut inside a line: the partial line is left out and reported, even where it would read (a
  // range or a time with digits missing).
  void cutInsideALine_data() {
    QTest::addColumn<QString>("tail");
    QTest::newRow("range cut to fewer digits") << "r 3 1.2";
    QTest::newRow("time cut short") << "r 3 1.25 0.1";
    QTest::newRow("scan line cut") << "scan 0.2 0 0";
    QTest::newRow("keyword cut") << "sc";
    QTest::newRow("'end' without its line ending") << "end";
  }
  void cutInsideALine() {
    QFETCH(QString, tail);
    const std::string text =
        "sglog 1\nname \"t\"\nrobot custom\naperture 0.4\nmin_range 0.1\nmax_range 5\n"
        "sonar 0 0 0 0\nsonar 1 0 0 1\nsonar 2 0 0 2\nsonar 3 0 0 3\nstreamed\nend_header\n"
        "scan 0 0 0 0 none\nr 0 1 0\nr 1 2 0\n" +
        tail.toStdString();
    sg::LoadReport report;
    const sg::Dataset got = parse(text, report);
    QCOMPARE(got.scans.size(), std::size_t{1});
    QCOMPARE(got.readingCount(), std::size_t{2});
    if (tail == "end") {
      QCOMPARE(report.skippedLines, std::size_t{0});
      return;
    }
    QCOMPARE(report.skippedLines, std::size_t{1});
    QVERIFY2(report.summary().find("cut short") != std::string::npos, report.summary().c_str());
  }

  // Without the 'streamed' record nothing changes: a log without 'end' is truncated.
  void unstreamedStillNeedsEnd() {
    const std::string text =
        "sglog 1\nname \"t\"\nrobot custom\naperture 0.4\nmin_range 0.1\nmax_range 5\n"
        "sonar 0 0 0 0\nend_header\nscan 0 0 0 0 none\nr 0 1 0\n";
    sg::LoadReport report;
    QVERIFY_THROWS_EXCEPTION(sg::LogError, parse(text, report));
  }

  void secondStreamedRecordIsAnError() {
    const std::string text =
        "sglog 1\nname \"t\"\nstreamed\nrobot custom\naperture 0.4\nmin_range 0.1\nmax_range 5\n"
        "sonar 0 0 0 0\nstreamed\nend_header\n";
    sg::LoadReport report;
    try {
      parse(text, report);
      QFAIL("no error");
    } catch (const sg::LogError& e) {
      QCOMPARE(QString(e.what()),
               QString("t.sglog:9: streamed: expected one 'streamed' line, found a second (the "
                       "first is line 3)"));
    }
  }

  // A scan the reader would reject is refused before anything is written.
  void refusesBadScans() {
    QTemporaryDir dir;
    const QString path = dir.filePath("live.sglog");
    const sg::Dataset d = sample();
    sg::SglogRecorder rec(path.toStdString(), d);
    rec.append(d.scans[5]);
    QVERIFY_THROWS_EXCEPTION(std::runtime_error, rec.append(d.scans[4]));  // earlier
    sg::Scan bad = d.scans[6];
    bad.readings.push_back({8, 1.0, bad.time});  // an AmigoBot has sonars 0..7
    QVERIFY_THROWS_EXCEPTION(std::runtime_error, rec.append(bad));
    rec.finish();
    QCOMPARE(sg::readSglog(path.toStdString()).scans.size(), std::size_t{1});
    QVERIFY_THROWS_EXCEPTION(std::runtime_error, rec.append(d.scans[7]));
  }

  // Issue 50, item 8: the start pose. Worked by hand: the robot's odometry says (1, 2) m facing
  // +y (90 degrees), then (1, 3) m: one metre ahead. Started at (5, 5) m facing +x, that metre is
  // along +x: (6, 5) m, heading 0. The true pose is already in the map's frame and stays.
  void placingMovesThePathRigidly() {
    sg::Dataset d;
    d.ring = sg::SonarRing::amigobot();
    const double quarter = std::numbers::pi / 2;
    d.scans.resize(2);
    d.scans[0].odometry = sg::Pose2D(1.0, 2.0, quarter);
    d.scans[1].odometry = sg::Pose2D(1.0, 3.0, quarter);
    d.scans[1].time = 1.0;
    d.scans[1].truth = sg::Pose2D(7.0, 7.0, 1.0);
    sg::placeOdometryAt(d, sg::Pose2D(5.0, 5.0, 0.0));
    QCOMPARE(d.scans[0].odometry, sg::Pose2D(5.0, 5.0, 0.0));
    QVERIFY(std::abs(d.scans[1].odometry.x() - 6.0) < 1e-15);
    QVERIFY(std::abs(d.scans[1].odometry.y() - 5.0) < 1e-15);
    QCOMPARE(d.scans[1].odometry.heading, 0.0);
    QCOMPARE(*d.scans[1].truth, sg::Pose2D(7.0, 7.0, 1.0));

    std::string why;
    const auto p = sg::parseStartPose("5,-2.5,90", &why);
    QVERIFY2(p.has_value(), why.c_str());
    QCOMPARE(*p, sg::Pose2D(5.0, -2.5, sg::wrapAngle(quarter)));
    QVERIFY(!sg::parseStartPose("5,2", &why));
    QCOMPARE(why, std::string("expected X,Y,THETA (metres, metres, degrees), found '5,2'"));
    QVERIFY(!sg::parseStartPose("5,nan,0", &why));
    QCOMPARE(why, std::string("expected a number for Y in X,Y,THETA, found 'nan'"));
    QVERIFY(!sg::parseStartPose("5,2,720", &why));
    QCOMPARE(why, std::string("expected THETA in degrees between -360 and 360, found '720'"));
  }

  // A recording that knows where the robot started writes it in the header ('start_pose', docs/
  // formats.md); the reader places the odometry there, and LogOptions::startPose overrides it.
  void aRecordedStartPosePlacesTheLog() {
    QTemporaryDir dir;
    const QString path = dir.filePath("live.sglog");
    const sg::Dataset d = sample();  // its first odometry is (0, 0, 0)
    const sg::Pose2D start(5.0, 4.0, 0.0);
    {
      sg::SglogRecorder rec(path.toStdString(), d, 1.0, start);
      for (const sg::Scan& s : d.scans) rec.append(s);
      rec.finish();
    }
    QVERIFY(readFile(path).find("\nstart_pose 5 4 0\nstreamed\nend_header\n") != std::string::npos);
    const sg::Dataset read = sg::readSglog(path.toStdString());
    QCOMPARE(read.scans.size(), d.scans.size());
    // Heading 0 at a first odometry of heading 0: the path is shifted by (5, 4) m, by hand.
    for (std::size_t i = 0; i < d.scans.size(); ++i) {
      QCOMPARE(read.scans[i].odometry.x(), d.scans[i].odometry.x() + 5.0);
      QCOMPARE(read.scans[i].odometry.y(), d.scans[i].odometry.y() + 4.0);
      QCOMPARE(read.scans[i].odometry.heading, d.scans[i].odometry.heading);
      QCOMPARE(read.scans[i].truth, d.scans[i].truth);
      QCOMPARE(read.scans[i].readings, d.scans[i].readings);
    }
    sg::LogOptions o;
    o.startPose = sg::Pose2D(0.0, 0.0, 0.0);
    sg::LoadReport report;
    const std::string text = readFile(path);
    sg::text::MemorySource source(text);
    QCOMPARE(sg::readSglog(source, "t.sglog", o, report).scans, d.scans);
  }

  void startPoseErrorsNameTheLine() {
    sg::Dataset d = sample();
    std::string text = sg::sglogHeaderText(d, false, sg::Pose2D(1.0, 2.0, 0.5));
    const std::size_t at = text.find("start_pose");
    QVERIFY(at != std::string::npos);
    const std::size_t line =
        static_cast<std::size_t>(std::count(text.begin(), text.begin() + at, '\n')) + 1;
    auto errorOf = [](const std::string& t) -> QString {
      sg::LoadReport report;
      try {
        parse(t, report);
      } catch (const sg::LogError& e) {
        return QString(e.what());
      }
      return "no error";
    };
    std::string twice = text;
    twice.insert(at, "start_pose 0 0 0\n");
    QCOMPARE(errorOf(twice + "end\n"),
             QString("t.sglog:%1: start_pose: expected one 'start_pose' line, found a second (the "
                     "first is line %2)")
                 .arg(line + 1)
                 .arg(line));
    std::string bad = text;
    bad.replace(at, std::string("start_pose 1 2").size(), "start_pose 1 north");
    QCOMPARE(
        errorOf(bad + "end\n"),
        QString("t.sglog:%1: start_pose y: expected a number of metres, found 'north'").arg(line));
    QVERIFY_THROWS_EXCEPTION(std::runtime_error,
                             sg::sglogHeaderText(d, false, sg::Pose2D(NAN, 0.0, 0.0)));
  }

  void unwritablePathNamesIt() {
    try {
      sg::SglogRecorder rec("/nonexistent-dir/x.sglog", sample());
      QFAIL("no error");
    } catch (const std::runtime_error& e) {
      QVERIFY2(QString(e.what()).startsWith("cannot write '/nonexistent-dir/x.sglog': "), e.what());
    }
  }
};

QTEST_GUILESS_MAIN(TstSglogRecorder)
#include "tst_sglog_recorder.moc"
