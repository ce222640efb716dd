// SPDX-License-Identifier: GPL-3.0-or-later
// Projects in the window, offscreen: a saved project opened in another window restores the whole
// document and its map; a corrupt project, or one whose log is gone, leaves the open document as it
// was; and the autosave of a `sonargrid` process killed with SIGKILL is found and recovered with
// the settings it had.

#include <QComboBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QFile>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QUndoStack>
#include <QtTest>
#include <cmath>
#include <limits>

#include "autosave.h"
#include "beam_model_view.h"
#include "cell_inspector.h"
#include "comparison_table.h"
#include "document.h"
#include "main_window.h"
#include "metrics_panel.h"
#include "parameter_panel.h"
#include "project_file.h"
#include "remap_controller.h"
#include "robot/robot_dock.h"
#include "sonargrid/io/csv_log.h"
#include "sonargrid/io/log_reader.h"
#include "sonargrid/reference/read_reference.h"
#include "sonargrid/reference/reference_json.h"
#include "sweep_view.h"
#include "timeline.h"

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

constexpr int kWaitMs = 120000;      // a bound against hangs, never a measured time
constexpr int kAppAutosaveMs = 200;  // the app processes' autosave interval (prepareApp)

// The first parameter of the model that its paper's rule uses (HIMM's rule ignores p_hit).
const ParameterSpec& firstUsed(const std::string& model) {
  const ModelInfo& info = sensorModelInfo(model);
  for (const ParameterSpec& p : info.parameters)
    if (unusedParameterReason(model, info.preferredRule, p.name).empty()) return p;
  return info.parameters.front();
}

// The model with its paper's rule and that parameter a quarter of the way from its default to
// its maximum, to two decimals (a whole number where it takes one): a setting no new session has.
MapperSettings offDefault(const std::string& model) {
  MapperSettings s;
  s.model = model;
  s.rule = sensorModelInfo(model).preferredRule;
  s.parameters = defaultParameters(s.model, s.rule);
  const ParameterSpec& p = firstUsed(model);
  double v = std::round((p.defaultValue + (p.max - p.defaultValue) / 4.0) * 100.0) / 100.0;
  if (p.integer) v = std::max(p.defaultValue + 1.0, std::round(v));
  s.parameters.set(p.name, std::min(v, p.max));
  return s;
}

// What a project holds, compared field by field (the view only where both have one).
bool sameDocument(const ProjectState& a, const ProjectState& b) {
  const auto reference = [](const ProjectState& s) {
    return s.reference ? referenceJsonText(*s.reference) : std::string();
  };
  return a.logPath == b.logPath && a.secondLogPath == b.secondLogPath &&
         reference(a) == reference(b) && a.referencePath == b.referencePath &&
         a.referenceModified == b.referenceModified && sameSettings(a.settings, b.settings) &&
         a.cellSize == b.cellSize && a.overlays == b.overlays && a.pinnedRows == b.pinnedRows &&
         a.sweep == b.sweep && (!a.view || !b.view || *a.view == *b.view);
}

// Each dock of the window used once, through its widgets where a user would.
void useEveryDock(MainWindow& window, const std::string& model) {
  Document* document = window.document();
  // Parameters: the model and its paper's rule, as the Mapping menu sets them, then the first
  // parameter the rule uses typed into the panel's spin box.
  MapperSettings chosen = offDefault(model);
  const ParameterSpec& first = firstUsed(model);
  const double typed = chosen.parameters.get(first.name);
  chosen.parameters.set(first.name, first.defaultValue);
  window.setMapperSettings(chosen, /*ruleNamed=*/true);
  QDoubleSpinBox* spin = window.parameterPanel()->spinBoxFor(QString::fromStdString(first.name));
  QVERIFY(spin);
  spin->setValue(typed);  // as shown: to the box's decimals
  QVERIFY(spin->value() != first.defaultValue);
  QCOMPARE(document->mapperSettings().parameters.get(first.name), spin->value());
  // Map: 10 cm cells.
  auto* cell = window.findChild<QDoubleSpinBox*>(QStringLiteral("cellSize"));
  QVERIFY(cell);
  cell->setValue(0.1);
  QCOMPARE(document->cellSize(), 0.1);
  QVERIFY(window.waitForMap(kWaitMs));
  // Timeline: a step back and to the end again.
  window.timeline()->stepBackward();
  QVERIFY(window.waitForMap(kWaitMs));
  window.timeline()->setTime(std::numeric_limits<double>::max());
  QVERIFY(window.waitForMap(kWaitMs));
  // Beam Model: another reading, and another model to compare with.
  window.chooseBeamSonar(3);
  auto* compare = window.beamModelView()->findChild<QComboBox*>(QStringLiteral("compareChooser"));
  QVERIFY(compare);
  compare->setCurrentIndex(compare->count() - 1);
  // Metrics: the panel's numbers of this map.
  auto* metrics = window.findChild<ui::MetricsPanel*>();
  QVERIFY(metrics);
  QVERIFY(metrics->waitForResult(kWaitMs));
  // Comparison: Pin Current.
  auto* table = window.findChild<ui::ComparisonTable*>();
  QVERIFY(table);
  emit table->pinRequested();
  QVERIFY(table->waitForResult(kWaitMs));
  // Sweep: the first parameter at two values by IOP, then Apply Best and Pin Best (the issue's
  // steps that once wrote a project that would not open).
  auto* sweep = window.findChild<ui::SweepView*>();
  QVERIFY(sweep);
  const double lo = first.defaultValue, hi = spin->value();
  sweep->setChoice({{QStringLiteral("%1=%2,%3")
                         .arg(QString::fromStdString(first.name))
                         .arg(lo, 0, 'g', 17)
                         .arg(hi, 0, 'g', 17)
                         .toStdString()},
                    {},
                    {"iop"}});
  QVERIFY(sweep->run());
  QVERIFY(sweep->waitForSweep(kWaitMs));
  QVERIFY2(sweep->applyBest(), qPrintable(sweep->statusText()));
  QVERIFY(sweep->pinBest());
  QVERIFY(window.waitForMap(kWaitMs));
  // Reference editor: one corner moved 10 cm, an edit the project holds inline.
  ReferenceMap edited = *document->reference();
  edited.objects.front().corners.front().x() += 0.1 / edited.metresPerUnit();
  document->setReference(edited, document->referencePath());
  QVERIFY(document->referenceModified());
  // Cell inspector: the trace of the centre cell.
  ui::CellInspector* inspector = window.cellInspector();
  const GridSpec& spec = window.gridView()->map()->spec;
  QSignalSpy traced(inspector, &ui::CellInspector::traced);
  QVERIFY(inspector->inspect(CellIndex(spec.width / 2, spec.height / 2)));
  QVERIFY(traced.wait(kWaitMs));
  // Robot: another world chosen, not started; it is not the document's.
  auto* robot = window.findChild<RobotDock*>();
  QVERIFY(robot);
  robot->setWorld(QStringLiteral(SONARGRID_DATASETS "/raschke-single/world.json"));
  // View: the robot's path switched off.
  document->setOverlays(document->overlays() & ~ui::Overlays(ui::Overlay::Path));
}

}  // namespace

class TestMainWindowProject : public QObject {
  Q_OBJECT

 private slots:
  // No crashed session's file outlives the function that made it: a failed row does not fail
  // the next one's orphans() checks.
  void cleanup() {
    for (const QString& f : QDir(autosaveDir_.path()).entryList({QStringLiteral("session-*")}))
      QFile::remove(autosaveDir_.filePath(f));
  }

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

  // A CSV log needs its columns and a ring to be read at all (docs/formats.md, "CSV and text
  // columns"): the project keeps them, and reopens the log with them. Before, it reopened the file
  // with no options and refused it for want of a column mapping.
  void aCsvLogsProjectReopensWithItsColumns() {
    const QString csv = QStringLiteral(SONARGRID_TEST_DATA "/logs/mm_ddeg.csv");
    LogOptions options;
    options.csv = parseCsvLayout(
        "header=1,time=1,x=2,y=3,theta=4,sonars=5-8,length=mm,angle=ddeg,noecho=5110");
    options.ring =
        readSonarGeometry(QStringLiteral(SONARGRID_TEST_DATA "/logs/ring4_mm.geom").toStdString());
    const Dataset expected = readLog(csv.toStdString(), options);
    QTemporaryDir dir;
    const QString file = dir.filePath(QStringLiteral("csv.sgproj"));
    {
      MainWindow window;
      window.loadLog(csv, options, true);
      QVERIFY(window.waitForLoad(kWaitMs));
      QVERIFY(window.document()->logReading() == readingOf(options));
      QVERIFY(window.saveProjectAs(file, true));
    }
    MainWindow window;
    QVERIFY(window.openProject(file, true));
    QVERIFY(window.waitForMap(kWaitMs));
    QCOMPARE(window.logPath(), csv);
    QVERIFY(*window.dataset() == expected);
    QVERIFY(window.document()->logReading() == readingOf(options));
    QVERIFY(!window.isWindowModified());
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
    prepareApp(app, home);
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

  // Issue 50, item 4: crash recovery end to end. The app opens a project (the room log, its
  // reference, HPF at ε = 0.2); its reference (a corner of the box moved 10 cm), its settings
  // (ε = 0.23, true pose) and its pinned rows (two) are edited in the running process
  // (SONARGRID_TEST_EDITS, docs/user-guide.md "Projects"); once the autosave holds them and a
  // further interval has passed, the process is killed with SIGKILL. The next start is offered
  // the session and recovers every edit, still unsaved, with the project it had open.
  void killedSessionWithEditsIsRecovered() {
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    const QString roomJson = QStringLiteral(SONARGRID_DATASETS "/room/room.json");
    ProjectState opened;
    opened.logPath = QFileInfo(kRoom).absoluteFilePath();
    opened.reference = readReference(roomJson.toStdString());
    opened.referencePath = QFileInfo(roomJson).absoluteFilePath();
    opened.settings = hpfAddition(0.2);
    const QString project = dir.filePath(QStringLiteral("room.sgproj"));
    writeProject(opened, project);

    ProjectState edited = opened;
    edited.reference->objects[1].corners[0] +=
        Eigen::Vector2d(0.1 / edited.reference->metresPerUnit(), 0.0);
    edited.referenceModified = true;
    edited.settings = hpfAddition(0.23);
    edited.settings.pose = PoseSource::Truth;
    edited.pinnedRows = {PinnedRow{QStringLiteral("ε 0.2"), hpfAddition(0.2), 0.05},
                         PinnedRow{QStringLiteral("ε 0.3"), hpfAddition(0.3), 0.05}};
    const QString edits = dir.filePath(QStringLiteral("edits.sgproj"));
    writeProject(edited, edits);

    QTemporaryDir home;
    QVERIFY(home.isValid());
    QProcess app;
    prepareApp(app, home);
    QProcessEnvironment env = app.processEnvironment();
    env.insert("SONARGRID_TEST_EDITS", edits);
    app.setProcessEnvironment(env);
    app.start(QStringLiteral(SONARGRID_APP), {project});
    QVERIFY(app.waitForStarted(30000));
    const QString autosave =
        autosaveDir_.filePath(QStringLiteral("session-%1.sgproj").arg(app.processId()));
    const QString wantReference = QString::fromStdString(referenceJsonText(*edited.reference));
    const auto holdsTheEdits = [&] {
      if (!QFile::exists(autosave)) return false;
      const ProjectState s = readProject(autosave);
      return s.reference &&
             QString::fromStdString(referenceJsonText(*s.reference)) == wantReference &&
             sameSettings(s.settings, edited.settings) && s.pinnedRows == edited.pinnedRows;
    };
    QElapsedTimer clock;
    clock.start();
    QTRY_VERIFY_WITH_TIMEOUT(holdsTheEdits(), kWaitMs);
    qInfo("edits autosaved %lld ms after the start", clock.elapsed());
    QTest::qWait(2 * kAppAutosaveMs);  // past the interval: the edits are old enough
    app.kill();
    QVERIFY(app.waitForFinished(30000));
    QCOMPARE(app.exitStatus(), QProcess::CrashExit);

    QCOMPARE(Autosave::orphans(), QStringList{autosave});  // offered
    QCOMPARE(Autosave::originalProject(autosave), QFileInfo(project).absoluteFilePath());
    MainWindow window(ui::GridView::Backend::Raster);
    window.show();
    QVERIFY(window.offerRecovery(QStringLiteral("yes")));
    QVERIFY(window.waitForLoad(kWaitMs));
    QVERIFY(window.waitForMap(kWaitMs));
    qInfo("recovered after %lld ms", clock.elapsed());
    const Document& d = *window.document();
    QCOMPARE(d.logPath(), opened.logPath);
    QVERIFY(d.reference().has_value());
    QCOMPARE(QString::fromStdString(referenceJsonText(*d.reference())), wantReference);
    QVERIFY(d.referenceModified());
    QVERIFY(sameSettings(d.mapperSettings(), edited.settings));
    QVERIFY(d.pinnedRows() == edited.pinnedRows);
    QVERIFY(d.isModified());  // recovered work is still unsaved
    QVERIFY(Autosave::orphans().isEmpty());
  }

  // Issue 49 item 2: a project the app wrote must always open. For every model, each dock is
  // used once as a user would (the parameter panel's spin box, the Map dock's cell size, the
  // timeline, the beam view's reading and compare model, the metrics panel, the comparison
  // table's pin, the sweep view's run with Apply Best and Pin Best, a reference edit, the cell
  // inspector, the Robot dock's world, an overlay switched off). Then the project is saved and
  // opens in a new window with nothing dropped and the same document and map; and the session's
  // autosave, taken while it was unsaved and left as a crashed session leaves it (no live lock),
  // is recovered with the same document, still unsaved. (A killed process cannot use the docks;
  // killedSessionOfEveryModelIsRecovered kills one per model with its settings.)
  void everyModelWithEveryDockRoundTrips_data() {
    QTest::addColumn<QString>("model");
    for (const std::string& name : sensorModelNames())
      QTest::newRow(name.c_str()) << QString::fromStdString(name);
  }

  void everyModelWithEveryDockRoundTrips() {
    QFETCH(QString, model);
    QSettings().clear();
    qputenv("SONARGRID_AUTOSAVE_MS", "100");
    QTemporaryDir dir;
    const QString file = dir.filePath(QStringLiteral("every-dock.sgproj"));
    const QString orphan = autosaveDir_.filePath(QStringLiteral("session-999998.sgproj"));
    ProjectState saved;
    std::vector<std::uint8_t> savedLevels;
    {
      MainWindow window(ui::GridView::Backend::Raster);
      qunsetenv("SONARGRID_AUTOSAVE_MS");
      window.resize(1280, 800);
      window.show();
      QVERIFY(window.openLog(kRoom, true));
      QVERIFY(window.waitForMap(kWaitMs));
      useEveryDock(window, model.toStdString());
      if (QTest::currentTestFailed()) return;
      QVERIFY(window.waitForMap(kWaitMs));
      QVERIFY(window.document()->isModified());
      saved = window.document()->state();
      saved.view = window.gridView()->view();
      // The window's autosave of this state, left behind as a crashed session leaves it.
      const QString autosave =
          autosaveDir_.filePath(QStringLiteral("session-%1.sgproj").arg(qApp->applicationPid()));
      QTRY_VERIFY_WITH_TIMEOUT(
          QFile::exists(autosave) && sameDocument(readProject(autosave), saved), kWaitMs);
      QFile::remove(orphan);
      QVERIFY(QFile::copy(autosave, orphan));

      QVERIFY(window.saveProjectAs(file, true));
      QVERIFY(!window.isWindowModified());
      savedLevels = window.gridView()->map()->level;
    }
    QStringList dropped;
    const ProjectState read = readProject(file, &dropped);
    QVERIFY2(dropped.isEmpty(), qPrintable(dropped.join(QStringLiteral("; "))));
    QVERIFY(sameDocument(read, saved));
    {
      MainWindow window(ui::GridView::Backend::Raster);
      window.show();
      QVERIFY(window.openProject(file, true));
      QVERIFY(window.waitForMap(kWaitMs));
      QVERIFY(sameDocument(window.document()->state(), saved));
      QCOMPARE(window.gridView()->view(), *saved.view);
      QVERIFY(window.gridView()->map()->level == savedLevels);
      QVERIFY(!window.isWindowModified());
    }
    {
      QCOMPARE(Autosave::orphans(), QStringList{orphan});
      MainWindow window(ui::GridView::Backend::Raster);
      window.show();
      QVERIFY(window.offerRecovery(QStringLiteral("yes")));
      QVERIFY(window.waitForLoad(kWaitMs));
      QVERIFY(window.waitForMap(kWaitMs));
      QVERIFY(sameDocument(window.document()->state(), saved));
      QVERIFY(window.gridView()->map()->level == savedLevels);
      QVERIFY(window.document()->isModified());  // recovered work is still unsaved
      QVERIFY(!QFile::exists(orphan));
    }
  }

  // A real SIGKILL for every model: the session maps the room with the model, its paper's rule,
  // a parameter off its default and 10 cm cells (edits, so it autosaves), and is killed; the
  // next window recovers those settings.
  void killedSessionOfEveryModelIsRecovered_data() { everyModelWithEveryDockRoundTrips_data(); }

  void killedSessionOfEveryModelIsRecovered() {
    QFETCH(QString, model);
    const MapperSettings settings = offDefault(model.toStdString());
    const ParameterSpec& changed = firstUsed(settings.model);
    QTemporaryDir home;
    QVERIFY(home.isValid());
    QProcess app;
    prepareApp(app, home);
    app.start(QStringLiteral(SONARGRID_APP),
              {kRoom, "--model", model, "--rule", QString::fromStdString(settings.rule), "--set",
               QStringLiteral("%1=%2")
                   .arg(QString::fromStdString(changed.name))
                   .arg(settings.parameters.get(changed.name), 0, 'g', 17),
               "--cell", "0.1"});
    QVERIFY(app.waitForStarted(30000));
    const QString autosave =
        autosaveDir_.filePath(QStringLiteral("session-%1.sgproj").arg(app.processId()));
    // Written once the log has loaded (the settings come first, the log in the background).
    const auto written = [&] {
      if (!QFile::exists(autosave)) return false;
      const ProjectState s = readProject(autosave);
      return s.logPath == QFileInfo(kRoom).absoluteFilePath() &&
             sameSettings(s.settings, settings) && s.cellSize == 0.1;
    };
    QTRY_VERIFY_WITH_TIMEOUT(written(), kWaitMs);
    app.kill();
    QVERIFY(app.waitForFinished(30000));
    QCOMPARE(app.exitStatus(), QProcess::CrashExit);
    QCOMPARE(Autosave::orphans(), QStringList{autosave});
    MainWindow window(ui::GridView::Backend::Raster);
    window.show();
    QVERIFY(window.offerRecovery(QStringLiteral("yes")));
    QVERIFY(window.waitForLoad(kWaitMs));
    QVERIFY(window.waitForMap(kWaitMs));
    const Document& d = *window.document();
    QCOMPARE(d.logPath(), QFileInfo(kRoom).absoluteFilePath());
    QVERIFY(sameSettings(d.mapperSettings(), settings));
    QCOMPARE(d.cellSize(), 0.1);
    QVERIFY(d.isModified());
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
  // A `sonargrid` child offscreen that autosaves every 200 ms into this test's folder, with its
  // own settings under `home`, not the user's.
  void prepareApp(QProcess& app, const QTemporaryDir& home) const {
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    env.insert("QT_QPA_PLATFORM", "offscreen");
    env.insert("SONARGRID_AUTOSAVE_MS", QString::number(kAppAutosaveMs));
    env.insert("SONARGRID_AUTOSAVE_DIR", autosaveDir_.path());
    env.insert("XDG_CONFIG_HOME", home.filePath("config"));
    env.insert("XDG_DATA_HOME", home.filePath("data"));
    app.setProcessEnvironment(env);
    app.setProcessChannelMode(QProcess::ForwardedErrorChannel);
  }

  QTemporaryDir autosaveDir_;
};

QTEST_MAIN(TestMainWindowProject)
#include "tst_main_window_project.moc"
