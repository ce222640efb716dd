// SPDX-License-Identifier: GPL-3.0-or-later
// --threads and SONARGRID_THREADS (docs/cli.md, "Threads"): a map is the same bytes whatever the
// thread count. Every model × rule pair `sonargrid-cli models` lists is mapped from the bundled
// room log (11 888 readings: above the threshold for threads) with --threads 1, --threads 2 and
// SONARGRID_THREADS=3; the --json output (less the timing key elapsed_ms) and the PNG must be
// byte-identical. 2.5 cm cells make a grid of 130 000 cells, so the snapshot is split too (in 2
// and 3 parts). Bad values are exit 2 with a message naming the flag or the variable.

#include <QByteArray>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QProcessEnvironment>
#include <QRegularExpression>
#include <QTemporaryDir>
#include <QtTest>

#include "cli_run.h"

namespace {

using cli_test::kCli;
const QString kRoomLog = QStringLiteral(SONARGRID_DATASETS "/room/room.sglog");

using cli_test::describe;
using cli_test::Run;

// Runs the CLI with SONARGRID_THREADS set to `threadsVariable` (unset when null, whatever the
// environment of the test says); never waits more than two minutes.
Run runCli(const QStringList& args, const QByteArray& threadsVariable = {}) {
  QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
  env.remove("SONARGRID_THREADS");
  if (!threadsVariable.isNull())
    env.insert("SONARGRID_THREADS", QString::fromUtf8(threadsVariable));
  return cli_test::runProgram(cli_test::kCli, args, {}, env);
}

QByteArray readFile(const QString& path) {
  QFile f(path);
  return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}

// The output with the timing key's value blanked: the one part that may differ run to run.
QByteArray withoutTiming(QByteArray json) {
  static const QRegularExpression elapsed(QStringLiteral("\"elapsed_ms\":[-0-9.eE+]+"));
  return QString::fromUtf8(json).replace(elapsed, QStringLiteral("\"elapsed_ms\":_")).toUtf8();
}

}  // namespace

class TstCliThreads : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase();
  void sameMapAnyThreadCount_data();
  void sameMapAnyThreadCount();
  void sameResultsOtherCommands_data();
  void sameResultsOtherCommands();
  void badValues_data();
  void badValues();

 private:
  QTemporaryDir tmp_;
  QList<QPair<QString, QString>> pairs_;
};

void TstCliThreads::initTestCase() {
  QVERIFY2(QFile::exists(kCli), qPrintable(kCli));
  QVERIFY(tmp_.isValid());
  const Run r = runCli({"models", "--json"});
  QVERIFY2(r.finished && r.code == 0, describe({"models", "--json"}, r));
  const QJsonArray compatible =
      QJsonDocument::fromJson(r.out).object().value("compatible").toArray();
  for (const QJsonValue& v : compatible)
    pairs_.append({v.toArray()[0].toString(), v.toArray()[1].toString()});
  QVERIFY(pairs_.size() >= 25);  // every cone model with the six probability rules, and HIMM's
}

void TstCliThreads::sameMapAnyThreadCount_data() {
  QTest::addColumn<QString>("model");
  QTest::addColumn<QString>("rule");
  for (const auto& [model, rule] : pairs_)
    QTest::addRow("%s × %s", qPrintable(model), qPrintable(rule)) << model << rule;
}

void TstCliThreads::sameMapAnyThreadCount() {
  QFETCH(QString, model);
  QFETCH(QString, rule);
  struct Way {
    const char* name;
    QStringList flags;
    QByteArray variable;  // null: SONARGRID_THREADS unset
  };
  const Way ways[] = {{"threads1", {"--threads", "1"}, {}},
                      {"threads2", {"--threads", "2"}, {}},
                      {"variable3", {}, "3"}};
  QByteArray firstJson, firstPng;
  for (const Way& w : ways) {
    const QString png = tmp_.filePath(model + "-" + rule + "-" + w.name + ".png");
    QStringList args = {"map", "--log",  kRoomLog, "--model", model,   "--rule",
                        rule,  "--cell", "0.025",  "--json",  "--png", png};
    args << w.flags;
    const Run r = runCli(args, w.variable);
    QVERIFY2(r.finished && r.status == QProcess::NormalExit && r.code == 0, describe(args, r));
    const QByteArray json = withoutTiming(r.out);
    const QByteArray image = readFile(png);
    QVERIFY2(!image.isEmpty(), qPrintable(png));
    if (firstJson.isNull()) {
      firstJson = json;
      firstPng = image;
      // The map is not empty (an empty map would compare equal however it was made).
      QVERIFY2(QJsonDocument::fromJson(r.out).object().value("cells_filled").toInt() > 100, r.out);
      continue;
    }
    QCOMPARE(json, firstJson);
    QVERIFY2(image == firstPng, qPrintable(png + " differs from the one-thread PNG"));
  }
}

void TstCliThreads::sameResultsOtherCommands_data() {
  // goodness feeds VSDNS every footprint: the mapper's ordered pipeline, not its bands; score
  // maps as map does. Their whole --json output must be the same bytes.
  QTest::addColumn<QStringList>("args");
  const QString reference = QStringLiteral(SONARGRID_DATASETS "/room/room.json");
  QTest::newRow("goodness hpf × bayes")
      << QStringList{"goodness", "--log", kRoomLog, "--model", "hpf", "--rule", "bayes", "--json"};
  QTest::newRow("goodness himm × himm")
      << QStringList{"goodness", "--log", kRoomLog, "--model", "himm", "--rule", "himm", "--json"};
  QTest::newRow("score murphy × addition")
      << QStringList{"score",   "--reference", reference, "--log",    kRoomLog,
                     "--model", "murphy",      "--rule",  "addition", "--json"};
}

void TstCliThreads::sameResultsOtherCommands() {
  QFETCH(QStringList, args);
  QByteArray first;
  for (const char* threads : {"1", "2", "3"}) {
    const QStringList withThreads = args + QStringList{"--threads", threads};
    const Run r = runCli(withThreads);
    QVERIFY2(r.finished && r.code == 0, describe(withThreads, r));
    if (first.isNull())
      first = r.out;
    else
      QCOMPARE(r.out, first);
  }
}

void TstCliThreads::badValues_data() {
  QTest::addColumn<QStringList>("flags");
  QTest::addColumn<QByteArray>("variable");  // null: unset
  QTest::addColumn<QString>("named");        // what the message must name
  QTest::newRow("--threads -1") << QStringList{"--threads", "-1"} << QByteArray() << "--threads";
  QTest::newRow("--threads 2.5") << QStringList{"--threads", "2.5"} << QByteArray() << "--threads";
  QTest::newRow("--threads many") << QStringList{"--threads", "many"} << QByteArray()
                                  << "--threads";
  QTest::newRow("--threads 1025") << QStringList{"--threads", "1025"} << QByteArray()
                                  << "--threads";
  QTest::newRow("--threads twice")
      << QStringList{"--threads", "1", "--threads", "2"} << QByteArray() << "--threads";
  QTest::newRow("SONARGRID_THREADS=0") << QStringList{} << QByteArray("0") << "SONARGRID_THREADS";
  QTest::newRow("SONARGRID_THREADS=-2") << QStringList{} << QByteArray("-2") << "SONARGRID_THREADS";
  QTest::newRow("SONARGRID_THREADS=four")
      << QStringList{} << QByteArray("four") << "SONARGRID_THREADS";
  // --threads does not excuse a bad variable: the next command without it would use it.
  QTest::newRow("SONARGRID_THREADS=x with --threads 2")
      << QStringList{"--threads", "2"} << QByteArray("x") << "SONARGRID_THREADS";
}

void TstCliThreads::badValues() {
  QFETCH(QStringList, flags);
  QFETCH(QByteArray, variable);
  QFETCH(QString, named);
  for (const char* command : {"map", "goodness"}) {
    QStringList args = {command, "--log", kRoomLog, "--model", "hpf", "--rule", "bayes"};
    args << flags;
    const Run r = runCli(args, variable);
    QVERIFY2(r.finished && r.code == 2, describe(args, r));
    QVERIFY2(r.out.isEmpty(), describe(args, r));
    QVERIFY2(QString::fromUtf8(r.err).contains(named), describe(args, r));
  }
}

QTEST_GUILESS_MAIN(TstCliThreads)
#include "tst_cli_threads.moc"
