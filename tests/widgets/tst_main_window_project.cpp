// SPDX-License-Identifier: GPL-3.0-or-later
// Projects in the window, offscreen: a saved project opened in another window restores the whole
// document and its map; a corrupt project, or one whose log is gone, leaves the open document as it
// was; and the autosave of a `sonargrid` process killed with SIGKILL is found and recovered with
// the settings it had.

#include <QDir>
#include <QFile>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QUndoStack>
#include <QtTest>

#include "autosave.h"
#include "document.h"
#include "main_window.h"
#include "project_file.h"
#include "remap_controller.h"

using namespace sg;
using namespace sg::app;

namespace {

const QString kRoom = QStringLiteral(SONARGRID_DATASETS "/room/room.sglog");

MapperSettings hpfAddition(double epsilon) {
  MapperSettings s;
  s.model = "hpf";
  s.rule = "addition";
  s.parameters = defaultParameters(s.model, s.rule);
  s.parameters.set("epsilon", epsilon);
  s.pose = PoseSource::Truth;
  return s;
}

}  // namespace

class TestMainWindowProject : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() {
    QStandardPaths::setTestModeEnabled(true);  // QSettings go to a scratch location
    QCoreApplication::setOrganizationName("SonarGridTest");
    QCoreApplication::setApplicationName("tst_main_window_project");
    QSettings().clear();
    QVERIFY(autosaveDir_.isValid());
    qputenv("SONARGRID_AUTOSAVE_DIR", autosaveDir_.path().toUtf8());
  }

  void savedProjectRestoresTheDocument() {
    QTemporaryDir dir;
    const QString file = dir.filePath(QStringLiteral("room.sgproj"));
    std::shared_ptr<const OccupancyMap> savedMap;
    ProjectState saved;
    {
      MainWindow window;
      window.show();
      QVERIFY(window.openLog(kRoom, true));
      window.setMapperSettings(hpfAddition(0.2));
      window.setCellSize(0.08);
      window.document()->setOverlays(ui::Overlays(ui::Overlay::Path) | ui::Overlay::Legend);
      window.document()->pinRow(PinnedRow{QStringLiteral("ε 0.2"), hpfAddition(0.2), 0.08});
      SweepPlan sweep;
      sweep.useSecondRun = false;
      window.document()->setSweep(sweep);
      QVERIFY(window.waitForMap(60000));
      QVERIFY(window.isWindowModified());
      QVERIFY(window.saveProjectAs(file, true));
      QVERIFY(!window.isWindowModified());
      QVERIFY(window.windowTitle().startsWith(QStringLiteral("room.sgproj[*]")));
      savedMap = window.gridView()->map();
      saved = window.document()->state();
      saved.view = window.gridView()->view();
    }
    MainWindow window;
    window.show();
    QVERIFY(window.openProject(file, true));
    QVERIFY(window.waitForMap(60000));
    const ProjectState& open = window.document()->state();
    QCOMPARE(open.logPath, QFileInfo(kRoom).absoluteFilePath());
    QVERIFY(sameSettings(open.settings, saved.settings));
    QCOMPARE(open.cellSize, 0.08);
    QCOMPARE(open.overlays, saved.overlays);
    QCOMPARE(window.gridView()->overlays(), saved.overlays);
    QVERIFY(open.pinnedRows == saved.pinnedRows);
    QVERIFY(open.sweep == saved.sweep);
    QVERIFY(open.reference.has_value());  // room.json, by path
    QCOMPARE(open.referencePath, saved.referencePath);
    QCOMPARE(window.gridView()->view(), *saved.view);
    QVERIFY(window.gridView()->map()->level == savedMap->level);
    QVERIFY(!window.isWindowModified());
    QCOMPARE(window.document()->projectPath(), file);
    QCOMPARE(window.document()->undoStack()->count(), 0);
  }

  void badProjectKeepsTheDocument_data() {
    QTest::addColumn<QByteArray>("text");
    QTest::newRow("truncated") << QByteArrayLiteral("{\"format\": \"sonargrid-project\", \"vers");
    QTest::newRow("log gone") << QByteArrayLiteral(
        "{\"format\": \"sonargrid-project\", \"version\": 1, \"log\": \"no-such.sglog\", "
        "\"mapping\": {\"model\": \"himm\", \"rule\": \"himm\", \"cell\": 0.2}}");
  }

  void badProjectKeepsTheDocument() {
    QFETCH(QByteArray, text);
    QSettings().clear();  // a new window starts from the defaults, not the last row's settings
    QTemporaryDir dir;
    const QString file = dir.filePath(QStringLiteral("bad.sgproj"));
    QFile f(file);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write(text);
    f.close();
    MainWindow window;
    window.show();
    QVERIFY(window.openLog(kRoom, true));
    window.setMapperSettings(hpfAddition(0.27));  // an edit: unsaved changes to keep
    QVERIFY(window.waitForMap(60000));
    const auto map = window.gridView()->map();
    const ProjectState before = window.document()->state();
    const int steps = window.document()->undoStack()->count();
    QVERIFY(!window.openProject(file, true));
    const ProjectState& after = window.document()->state();
    QCOMPARE(after.logPath, before.logPath);
    QVERIFY(sameSettings(after.settings, before.settings));
    QCOMPARE(after.cellSize, before.cellSize);
    QCOMPARE(window.document()->undoStack()->count(), steps);
    QVERIFY(window.document()->projectPath().isEmpty());
    QCOMPARE(window.gridView()->map(), map);
    QVERIFY(window.isWindowModified());
  }

  void killedSessionIsRecovered() {
    QTemporaryDir home;
    QVERIFY(home.isValid());
    QProcess app;
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    env.insert("QT_QPA_PLATFORM", "offscreen");
    env.insert("SONARGRID_AUTOSAVE_MS", "200");
    env.insert("SONARGRID_AUTOSAVE_DIR", autosaveDir_.path());
    // The child's own settings, not the user's.
    env.insert("XDG_CONFIG_HOME", home.filePath("config"));
    env.insert("XDG_DATA_HOME", home.filePath("data"));
    app.setProcessEnvironment(env);
    app.setProcessChannelMode(QProcess::ForwardedErrorChannel);
    // The settings differ from a new session's (HIMM, 5 cm): edits, so the document is modified.
    app.start(QStringLiteral(SONARGRID_APP),
              {kRoom, "--model", "hpf", "--rule", "addition", "--set", "epsilon=0.23", "--pose",
               "truth", "--cell", "0.1"});
    QVERIFY(app.waitForStarted(30000));
    const QString autosave =
        autosaveDir_.filePath(QStringLiteral("session-%1.sgproj").arg(app.processId()));
    // Written once the log has loaded (the file names it).
    QTRY_VERIFY_WITH_TIMEOUT(QFile::exists(autosave) && readProject(autosave).logPath ==
                                                            QFileInfo(kRoom).absoluteFilePath(),
                             60000);
    QVERIFY(Autosave::orphans().isEmpty());  // its session is alive: not offered
    app.kill();                              // SIGKILL: no clean exit, the file stays
    QVERIFY(app.waitForFinished(30000));
    QCOMPARE(app.exitStatus(), QProcess::CrashExit);
    QVERIFY(QFile::exists(autosave));
    QCOMPARE(Autosave::orphans(), QStringList{autosave});

    MainWindow window;
    window.show();
    QVERIFY(window.offerRecovery(QStringLiteral("yes")));
    QVERIFY(window.waitForLoad(60000));
    QVERIFY(window.waitForMap(60000));
    const Document& d = *window.document();
    QCOMPARE(d.logPath(), QFileInfo(kRoom).absoluteFilePath());
    QVERIFY(sameSettings(d.mapperSettings(), hpfAddition(0.23)));
    QCOMPARE(d.cellSize(), 0.1);
    QCOMPARE(window.gridView()->map()->spec.cellSize, 0.1);
    QVERIFY(d.isModified());  // recovered work is still unsaved
    QVERIFY(window.isWindowModified());
    QVERIFY(!QFile::exists(autosave));
    QVERIFY(Autosave::orphans().isEmpty());
  }

  void declinedRecoveryDeletesTheAutosave() {
    // A crashed session's leftovers, as the killed process leaves them: a project and a lock
    // naming a process that no longer runs.
    const QString file = autosaveDir_.filePath(QStringLiteral("session-999999.sgproj"));
    ProjectState s;
    s.settings = hpfAddition(0.3);
    writeProject(s, file, ProjectPaths::Absolute);
    QVERIFY(Autosave::orphans().contains(file));
    MainWindow window;
    QVERIFY(!window.offerRecovery(QStringLiteral("keep")));
    QVERIFY(QFile::exists(file));
    QVERIFY(!window.offerRecovery(QStringLiteral("no")));
    QVERIFY(!QFile::exists(file));
  }

 private:
  QTemporaryDir autosaveDir_;
};

QTEST_MAIN(TestMainWindowProject)
#include "tst_main_window_project.moc"
