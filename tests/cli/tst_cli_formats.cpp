// SPDX-License-Identifier: GPL-3.0-or-later
// The log-reading flags of sonargrid-cli (--format, --lenient, --robot, --columns, --poses,
// --start-pose) on map, score and goodness, and the convert command (docs/cli.md).

#include <QFile>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QTemporaryDir>
#include <QtTest>
#include <algorithm>
#include <cmath>

namespace {

const QString kCli = QStringLiteral(SONARGRID_CLI);
const QString kLogs = QStringLiteral(SONARGRID_TEST_DATA) + "/logs/";
const QString kCsvSpec =
    "header=1,time=1,x=2,y=3,theta=4,sonars=5-8,length=mm,angle=ddeg,noecho=5110";

struct Run {
  int code = -1;
  QByteArray out;
  QByteArray err;
};

Run runCli(const QStringList& args) {
  QProcess p;
  p.start(kCli, args);
  Run r;
  if (!p.waitForStarted(10000) || !p.waitForFinished(60000)) {
    p.kill();
    p.waitForFinished(5000);
    r.err = "did not run to completion";
    return r;
  }
  r.code = p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -2;
  r.out = p.readAllStandardOutput();
  r.err = p.readAllStandardError();
  return r;
}

QByteArray describe(const QStringList& args, const Run& r) {
  return "sonargrid-cli " + args.join(' ').toUtf8() + "\n  exit " + QByteArray::number(r.code) +
         "\n  stdout: " + r.out.left(400) + "\n  stderr: " + r.err.left(600);
}

QJsonObject jsonOf(const QByteArray& out) {
  return QJsonDocument::fromJson(out).object();
}

const QString kBags = QStringLiteral(SONARGRID_TEST_DATA) + "/bags/room/";
const QString kRoom = QStringLiteral(SONARGRID_DATASETS) + "/room/room.sglog";

QByteArray fileBytes(const QString& path) {
  QFile f(path);
  return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}

const QStringList kHimm{"--model", "himm", "--rule", "himm", "--json"};

}  // namespace

class TstCliFormats : public QObject {
  Q_OBJECT
 private slots:
  void mapEveryFormat_data();
  void mapEveryFormat();
  void convertCarmenToSglogMapsTheSame();
  void convertSglogToCarmenAndBack();
  void convertJson();
  void lenientReportsOnStderr();
  void bagsMapAsTheirSglog_data();
  void bagsMapAsTheirSglog();
  void convertABagWritesItsLog();
  void bagTopicFlags();
  void scoreAndGoodnessTakeTheFlags();
  void startPosePutsTheOdometryMapOnItsReference();
  void errors_data();
  void errors();
};

void TstCliFormats::mapEveryFormat_data() {
  QTest::addColumn<QStringList>("args");
  QTest::addColumn<int>("readings");
  // Readings: small.clf 2 SONAR lines x 4; small_p2 2 scans x 4 (the early one is skipped);
  // small_p1 2 x 8; mm_ddeg.csv 3 rows x 4; ranges_only.txt 3 rows x 4.
  QTest::newRow("carmen auto") << QStringList{"--log", kLogs + "small.clf"} << 8;
  QTest::newRow("carmen forced") << QStringList{"--log", kLogs + "small.clf", "--format", "carmen"}
                                 << 8;
  QTest::newRow("player 2") << QStringList{"--log", kLogs + "small_p2.playerlog"} << 8;
  QTest::newRow("player 1 + preset")
      << QStringList{"--log", kLogs + "small_p1.playerlog", "--robot", "amigobot"} << 16;
  QTest::newRow("csv") << QStringList{"--log",   kLogs + "mm_ddeg.csv",  "--columns", kCsvSpec,
                                      "--robot", kLogs + "ring4_mm.geom"}
                       << 12;
  QTest::newRow("csv + poses") << QStringList{"--log",     kLogs + "ranges_only.txt",
                                              "--format",  "csv",
                                              "--columns", "time=1,sonars=2-5",
                                              "--poses",   kLogs + "poses.txt",
                                              "--robot",   kLogs + "ring4_mm.geom"}
                               << 12;
}

void TstCliFormats::mapEveryFormat() {
  QFETCH(QStringList, args);
  QFETCH(int, readings);
  const QStringList all = QStringList{"map"} + args + kHimm;
  const Run r = runCli(all);
  QVERIFY2(r.code == 0 && r.err.isEmpty(), describe(all, r));
  QCOMPARE(jsonOf(r.out).value("readings").toInt(), readings);
}

void TstCliFormats::convertCarmenToSglogMapsTheSame() {
  QTemporaryDir dir;
  const QString sglog = dir.filePath("small.sglog");
  const Run c = runCli({"convert", "--in", kLogs + "small.clf", "--out", sglog});
  QVERIFY2(c.code == 0, describe({"convert"}, c));
  const Run a = runCli(QStringList{"map", "--log", kLogs + "small.clf", "--pose", "truth"} + kHimm);
  const Run b = runCli(QStringList{"map", "--log", sglog, "--pose", "truth"} + kHimm);
  QVERIFY(a.code == 0 && b.code == 0);
  QJsonObject ja = jsonOf(a.out), jb = jsonOf(b.out);
  ja.remove("elapsed_ms");
  jb.remove("elapsed_ms");
  QCOMPARE(ja, jb);
}

void TstCliFormats::convertSglogToCarmenAndBack() {
  // CARMEN carries one range per sonar per SONAR line: the sonars small.sglog leaves out of a
  // scan come back as no-echo readings (3 scans x 4 sonars = 12 instead of 5), which HIMM ignores,
  // so the map is the same.
  QTemporaryDir dir;
  const QString clf = dir.filePath("small.clf");
  const QString back = dir.filePath("back.sglog");
  const QString src = QStringLiteral(SONARGRID_TEST_DATA) + "/sglog/small.sglog";
  QCOMPARE(runCli({"convert", "--in", src, "--out", clf}).code, 0);
  QCOMPARE(runCli({"convert", "--in", clf, "--out", back}).code, 0);
  const Run a = runCli(QStringList{"map", "--log", src} + kHimm);
  const Run b = runCli(QStringList{"map", "--log", back} + kHimm);
  QJsonObject ja = jsonOf(a.out), jb = jsonOf(b.out);
  QCOMPARE(ja.value("readings").toInt(), 5);
  QCOMPARE(jb.value("readings").toInt(), 12);
  for (const char* key : {"elapsed_ms", "readings"}) {
    ja.remove(key);
    jb.remove(key);
  }
  QCOMPARE(ja, jb);
}

void TstCliFormats::convertJson() {
  QTemporaryDir dir;
  const QStringList args{
      "convert", "--in",  kLogs + "small.clf", "--out", dir.filePath("x.log"), "--to",
      "sglog",   "--json"};
  const Run r = runCli(args);
  QVERIFY2(r.code == 0 && r.err.isEmpty(), describe(args, r));
  const QJsonObject o = jsonOf(r.out);
  QCOMPARE(o.value("in_format").toString(), QString("carmen"));
  QCOMPARE(o.value("out_format").toString(), QString("sglog"));
  QCOMPARE(o.value("scans").toInt(), 2);
  QCOMPARE(o.value("readings").toInt(), 8);
  QCOMPARE(o.value("lines").toInt(), 12);
  QCOMPARE(o.value("skipped_lines").toInt(), 0);
  // PARAM, SYNC and FLASER once each (tests/data/logs/small.clf).
  QCOMPARE(o.value("ignored_messages").toObject(),
           (QJsonObject{{"PARAM", 1}, {"SYNC", 1}, {"FLASER", 1}}));
}

void TstCliFormats::lenientReportsOnStderr() {
  const QString path = kLogs + "bad/range.clf";
  const QStringList args = QStringList{"map", "--log", path, "--lenient"} + kHimm;
  const Run r = runCli(args);
  QVERIFY2(r.code == 0, describe(args, r));
  QCOMPARE(jsonOf(r.out).value("readings").toInt(), 2);  // the one good SONAR of two sonars
  QCOMPARE(QString::fromUtf8(r.err),
           "sonargrid-cli: " + path + ": --lenient skipped 1 bad line:\n  1 line: " + path +
               ":3: SONAR r[1]: expected a range in metres >= 0, found 'x'\n");
}

void TstCliFormats::scoreAndGoodnessTakeTheFlags() {
  const QStringList common{"--log",    kLogs + "small_p1.playerlog",
                           "--robot",  "amigobot",
                           "--format", "player",
                           "--model",  "himm",
                           "--rule",   "himm",
                           "--json"};
  const Run g = runCli(QStringList{"goodness"} + common);
  QVERIFY2(g.code == 0, describe(common, g));
  const QString ref = QStringLiteral(SONARGRID_TEST_DATA) + "/reference/box_cm.json";
  const Run s = runCli(QStringList{"score", "--reference", ref, "--metrics", "iop"} + common);
  QVERIFY2(s.code == 0, describe(common, s));
}

// Issue 50, item 8. A robot switched on where it stands starts its odometry at 0, so its map
// lies in a frame of its own. The room log rewritten with its odometry starting at (0, 0, 0)
// (convert --start-pose 0,0,0: the path moved rigidly) is that robot's log; its first scan's true
// pose, (1.5 m, 1 m, 0) as room.sglog's first 'scan' line says, is where it stood in the
// reference's frame. The room's odometry equals its true pose (datasets/README.md), so placing
// the odometry there must score as the true-pose map of the room log does.
void TstCliFormats::startPosePutsTheOdometryMapOnItsReference() {
  QTemporaryDir tmp;
  QVERIFY(tmp.isValid());
  const QString zero = tmp.filePath("room-from-zero.sglog");
  const QStringList convert{"convert", "--in", kRoom, "--out", zero, "--start-pose", "0,0,0"};
  const Run c = runCli(convert);
  QVERIFY2(c.code == 0, describe(convert, c));
  QVERIFY(fileBytes(zero).contains("\nscan 0 0 0 0 1.5 1 0\n"));  // odometry 0, truth kept

  const QString ref = QStringLiteral(SONARGRID_DATASETS) + "/room/room.json";
  auto score = [&](const QString& log, const QStringList& more) {
    const QStringList args = QStringList{"score",   "--reference", ref,      "--log", log,
                                         "--model", "himm",        "--rule", "himm",  "--json"} +
                             more;
    const Run r = runCli(args);
    [&] { QVERIFY2(r.code == 0, describe(args, r)); }();
    return jsonOf(r.out);
  };
  const QJsonObject truth = score(kRoom, {"--pose", "truth"});
  const QJsonObject unplaced = score(zero, {"--pose", "odom"});
  const QJsonObject placed = score(zero, {"--pose", "odom", "--start-pose", "1.5,1,0"});
  QVERIFY(!truth.isEmpty() && !unplaced.isEmpty() && !placed.isEmpty());
  // Unplaced, the map is off by the start pose: IOP near a metre, no correlation (measured 974 mm
  // and -5 %); placed, every metric is the true-pose map's.
  QVERIFY2(unplaced["iop_mm"].toDouble() > 500.0,
           QByteArray::number(unplaced["iop_mm"].toDouble()));
  QVERIFY(unplaced["correlation_pct"].toDouble() < 10.0);
  QVERIFY(truth["iop_mm"].toDouble() < 100.0);
  for (const QString& key : truth.keys()) {
    if (!truth[key].isDouble()) continue;
    const double a = truth[key].toDouble();
    const double b = placed[key].toDouble();
    QVERIFY2(std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(a)),
             qPrintable(key + ": " + QString::number(a, 'g', 17) + " vs " +
                        QString::number(b, 'g', 17)));
  }

  // A start pose in the log's header (what `record --start-pose` writes) places it the same way,
  // and --start-pose overrides it.
  QByteArray text = fileBytes(zero);
  text.replace("\nend_header\n", "\nstart_pose 1.5 1 0\nend_header\n");
  const QString headed = tmp.filePath("room-headed.sglog");
  QFile out(headed);
  QVERIFY(out.open(QIODevice::WriteOnly) && out.write(text) == text.size());
  out.close();
  QCOMPARE(score(headed, {"--pose", "odom"})["iop_mm"].toDouble(), placed["iop_mm"].toDouble());
  QCOMPARE(score(headed, {"--pose", "odom", "--start-pose", "0,0,0"})["iop_mm"].toDouble(),
           unplaced["iop_mm"].toDouble());
}

void TstCliFormats::errors_data() {
  QTest::addColumn<QStringList>("args");
  QTest::addColumn<QString>("message");  // stderr without "sonargrid-cli: " and the newline
  const QString bad = kLogs + "bad/range.clf";
  QTest::newRow("format") << QStringList{"map", "--log", bad, "--format", "clf"}
                          << "--format takes auto, sglog, carmen, player, csv or bag, got 'clf'";
  QTest::newRow("strict") << QStringList{"map", "--log", bad}
                          << bad + ":3: SONAR r[1]: expected a range in metres >= 0, found 'x'";
  QTest::newRow("robot") << QStringList{"map", "--log", bad, "--robot", "pioneer"}
                         << "--robot takes a preset (p3dx, amigobot, k2a, or a sonar geometry "
                            "file), got 'pioneer'";
  QTest::newRow("columns") << QStringList{"map", "--log", bad, "--columns", "time=1"}
                           << "--columns item 'time=1': expected sonar columns "
                              "(sonars=FIRST-LAST)";
  QTest::newRow("columns with carmen")
      << QStringList{"map", "--log", bad, "--format", "carmen", "--columns", "time=1,sonars=2"}
      << "--columns and --poses describe CSV logs; they do not go with --format carmen";
  QTest::newRow("poses alone") << QStringList{"map", "--log", bad, "--poses", "p.txt"}
                               << "--poses needs --columns";
  QTest::newRow("player without geometry")
      << QStringList{"map", "--log", kLogs + "small_p1.playerlog"}
      << kLogs +
             "small_p1.playerlog: geometry: expected sonar geometry messages or a robot "
             "preset (--robot), found neither";
  QTest::newRow("convert extension")
      << QStringList{"convert", "--in", bad, "--out", "x.txt"}
      << "cannot tell the output format from 'x.txt' (.sglog, .clf or .carmen); give --to sglog "
         "or --to carmen";
  QTest::newRow("convert to") << QStringList{"convert", "--in", bad, "--out", "x", "--to", "csv"}
                              << "--to takes sglog or carmen, got 'csv'";
  QTest::newRow("start pose count")
      << QStringList{"map", "--log", bad, "--start-pose", "1.5,1"}
      << "--start-pose: expected X,Y,THETA (metres, metres, degrees), found '1.5,1'";
  QTest::newRow("start pose number")
      << QStringList{"map", "--log", bad, "--start-pose", "1,2,north"}
      << "--start-pose: expected a number for THETA in X,Y,THETA, found 'north'";
}

void TstCliFormats::errors() {
  QFETCH(QStringList, args);
  QFETCH(QString, message);
  QStringList all = args;
  if (all.first() == "map") all += QStringList{"--model", "himm", "--rule", "himm"};
  const Run r = runCli(all);
  QVERIFY2(r.code == 2, describe(all, r));
  QCOMPARE(QString::fromUtf8(r.err), "sonargrid-cli: " + message + "\n");
  QVERIFY(r.out.isEmpty());
}

void TstCliFormats::bagsMapAsTheirSglog_data() {
  QTest::addColumn<QString>("bag");
  // datasets/room/room.sglog converted by python3-rosbag, @mcap/core and SQLite
  // (tests/data/bags/room/README.md).
  for (const char* b : {"room-none.bag", "room-bz2.bag", "room-lz4.bag", "room-zstd.mcap",
                        "room-lz4.mcap", "room-sqlite"}) {
    QTest::newRow(b) << QString::fromLatin1(b);
  }
}

void TstCliFormats::bagsMapAsTheirSglog() {
  // The same JSON (elapsed_ms aside: grid, cells, the histogram of levels) and the same PNG bytes
  // as the .sglog the bag was made from.
  QFETCH(QString, bag);
  QTemporaryDir dir;
  const QStringList common{"--model", "hpf", "--rule", "bayes", "--pose", "truth", "--json"};
  const QStringList a =
      QStringList{"map", "--log", kBags + bag, "--png", dir.filePath("a.png")} + common;
  const QStringList b = QStringList{"map", "--log", kRoom, "--png", dir.filePath("b.png")} + common;
  const Run ra = runCli(a);
  const Run rb = runCli(b);
  QVERIFY2(ra.code == 0, describe(a, ra));
  QVERIFY2(rb.code == 0, describe(b, rb));
  // What was read is said on stderr.
  QVERIFY2(ra.err.contains("sonar: /sonar (sensor_msgs/Range, 11888 messages), picked"),
           describe(a, ra));
  QJsonObject ja = jsonOf(ra.out), jb = jsonOf(rb.out);
  ja.remove("elapsed_ms");
  jb.remove("elapsed_ms");
  QCOMPARE(ja, jb);
  QCOMPARE(ja.value("readings").toInt(), 11888);
  const QByteArray pa = fileBytes(dir.filePath("a.png"));
  QVERIFY(!pa.isEmpty());
  QVERIFY(pa == fileBytes(dir.filePath("b.png")));
}

void TstCliFormats::convertABagWritesItsLog() {
  QTemporaryDir dir;
  const QString out = dir.filePath("room.sglog");
  const QStringList args{"convert", "--in", kBags + "room-zstd.mcap", "--out", out, "--json"};
  const Run c = runCli(args);
  QVERIFY2(c.code == 0, describe(args, c));
  QCOMPARE(jsonOf(c.out).value("in_format").toString(), QStringLiteral("bag"));
  QCOMPARE(jsonOf(c.out).value("scans").toInt(), 743);
  const Run a = runCli(QStringList{"map", "--log", out, "--pose", "truth"} + kHimm);
  const Run b = runCli(QStringList{"map", "--log", kRoom, "--pose", "truth"} + kHimm);
  QJsonObject ja = jsonOf(a.out), jb = jsonOf(b.out);
  ja.remove("elapsed_ms");
  jb.remove("elapsed_ms");
  QCOMPARE(ja, jb);
}

void TstCliFormats::bagTopicFlags() {
  // --truth-topic - : no true pose, so --pose truth is refused.
  const QStringList none{"map",           "--log",   kBags + "room-lz4.bag",
                         "--truth-topic", "-",       "--pose",
                         "truth",         "--model", "himm",
                         "--rule",        "himm"};
  const Run r = runCli(none);
  QVERIFY2(r.code == 2, describe(none, r));
  // An unknown topic names the bag's topics.
  const QStringList bad{"map",          "--log",  kBags + "room-lz4.bag",
                        "--odom-topic", "/nope",  "--model",
                        "himm",         "--rule", "himm"};
  const Run rb = runCli(bad);
  QVERIFY2(rb.code == 2 && rb.err.contains("the odometry topic /nope is not in the bag") &&
               rb.err.contains("/odom (nav_msgs/Odometry)"),
           describe(bad, rb));
  // The RosAria bag needs the robot; with it, it maps.
  const QStringList aria{"map",  "--log", kBags + "rosaria-room.bag", "--model", "himm", "--rule",
                         "himm", "--json"};
  const Run ra = runCli(aria);
  QVERIFY2(ra.code == 2 && ra.err.contains("--robot"), describe(aria, ra));
  const Run rb2 = runCli(aria + QStringList{"--robot", "p3dx"});
  QVERIFY2(rb2.code == 0, describe(aria, rb2));
  // A topic flag with a text format is a usage error.
  const QStringList mixed{"map",    "--log",   kRoom,  "--format", "sglog", "--sonar-topic",
                          "/sonar", "--model", "himm", "--rule",   "himm"};
  QCOMPARE(runCli(mixed).code, 2);
}

QTEST_GUILESS_MAIN(TstCliFormats)
#include "tst_cli_formats.moc"
