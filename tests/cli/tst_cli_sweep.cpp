// SPDX-License-Identifier: GPL-3.0-or-later
// `sweep`, `sweep-merge` and `optimize` (issue 14; docs/sweeps.md). Tiny grids on the bundled
// arafat-room log (parameterized × bayes-recursive, paper 002's model), so each sweep takes a
// second or two. Every expected result is a property of the contract: shards merged equal the
// whole sweep byte for byte; a sweep stopped by a signal and rerun equals an uninterrupted one; a
// row equals what `score` and `goodness` say of the same set; the same seed gives the same search.

#include <signal.h>

#include <QByteArray>
#include <QElapsedTimer>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QProcessEnvironment>
#include <QTemporaryDir>
#include <QThread>
#include <QtTest>

#include "cli_run.h"

namespace {

using cli_test::kCli;
const QString kRun1 = QStringLiteral(SONARGRID_DATASETS "/arafat-room/run-1.sglog");
const QString kRun2 = QStringLiteral(SONARGRID_DATASETS "/arafat-room/run-2.sglog");
const QString kWorld = QStringLiteral(SONARGRID_DATASETS "/arafat-room/world.json");

using cli_test::describe;
using cli_test::Run;

// The CLI without the test-only per-set delay, whatever the test's environment says.
Run runCli(const QStringList& args) {
  QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
  env.remove("SONARGRID_TEST_SET_DELAY_MS");
  return cli_test::runProgram(cli_test::kCli, args, {}, env);
}

QByteArray readFile(const QString& path) {
  QFile f(path);
  return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}

// The sweep of these tests: 3 × 2 sets (p2 inner, p5 outer... as written: p5 outer), p1 tied.
QStringList baseSweep() {
  return {"sweep",
          "--log",
          kRun1,
          "--reference",
          kWorld,
          "--model",
          "parameterized",
          "--rule",
          "bayes-recursive",
          "--grid",
          "p5=6,15",
          "--grid",
          "p4=0.95:0.01:0.97",
          "--tie",
          "p1=1-p4",
          "--metric",
          "vsdns,entropy",
          "--metric",
          "iop,correlation,auc"};
}

// The data rows of a sweep CSV (lines not starting with '#', less the column line), split.
QList<QList<QByteArray>> dataRows(const QByteArray& csv, QList<QByteArray>* columns = nullptr) {
  QList<QList<QByteArray>> rows;
  bool header = true;
  for (const QByteArray& line : csv.split('\n')) {
    if (line.isEmpty() || line.startsWith('#')) continue;
    if (header) {
      header = false;
      if (columns) *columns = line.split(',');
      continue;
    }
    rows.append(line.split(','));
  }
  return rows;
}

int countDataRows(const QString& path) {
  return static_cast<int>(dataRows(readFile(path)).size());
}

}  // namespace

class TstCliSweep : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase();
  void shardsMergeToWholeSweep();
  void sameBytesAnyThreadCount();
  void interruptedSweepResumes_data();
  void interruptedSweepResumes();
  void resumeRefusesOtherArguments();
  void rowsEqualMapAndScore_data();
  void rowsEqualMapAndScore();
  void tieSetsParameter();
  void badValuesExit2_data();
  void badValuesExit2();
  void mergeRefusesOtherSweeps();
  void optimizeDeterministicForSeed();

 private:
  QString path(const QString& name) const { return tmp_.filePath(name); }
  QTemporaryDir tmp_;
  QByteArray whole_;  // the uninterrupted whole sweep's CSV
  QByteArray wholeJson_;
};

void TstCliSweep::initTestCase() {
  QVERIFY2(QFile::exists(kCli), qPrintable(kCli));
  QVERIFY(tmp_.isValid());
  const QStringList args = baseSweep() << "--csv" << path("whole.csv") << "--json";
  const Run r = runCli(args);
  QVERIFY2(r.finished && r.code == 0, describe(args, r));
  whole_ = readFile(path("whole.csv"));
  wholeJson_ = r.out;
  QCOMPARE(dataRows(whole_).size(), 6);
  const QJsonObject json = QJsonDocument::fromJson(r.out).object();
  QCOMPARE(json.value("rows").toInt(), 6);
  QVERIFY2(json.value("paper002").toObject().contains("optimal_histogram"), r.out);
  QVERIFY2(json.value("best").toObject().value("iop").toObject().contains("iop_mm"), r.out);
  QVERIFY2(json.value("best").toObject().value("entropy").toObject().contains("map_entropy"),
           r.out);
}

void TstCliSweep::shardsMergeToWholeSweep() {
  QStringList mergeArgs{"sweep-merge"};
  // Given out of order: the merge orders rows by set, not by file.
  for (int i : {2, 0, 1}) {
    const QString out = path(QString("shard%1.csv").arg(i));
    const QStringList args = baseSweep() << "--shard" << QString("%1/3").arg(i) << "--csv" << out;
    const Run r = runCli(args);
    QVERIFY2(r.finished && r.code == 0, describe(args, r));
    QCOMPARE(countDataRows(out), 2);  // sets i and i + 3
    mergeArgs << out;
  }
  mergeArgs << "--csv" << path("merged.csv") << "--json";
  const Run r = runCli(mergeArgs);
  QVERIFY2(r.finished && r.code == 0, describe(mergeArgs, r));
  QVERIFY2(readFile(path("merged.csv")) == whole_, "the merged shards differ from the whole sweep");
  QCOMPARE(r.out, wholeJson_);
}

void TstCliSweep::sameBytesAnyThreadCount() {
  for (const char* threads : {"1", "2"}) {
    const QString out = path(QString("threads%1.csv").arg(threads));
    const QStringList args = baseSweep() << "--threads" << threads << "--csv" << out;
    const Run r = runCli(args);
    QVERIFY2(r.finished && r.code == 0, describe(args, r));
    QVERIFY2(readFile(out) == whole_, qPrintable(out + " differs from the whole sweep"));
  }
}

void TstCliSweep::interruptedSweepResumes_data() {
  QTest::addColumn<int>("signal");
  QTest::newRow("SIGINT") << int(SIGINT);
  QTest::newRow("SIGTERM") << int(SIGTERM);
  // Issue 50, item 4: no chance to say anything; the rows already appended are whole.
  QTest::newRow("SIGKILL") << int(SIGKILL);
}

void TstCliSweep::interruptedSweepResumes() {
  QFETCH(int, signal);
  const QString out = path(QString("interrupted%1.csv").arg(signal));
  const QStringList args = baseSweep() << "--threads"
                                       << "2"
                                       << "--csv" << out;
  // The test-only hook (docs/sweeps.md): every set waits 400 ms before its row is written, so the
  // signal comes while sets are left.
  QProcess p;
  QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
  env.insert("SONARGRID_TEST_SET_DELAY_MS", "400");
  p.setProcessEnvironment(env);
  p.start(kCli, args);
  QVERIFY(p.waitForStarted(10000));
  QElapsedTimer waited;
  waited.start();
  while (countDataRows(out) < 1 && waited.elapsed() < 60000 && p.state() == QProcess::Running)
    QThread::msleep(20);
  QVERIFY2(countDataRows(out) >= 1, "no row appeared");
  QCOMPARE(::kill(static_cast<pid_t>(p.processId()), signal), 0);
  QVERIFY(p.waitForFinished(60000));
  if (signal == SIGKILL) {
    QCOMPARE(p.exitStatus(), QProcess::CrashExit);
  } else {
    QCOMPARE(p.exitStatus(), QProcess::NormalExit);
    QCOMPARE(p.exitCode(), 128 + signal);
    QVERIFY2(p.readAllStandardError().contains("run the same command again to resume"), "message");
  }

  // What is left is valid: the whole sweep's header and its first rows, nothing else.
  const QByteArray partial = readFile(out);
  const int rows = countDataRows(out);
  QVERIFY2(rows >= 1 && rows < 6, qPrintable(QString("%1 rows after the signal").arg(rows)));
  QVERIFY2(whole_.startsWith(partial), "the partial CSV is not a prefix of the whole sweep's");
  QVERIFY(partial.endsWith('\n'));

  const Run r = runCli(args);
  QVERIFY2(r.finished && r.code == 0, describe(args, r));
  QVERIFY2(r.out.contains(QByteArray::number(rows) + " resumed"), r.out);
  QVERIFY2(readFile(out) == whole_, "the resumed sweep differs from an uninterrupted one");
}

void TstCliSweep::resumeRefusesOtherArguments() {
  const QString out = path("other.csv");
  QVERIFY(QFile::copy(path("whole.csv"), out));
  QStringList args = baseSweep() << "--csv" << out;
  args[args.indexOf("p5=6,15")] = "p5=6,16";
  const Run r = runCli(args);
  QVERIFY2(r.finished && r.code == 2, describe(args, r));
  QVERIFY2(r.err.contains("holds a different sweep") && r.err.contains("grid"), r.err);
  QVERIFY(readFile(out) == whole_);  // untouched
  QStringList shard = baseSweep() << "--shard"
                                  << "1/2"
                                  << "--csv" << out;
  const Run s = runCli(shard);
  QVERIFY2(s.finished && s.code == 2 && s.err.contains("shard 0/1"), describe(shard, s));
}

void TstCliSweep::rowsEqualMapAndScore_data() {
  QTest::addColumn<int>("pick");  // the set's index in baseSweep() (p5 outer, p4 inner)
  QTest::newRow("set 1: p5 6, p4 0.96") << 1;
  QTest::newRow("set 4: p5 15, p4 0.96") << 4;
}

void TstCliSweep::rowsEqualMapAndScore() {
  QFETCH(int, pick);
  QList<QByteArray> columns;
  const QList<QList<QByteArray>> rows = dataRows(whole_, &columns);
  for (const char* column : {"vsdns", "map_entropy", "iop_mm", "correlation_pct", "auc"})
    QVERIFY2(columns.contains(column), column);
  const QList<QByteArray>& row = rows[pick];
  QCOMPARE(row[0].toInt(), pick);
  QStringList mapFlags{"--log", kRun1, "--model", "parameterized", "--rule", "bayes-recursive"};
  for (const char* p : {"p1", "p2", "p3", "p4", "p5"})
    mapFlags << "--set" << QString("%1=%2").arg(p, QString(row[columns.indexOf(p)]));
  const QStringList score =
      QStringList{"score", "--reference", kWorld, "--metrics", "iop,correlation,auc", "--json"}
      << mapFlags;
  const Run s = runCli(score);
  QVERIFY2(s.finished && s.code == 0, describe(score, s));
  const QJsonObject sj = QJsonDocument::fromJson(s.out).object();
  for (const char* key : {"iop_mm", "correlation_pct", "auc"}) {
    // Exact: the same map (bit-identical at any thread count) and the same metric code.
    QCOMPARE(row[columns.indexOf(key)].toDouble(), sj.value(key).toDouble());
  }
  const QStringList goodness = QStringList{"goodness", "--json"} << mapFlags;
  const Run g = runCli(goodness);
  QVERIFY2(g.finished && g.code == 0, describe(goodness, g));
  const QJsonObject gj = QJsonDocument::fromJson(g.out).object();
  QCOMPARE(row[columns.indexOf("vsdns")].toDouble(), gj.value("vsdns").toDouble());
  // The sweep's map_entropy is goodness's entropy_bits (Σ over the observed cells) of the same
  // map, exactly.
  QCOMPARE(row[columns.indexOf("map_entropy")].toDouble(), gj.value("entropy_bits").toDouble());
}

void TstCliSweep::tieSetsParameter() {
  QList<QByteArray> columns;
  const QList<QList<QByteArray>> rows = dataRows(whole_, &columns);
  QCOMPARE(rows.size(), 6);
  const double p4s[] = {0.95, 0.96, 0.97};  // the axis p4=0.95:0.01:0.97, decimal steps
  for (int i = 0; i < rows.size(); ++i) {
    const double p4 = rows[i][columns.indexOf("p4")].toDouble();
    QCOMPARE(p4, p4s[i % 3]);  // p4 is the inner (last) axis
    QCOMPARE(rows[i][columns.indexOf("p5")].toDouble(), i < 3 ? 6.0 : 15.0);
    QCOMPARE(rows[i][columns.indexOf("p1")].toDouble(), 1.0 - p4);  // --tie p1=1-p4
  }
  // A constant tie and a tie to a parameter, both in one sweep.
  const QString out = path("ties.csv");
  const QStringList args = {"sweep",
                            "--log",
                            kRun1,
                            "--model",
                            "parameterized",
                            "--rule",
                            "bayes-recursive",
                            "--grid",
                            "p2=0.05,0.1",
                            "--tie",
                            "p1=0.03",
                            "--tie",
                            "p4=0.97",
                            "--tie",
                            "p3=p2",
                            "--metric",
                            "derivative",
                            "--csv",
                            out};
  const Run r = runCli(args);
  QVERIFY2(r.finished && r.code == 0, describe(args, r));
  const QList<QList<QByteArray>> tied = dataRows(readFile(out), &columns);
  QCOMPARE(tied.size(), 2);
  for (const QList<QByteArray>& row : tied) {
    QCOMPARE(row[columns.indexOf("p1")], QByteArray("0.03"));
    QCOMPARE(row[columns.indexOf("p4")], QByteArray("0.97"));
    QCOMPARE(row[columns.indexOf("p3")], row[columns.indexOf("p2")]);
    QVERIFY(!row[columns.indexOf("derivative_noise")].isEmpty());
  }
}

void TstCliSweep::badValuesExit2_data() {
  QTest::addColumn<QStringList>("args");
  QTest::addColumn<QString>("message");  // the stderr names this
  const QStringList common{"--log", kRun1, "--model", "parameterized", "--rule", "bayes-recursive"};
  const QStringList csv{"--csv", "/nonexistent-folder/never-written.csv"};
  auto sweep = [&](const QStringList& extra) {
    return QStringList{"sweep"} << common << extra << csv;
  };
  QTest::newRow("grid backwards") << sweep({"--grid", "p2=0.2:0.05:0.1", "--metric", "vsdns"})
                                  << "--grid";
  QTest::newRow("grid out of range") << sweep({"--grid", "p2=0.05,5", "--metric", "vsdns"})
                                     << "--grid 'p2=0.05,5': p2 = 5 is outside its declared range";
  QTest::newRow("grid unknown parameter") << sweep({"--grid", "nope=1,2", "--metric", "vsdns"})
                                          << "--grid 'nope=1,2': unknown parameter";
  QTest::newRow("grid not numbers")
      << sweep({"--grid", "p2=a:b:c", "--metric", "vsdns"}) << "--grid";
  QTest::newRow("grid zero step") << sweep({"--grid", "p2=0.05:0:0.2", "--metric", "vsdns"})
                                  << "--grid";
  QTest::newRow("tie expression") << sweep({"--grid", "p4=0.95,0.96", "--tie", "p1=log(p4)",
                                            "--metric", "vsdns"})
                                  << "--tie";
  QTest::newRow("tie out of range")
      << sweep({"--grid", "p4=0.95,0.96", "--tie", "p1=3-p4", "--metric", "vsdns"}) << "--tie";
  QTest::newRow("tie on a swept parameter")
      << sweep({"--grid", "p4=0.95,0.96", "--tie", "p4=1-p1", "--metric", "vsdns"}) << "--tie";
  QTest::newRow("shard beyond") << sweep({"--grid", "p2=0.05,0.1", "--shard", "3/3", "--metric",
                                          "vsdns"})
                                << "--shard";
  QTest::newRow("shard text") << sweep({"--grid", "p2=0.05,0.1", "--shard", "one", "--metric",
                                        "vsdns"})
                              << "--shard";
  QTest::newRow("reference metric, no reference")
      << sweep({"--grid", "p2=0.05,0.1", "--metric", "iop"}) << "--reference";
  QTest::newRow("two-run, no second log")
      << sweep({"--grid", "p2=0.05,0.1", "--metric", "two-run"}) << "--second-log";
  QTest::newRow("unknown metric") << sweep({"--grid", "p2=0.05,0.1", "--metric", "beauty"})
                                  << "--metric";
  QTest::newRow("range backwards") << (QStringList{"optimize"} << common << "--range"
                                                               << "p2=0.2:0.1"
                                                               << "--metric"
                                                               << "vsdns")
                                   << "--range";
  QTest::newRow("range out of range") << (QStringList{"optimize"} << common << "--range"
                                                                  << "p5=1:400"
                                                                  << "--metric"
                                                                  << "vsdns")
                                      << "--range 'p5=1:400': p5";
  QTest::newRow("unknown algorithm") << (QStringList{"optimize"} << common << "--range"
                                                                 << "p2=0.05:0.2"
                                                                 << "--metric"
                                                                 << "vsdns"
                                                                 << "--algorithm"
                                                                 << "luck")
                                     << "--algorithm";
}

void TstCliSweep::badValuesExit2() {
  QFETCH(QStringList, args);
  QFETCH(QString, message);
  const Run r = runCli(args);
  QVERIFY2(r.finished && r.status == QProcess::NormalExit && r.code == 2, describe(args, r));
  QVERIFY2(r.err.contains(message.toUtf8()), describe(args, r));
}

void TstCliSweep::mergeRefusesOtherSweeps() {
  const QString a = path("a0.csv");
  const QString b = path("b1.csv");
  QStringList one = baseSweep() << "--shard"
                                << "0/2"
                                << "--csv" << a;
  QStringList other = baseSweep() << "--shard"
                                  << "1/2"
                                  << "--csv" << b;
  other[other.indexOf("p5=6,15")] = "p5=7,15";
  for (const QStringList& args : {one, other}) {
    const Run r = runCli(args);
    QVERIFY2(r.finished && r.code == 0, describe(args, r));
  }
  const QStringList merge{"sweep-merge", a, b, "--csv", path("never.csv")};
  const Run r = runCli(merge);
  QVERIFY2(r.finished && r.code == 2 && r.err.contains("different sweep"), describe(merge, r));
  QVERIFY(!QFile::exists(path("never.csv")));
  const QStringList missing{"sweep-merge", a, "--csv", path("never.csv")};
  const Run m = runCli(missing);
  QVERIFY2(m.finished && m.code == 2 && m.err.contains("shard 1/2 is missing"),
           describe(missing, m));
  const QStringList twice{"sweep-merge", a, a, "--csv", path("never.csv")};
  const Run t = runCli(twice);
  QVERIFY2(t.finished && t.code == 2 && t.err.contains("given twice"), describe(twice, t));
}

void TstCliSweep::optimizeDeterministicForSeed() {
  const QStringList args = {
      "optimize",    "--log",         kRun1,      "--reference",     kWorld,
      "--model",     "parameterized", "--rule",   "bayes-recursive", "--range",
      "p2=0.05:0.2", "--range",       "p5=6:40",  "--tie",           "p1=1-p4",
      "--metric",    "iop",           "--metric", "vsdns",           "--budget",
      "12",          "--seed",        "7",        "--json"};
  QByteArray first;
  for (const char* threads : {"1", "2"}) {
    const QStringList withThreads = QStringList(args) << "--threads" << threads;
    const Run r = runCli(withThreads);
    QVERIFY2(r.finished && r.code == 0, describe(withThreads, r));
    const QJsonObject json = QJsonDocument::fromJson(r.out).object();
    QCOMPARE(json.value("evaluations").toInt(), 12);
    QCOMPARE(json.value("path").toArray().size(), 12);
    QVERIFY(json.value("best").toObject().contains("iop_mm"));
    if (first.isNull())
      first = r.out;
    else
      QCOMPARE(r.out, first);
  }
}

QTEST_GUILESS_MAIN(TstCliSweep)
#include "tst_cli_sweep.moc"
