// SPDX-License-Identifier: GPL-3.0-or-later
// The desktop app's text-only command line: --help and --version print and exit 0 without any
// display (no DISPLAY, no WAYLAND_DISPLAY, no QT_QPA_PLATFORM), as a terminal user or a packager's
// check would run them.
#include <QProcess>
#include <QProcessEnvironment>
#include <QTest>

class TestAppCommandLine : public QObject {
  Q_OBJECT

 private slots:
  void textOnly_data() {
    QTest::addColumn<QStringList>("args");
    QTest::addColumn<QString>("expected");
    // QCommandLineParser's help starts "Usage: <program>" and lists every option; the version
    // line is "<application name> <version>" (SONARGRID_VERSION is the project's version).
    QTest::newRow("--help") << QStringList{"--help"} << QStringLiteral("--screenshot <FILE>");
    QTest::newRow("-h") << QStringList{"-h"} << QStringLiteral("Usage: ");
    QTest::newRow("--help after a log")
        << QStringList{"some.sglog", "--help"} << QStringLiteral("--reference <REF>");
    QTest::newRow("--version") << QStringList{"--version"}
                               << QStringLiteral("sonargrid " SONARGRID_VERSION);
    QTest::newRow("-v") << QStringList{"-v"} << QStringLiteral("sonargrid " SONARGRID_VERSION);
  }
  void textOnly() {
    QFETCH(QStringList, args);
    QFETCH(QString, expected);
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    for (const char* name : {"DISPLAY", "WAYLAND_DISPLAY", "QT_QPA_PLATFORM"})
      env.remove(QString::fromLatin1(name));
    QProcess app;
    app.setProcessEnvironment(env);
    app.start(QStringLiteral(SONARGRID_APP), args);
    QVERIFY(app.waitForFinished(30000));
    const QString out = QString::fromUtf8(app.readAllStandardOutput());
    const QString err = QString::fromUtf8(app.readAllStandardError());
    QCOMPARE(app.exitStatus(), QProcess::NormalExit);  // not SIGABRT
    QVERIFY2(app.exitCode() == 0, qPrintable(err));
    QVERIFY2(out.contains(expected), qPrintable(out));
  }
};

QTEST_GUILESS_MAIN(TestAppCommandLine)
#include "tst_app_command_line.moc"
