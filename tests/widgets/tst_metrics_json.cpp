// SPDX-License-Identifier: GPL-3.0-or-later
// `sonargrid LOG --reference REF ... --metrics-json FILE` (and from a project) writes the metrics
// panel's numbers with the keys, order and values of `sonargrid-cli score --json` for the same
// inputs; without a reference, those of `sonargrid-cli goodness --json`. Both programs run as
// separate processes, the app offscreen.

#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QRegularExpression>
#include <QTemporaryDir>
#include <QtTest>

namespace {

const QString kRoomLog = QStringLiteral(SONARGRID_DATASETS "/room/room.sglog");
const QString kRoomReference = QStringLiteral(SONARGRID_DATASETS "/room/room.json");

struct Run {
  int exitCode = -1;
  QByteArray out, err;
};

Run run(const QString& program, const QStringList& args, const QString& home) {
  QProcess p;
  QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
  env.insert("QT_QPA_PLATFORM", "offscreen");
  env.insert("XDG_CONFIG_HOME", home);  // no remembered settings of another session
  env.insert("HOME", home);
  p.setProcessEnvironment(env);
  p.start(program, args);
  Run r;
  if (!p.waitForFinished(300000)) {
    p.kill();
    p.waitForFinished();
    r.err = "timed out";
    return r;
  }
  r.exitCode = p.exitCode();
  r.out = p.readAllStandardOutput();
  r.err = p.readAllStandardError();
  return r;
}

QJsonObject parse(const QByteArray& bytes) {
  QJsonParseError error;
  const QJsonDocument doc = QJsonDocument::fromJson(bytes, &error);
  if (error.error != QJsonParseError::NoError) qWarning() << error.errorString() << bytes;
  return doc.object();
}

QStringList keysInOrder(const QByteArray& json) {
  // QJsonObject sorts its keys; the order is read from the text.
  QStringList keys;
  const QRegularExpression key(QStringLiteral("\"([a-z_0-9]+)\":"));
  for (auto it = key.globalMatch(QString::fromUtf8(json)); it.hasNext();)
    keys << it.next().captured(1);
  return keys;
}

}  // namespace

class TestMetricsJson : public QObject {
  Q_OBJECT

 private slots:
  void sameAsTheCli_data() {
    QTest::addColumn<QStringList>("mapFlags");
    QTest::addColumn<bool>("reference");
    QTest::newRow("himm x himm, 10 cm")
        << QStringList{"--model", "himm", "--rule", "himm", "--cell", "0.1"} << true;
    QTest::newRow("hpf x addition, 5 cm, a --set")
        << QStringList{"--model", "hpf",          "--rule", "addition",
                       "--set",   "epsilon=0.05", "--cell", "0.05"}
        << true;
    QTest::newRow("no reference: goodness")
        << QStringList{"--model", "himm", "--rule", "himm", "--cell", "0.1"} << false;
  }

  void sameAsTheCli() {
    QFETCH(QStringList, mapFlags);
    QFETCH(bool, reference);
    QTemporaryDir dir;
    const QString json = dir.filePath("metrics.json");
    const QString shot = dir.filePath("window.png");
    // Without a reference, a copy of the log away from room.json (which the window would take
    // along as the log's reference).
    const QString log = reference ? kRoomLog : dir.filePath("alone.sglog");
    if (!reference) QVERIFY(QFile::copy(kRoomLog, log));
    QStringList appArgs{log};
    if (reference) appArgs << "--reference" << kRoomReference;
    appArgs << mapFlags << "--screenshot" << shot << "--metrics-json" << json;
    const Run app = run(SONARGRID_APP, appArgs, dir.path());
    QVERIFY2(app.exitCode == 0, app.err.constData());
    QVERIFY(QFileInfo(shot).size() > 0);
    QFile file(json);
    QVERIFY(file.open(QIODevice::ReadOnly));
    const QByteArray appJson = file.readAll();

    QStringList cliArgs{reference ? "score" : "goodness", "--log", log, "--json"};
    if (reference) cliArgs << "--reference" << kRoomReference;
    cliArgs << mapFlags;
    const Run cli = run(SONARGRID_CLI, cliArgs, dir.path());
    QVERIFY2(cli.exitCode == 0, cli.err.constData());

    QCOMPARE(keysInOrder(appJson), keysInOrder(cli.out));
    const QJsonObject a = parse(appJson), b = parse(cli.out);
    QVERIFY(!a.isEmpty());
    QCOMPARE(a.keys(), b.keys());
    for (const QString& key : b.keys()) {
      // Shortest round-trip decimals on both sides: equal doubles print equal.
      QVERIFY2(a[key] == b[key], qPrintable(QStringLiteral("%1: app %2, cli %3")
                                                .arg(key)
                                                .arg(a[key].toDouble(), 0, 'g', 17)
                                                .arg(b[key].toDouble(), 0, 'g', 17)));
    }
    QVERIFY(a.contains(reference ? "iop_mm" : "vsdns"));
  }

  void needsSomethingToMap() {
    QTemporaryDir dir;
    const Run app = run(SONARGRID_APP, {"--metrics-json", dir.filePath("m.json")}, dir.path());
    QCOMPARE(app.exitCode, 2);
    QVERIFY2(app.err.contains("--metrics-json needs a LOG or a PROJECT"), app.err.constData());
  }
};

QTEST_GUILESS_MAIN(TestMetricsJson)
#include "tst_metrics_json.moc"
