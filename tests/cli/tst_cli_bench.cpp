// SPDX-License-Identifier: GPL-3.0-or-later
// `sonargrid-cli bench` (docs/cli.md, "bench"): the --json contract — exactly the keys of issue 15,
// one timing per allowed model/rule pair for both workloads, the thread count asked for, the
// office log's reading count as `map` reports it, and the bytes per cell each rule's layout gives.
// Timings are checked only for being positive and finite: no unit test measures speed.

#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QProcessEnvironment>
#include <QSet>
#include <QtTest>
#include <cmath>

namespace {

const QString kCli = QStringLiteral(SONARGRID_CLI);
const QString kOfficeLog = QStringLiteral(SONARGRID_DATASETS "/office/office.sglog");

struct Run {
  bool finished = false;
  int code = -1;
  QByteArray out;
  QByteArray err;
};

Run runCli(const QStringList& args, int timeoutMs = 120000) {
  QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
  env.remove("SONARGRID_THREADS");
  QProcess p;
  p.setProcessEnvironment(env);
  p.start(kCli, args);
  Run r;
  if (!p.waitForStarted(10000)) return r;
  r.finished = p.waitForFinished(timeoutMs);
  if (!r.finished) {
    p.kill();
    p.waitForFinished(5000);
    return r;
  }
  r.code = p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1;
  r.out = p.readAllStandardOutput();
  r.err = p.readAllStandardError();
  return r;
}

QByteArray describe(const QStringList& args, const Run& r) {
  return "sonargrid-cli " + args.join(' ').toUtf8() + "\n  exit " + QByteArray::number(r.code) +
         "\n  stdout: " + r.out.left(400) + "\n  stderr: " + r.err.left(400);
}

bool positiveFinite(const QJsonValue& v) {
  return v.isDouble() && std::isfinite(v.toDouble()) && v.toDouble() > 0.0;
}

}  // namespace

class TstCliBench : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase();
  void quickJson();
  void bytesPerCell_data();
  void bytesPerCell();
  void badFlags_data();
  void badFlags();

 private:
  QSet<QString> pairs_;  // "model/rule" of every allowed pair
  QJsonObject bench_;    // bench --quick --json --threads 2
};

void TstCliBench::initTestCase() {
  QVERIFY2(QFile::exists(kCli), qPrintable(kCli));
  const Run models = runCli({"models", "--json"});
  QVERIFY2(models.finished && models.code == 0, describe({"models", "--json"}, models));
  for (const QJsonValue& v :
       QJsonDocument::fromJson(models.out).object().value("compatible").toArray())
    pairs_.insert(v.toArray()[0].toString() + "/" + v.toArray()[1].toString());
  QVERIFY(pairs_.size() >= 25);
  // --quick finishes within a minute on an idle 2-core machine; a loaded one gets fifteen.
  const QStringList args = {"bench", "--quick", "--json", "--threads", "2"};
  const Run r = runCli(args, 900000);
  QVERIFY2(r.finished && r.code == 0, describe(args, r));
  QJsonParseError error;
  const QJsonDocument doc = QJsonDocument::fromJson(r.out, &error);
  QVERIFY2(error.error == QJsonParseError::NoError && doc.isObject(), r.out.left(400));
  bench_ = doc.object();
}

void TstCliBench::quickJson() {
  // Exactly the keys of the contract (issue 15; the fast engine's three, docs/cli.md).
  const QStringList keys = {"cores",
                            "office_readings",
                            "office_remap_ms",
                            "workload_remap_ms",
                            "office_remap_ms_fast",
                            "workload_remap_ms_fast",
                            "fast_deviation_office",
                            "load_1m_readings_s",
                            "bytes_per_cell"};
  QStringList got = bench_.keys();
  QStringList want = keys;
  got.sort();
  want.sort();
  QCOMPARE(got, want);
  // --threads 2 is what the policy uses.
  QCOMPARE(bench_.value("cores").toInt(), 2);
  // The office log's readings, as `map` counts them.
  const QStringList mapArgs = {"map",  "--log",  kOfficeLog, "--model",
                               "himm", "--rule", "himm",     "--json"};
  const Run map = runCli(mapArgs);
  QVERIFY2(map.finished && map.code == 0, describe(mapArgs, map));
  const qint64 readings = QJsonDocument::fromJson(map.out).object().value("readings").toInteger(-1);
  QVERIFY(readings > 100000);  // the bundled office log holds some 112 000 readings
  QCOMPARE(bench_.value("office_readings").toInteger(), readings);
  // One positive, finite time per allowed pair, no other key.
  for (const char* workload : {"office_remap_ms", "workload_remap_ms"}) {
    const QJsonObject times = bench_.value(workload).toObject();
    const QStringList timed = times.keys();
    QCOMPARE(QSet<QString>(timed.begin(), timed.end()), pairs_);
    for (auto it = times.begin(); it != times.end(); ++it)
      QVERIFY2(positiveFinite(it.value()), qPrintable(QString(workload) + " " + it.key()));
  }
  QVERIFY(positiveFinite(bench_.value("load_1m_readings_s")));
  // The fast engine: timed, and its deviation from the exact map given, for the pairs where it
  // has cells of its own (a cone model with the Bayes family: 4 × 2), within the accuracy
  // contract (docs/models.md: at most 0.1 % of observed cells, by at most one level).
  QSet<QString> fastPairs;
  for (const char* model : {"hpf", "konolige", "murphy", "parameterized"})
    for (const char* rule : {"bayes", "bayes-recursive"})
      fastPairs.insert(QString(model) + "/" + rule);
  for (const char* key : {"office_remap_ms_fast", "workload_remap_ms_fast"}) {
    const QJsonObject times = bench_.value(key).toObject();
    const QStringList timed = times.keys();
    QCOMPARE(QSet<QString>(timed.begin(), timed.end()), fastPairs);
    for (auto it = times.begin(); it != times.end(); ++it)
      QVERIFY2(positiveFinite(it.value()), qPrintable(QString(key) + " " + it.key()));
  }
  const QJsonObject deviation = bench_.value("fast_deviation_office").toObject();
  const QStringList measured = deviation.keys();
  QCOMPARE(QSet<QString>(measured.begin(), measured.end()), fastPairs);
  for (auto it = deviation.begin(); it != deviation.end(); ++it) {
    const QJsonObject d = it.value().toObject();
    QVERIFY2(d.value("levels_differ_pct").toDouble(-1) >= 0.0 &&
                 d.value("levels_differ_pct").toDouble(-1) <= 0.1,
             qPrintable(it.key()));
    QVERIFY2(d.value("max_level_step").toInt(-1) >= 0 && d.value("max_level_step").toInt(-1) <= 1,
             qPrintable(it.key()));
  }
}

void TstCliBench::bytesPerCell_data() {
  QTest::addColumn<QString>("rule");
  QTest::addColumn<int>("bytes");
  // The rule's planes (rule_classes.h), 1 byte of observed/written mark (grid.h), what a snapshot
  // keeps of its own (occupancy_map.h: level and observed, a byte each; its other layers read the
  // planes it shares with the grid) and the OpenGL view's copy of the uploaded levels, 1 byte:
  // 1 + 2 + 1 = 4 besides the planes.
  QTest::newRow("addition") << "addition" << 4 + 4 + 4;  // Emp and Occ, floats
  QTest::newRow("bayes") << "bayes" << 8 + 4;            // p, a double
  QTest::newRow("bayes-recursive") << "bayes-recursive" << 8 + 4;
  QTest::newRow("log") << "log" << 8 + 4;          // Emp · Occ
  QTest::newRow("logodds") << "logodds" << 8 + 4;  // the odds
  QTest::newRow("himm") << "himm" << 1 + 4;        // CV, a byte
  // The two smaller of the three masses, floats (DempsterShaferCell).
  QTest::newRow("dempster-shafer") << "dempster-shafer" << 8 + 4;
  // The fast engine's Bayes cells: four bytes (rule_classes.h, BayesFloatCell).
  QTest::newRow("bayes/fast") << "bayes/fast" << 4 + 4;
  QTest::newRow("bayes-recursive/fast") << "bayes-recursive/fast" << 4 + 4;
}

void TstCliBench::bytesPerCell() {
  QFETCH(QString, rule);
  QFETCH(int, bytes);
  const QJsonObject perRule = bench_.value("bytes_per_cell").toObject();
  QCOMPARE(perRule.size(), 9);
  QCOMPARE(perRule.value(rule).toInt(-1), bytes);
}

void TstCliBench::badFlags_data() {
  QTest::addColumn<QStringList>("args");
  QTest::addColumn<QString>("named");
  QTest::newRow("negative threads") << QStringList{"bench", "--threads", "-1"} << "--threads";
  QTest::newRow("unknown flag") << QStringList{"bench", "--fast"} << "--fast";
}

void TstCliBench::badFlags() {
  QFETCH(QStringList, args);
  QFETCH(QString, named);
  const Run r = runCli(args);
  QVERIFY2(r.finished && r.code == 2, describe(args, r));
  QVERIFY2(r.err.contains(named.toUtf8()), r.err);
}

QTEST_GUILESS_MAIN(TstCliBench)
#include "tst_cli_bench.moc"
