// SPDX-License-Identifier: GPL-3.0-or-later
// No exception leaves a worker (issue 49: "No `terminate` path"). The sweep view once died with
// "terminate called after throwing an instance of 'sg::ParameterError'" when a HIMM decrement was
// swept over a fraction. Here every sensor model the registry makes is wrapped (the core's test
// hook, sonargrid/testing/registry_hooks.h) so that, while armed, each beam it rasterises throws
// that same ParameterError on whatever thread maps it. Each background job of the window then runs
// once: the re-map, the metrics panel's goodness measures, the cell inspector's trace, the
// comparison table's pinned row, the sweep view, the log loader (a file that cannot be read) and
// the live robot's map. Each must show the error, and the document must stay as it was: the same
// log, reference, settings, cells, pinned rows, undo history and modified flag, with the last good
// map still on screen and a re-map working once the fault is gone.

#include <QFile>
#include <QLabel>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QStatusBar>
#include <QTemporaryDir>
#include <QUndoStack>
#include <QtTest>
#include <atomic>
#include <optional>

#include "cell_inspector.h"
#include "comparison_table.h"
#include "document.h"
#include "grid_view.h"
#include "main_window.h"
#include "metrics_panel.h"
#include "remap_controller.h"
#include "robot/robot_dock.h"
#include "robot/robot_session.h"
#include "sonargrid/params/parameters.h"
#include "sonargrid/testing/registry_hooks.h"
#include "sweep_view.h"

using namespace sg;

namespace {

constexpr int kWaitMs = 120000;  // a bound against hangs, never a measured time
// The message of the exception that killed the sweep view (issue 49 item 1).
const char* const kFault = "parameter 'decrement' takes a whole number";

std::atomic<bool> armed{false};

// Arms the fault for its scope.
struct Armed {
  Armed() { armed = true; }
  ~Armed() { armed = false; }
  Armed(const Armed&) = delete;
  Armed& operator=(const Armed&) = delete;
};

void maybeThrow() {
  if (armed.load()) throw ParameterError(kFault);
}

// A real model whose beams throw while armed, on every mapping path it has: whole footprints,
// row windows, evidence runs, and HIMM's direct paths (cells listed on one thread and folded on
// another, or listed and folded at once).
class ThrowingModel final : public SensorModel {
 public:
  explicit ThrowingModel(std::unique_ptr<SensorModel> real) : real_(std::move(real)) {}
  const ModelInfo& info() const override { return real_->info(); }
  void configure(const ParameterSet& params) override { real_->configure(params); }
  ModelValue evaluate(double delta, double theta, double range, double maxRange) const override {
    return real_->evaluate(delta, theta, range, maxRange);
  }
  double reach(double maxRange) const override { return real_->reach(maxRange); }
  void footprint(const Beam& beam, const GridSpec& grid, const BeamTables& tables,
                 Footprint& out) const override {
    maybeThrow();
    real_->footprint(beam, grid, tables, out);
  }
  void footprintRows(const Beam& beam, const GridSpec& grid, const BeamTables& tables,
                     RowWindow window, Footprint& out) const override {
    maybeThrow();
    real_->footprintRows(beam, grid, tables, window, out);
  }
  bool rasterisesRows() const override { return real_->rasterisesRows(); }
  bool evidenceRuns(const Beam& beam, const GridSpec& grid, const BeamTables& tables,
                    RowWindow window, EvidenceRuns& out) const override {
    maybeThrow();
    return real_->evidenceRuns(beam, grid, tables, window, out);
  }
  bool listDirect(const Beam* beams, std::size_t count, const GridSpec& grid,
                  DirectCells& out) const override {
    maybeThrow();
    return real_->listDirect(beams, count, grid, out);
  }
  bool applyDirect(const DirectCells& cells, const UpdateRule& rule, Grid& grid) const override {
    maybeThrow();
    return real_->applyDirect(cells, rule, grid);
  }
  bool integrateDirect(const Beam* beams, std::size_t count, const UpdateRule& rule,
                       Grid& grid) const override {
    maybeThrow();
    return real_->integrateDirect(beams, count, rule, grid);
  }

 private:
  std::unique_ptr<SensorModel> real_;
};

// What "the document stays as it was" compares.
struct DocumentState {
  QString log, reference;
  std::string model, rule;
  std::map<std::string, double> parameters;
  double cellSize = 0.0;
  std::size_t pinned = 0;
  int undoCount = 0, undoIndex = 0;
  bool modified = false;

  explicit DocumentState(const app::Document& d)
      : log(d.logPath()),
        reference(d.referencePath()),
        model(d.mapperSettings().model),
        rule(d.mapperSettings().rule),
        parameters(d.mapperSettings().parameters.values()),
        cellSize(d.cellSize()),
        pinned(d.pinnedRows().size()),
        undoCount(d.undoStack()->count()),
        undoIndex(d.undoStack()->index()),
        modified(d.isModified()) {}
  bool operator==(const DocumentState&) const = default;
};

bool labelSays(QWidget* root, const QString& text) {
  for (QLabel* label : root->findChildren<QLabel*>())
    if (label->text().contains(text)) return true;
  return false;
}

}  // namespace

class TestBackgroundErrors : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() {
    QStandardPaths::setTestModeEnabled(true);  // QSettings go to a scratch location
    QCoreApplication::setOrganizationName("SonarGridTest");
    QCoreApplication::setApplicationName("tst_background_errors");
    QSettings().clear();
    testing::wrapSensorModels([](std::unique_ptr<SensorModel> real) {
      return std::unique_ptr<SensorModel>(std::make_unique<ThrowingModel>(std::move(real)));
    });
  }
  void cleanupTestCase() { testing::wrapSensorModels({}); }

  void init() {
    window_ = std::make_unique<app::MainWindow>(ui::GridView::Backend::Raster);
    window_->resize(1280, 800);
    window_->show();
    QVERIFY(window_->openLog(QStringLiteral(SONARGRID_DATASETS "/room/room.sglog"), true));
    QVERIFY(window_->waitForMap(kWaitMs));
    lastGoodMap_ = window_->gridView()->map();
  }
  void cleanup() {
    armed = false;
    lastGoodMap_.reset();
    window_.reset();
  }

  void remapShowsTheError() {
    // A new HIMM increment: the window re-maps (the same settings again would reuse the map).
    MapperSettings changed = window_->document()->mapperSettings();
    changed.parameters.set("increment", changed.parameters.get("increment") + 1.0);
    ui::RemapController* remap = window_->remapController();
    QSignalSpy failed(remap, &ui::RemapController::failed);
    std::optional<DocumentState> before;
    {
      const Armed fault;
      window_->document()->setMapperSettings(changed);
      before.emplace(*window_->document());  // the user's edit is kept
      QVERIFY(failed.wait(kWaitMs));
    }
    QVERIFY2(failed.at(0).at(0).toString().contains(kFault),
             qPrintable(failed.at(0).at(0).toString()));
    QVERIFY(labelSays(window_->statusBar(), tr("mapping failed")));
    checkIntact(*before);
  }

  void metricsPanelShowsTheError() {
    // Without a reference the panel maps the log again for paper 002's goodness measures.
    window_->document()->setReference(std::nullopt, QString());
    QVERIFY(window_->waitForMap(kWaitMs));
    lastGoodMap_ = window_->gridView()->map();
    auto* panel = window_->findChild<ui::MetricsPanel*>();
    QVERIFY(panel);
    QVERIFY(panel->waitForResult(kWaitMs));
    const DocumentState before(*window_->document());
    {
      // The goodness of other settings (those shown are known and not measured again).
      const Armed fault;
      MapperSettings other = window_->document()->mapperSettings();
      other.parameters.set("increment", other.parameters.get("increment") + 1.0);
      panel->setRuns(window_->document()->dataset(), nullptr, other,
                     window_->document()->cellSize());
      QVERIFY(panel->waitForResult(kWaitMs));
    }
    QVERIFY(panel->result());
    QVERIFY2(panel->result()->goodnessError.contains(kFault),
             qPrintable(panel->result()->goodnessError));
    QVERIFY(labelSays(panel, tr("Goodness not computed")));
    checkIntact(before);
  }

  void cellInspectorShowsTheError() {
    ui::CellInspector* inspector = window_->cellInspector();
    const DocumentState before(*window_->document());
    QSignalSpy failed(inspector, &ui::CellInspector::traceFailed);
    {
      const Armed fault;
      const GridSpec& spec = window_->gridView()->map()->spec;
      QVERIFY(inspector->inspect(CellIndex(spec.width / 2, spec.height / 2)));
      QVERIFY(failed.wait(kWaitMs));
    }
    QVERIFY2(failed.at(0).at(0).toString().contains(kFault),
             qPrintable(failed.at(0).at(0).toString()));
    QVERIFY(inspector->trace() == nullptr);
    QVERIFY(labelSays(inspector, kFault));
    checkIntact(before);
  }

  void comparisonTableShowsTheError() {
    auto* table = window_->findChild<ui::ComparisonTable*>();
    QVERIFY(table);
    app::PinnedRow row;
    row.label = QStringLiteral("pinned while the model throws");
    row.settings = window_->document()->mapperSettings();
    row.cellSize = window_->document()->cellSize();
    // The pin is the user's edit and stays: one more row, one more undo step, nothing else.
    DocumentState expected(*window_->document());
    ++expected.pinned;
    ++expected.undoCount;
    ++expected.undoIndex;
    expected.modified = true;
    {
      const Armed fault;
      window_->document()->pinRow(row);
      QVERIFY(table->waitForResult(kWaitMs));
    }
    // Its numbers are not there, and the table says why.
    QVERIFY(table->result(0) == nullptr);
    QVERIFY(labelSays(table, kFault));
    checkIntact(expected);
  }

  void sweepViewShowsTheError() {
    auto* view = window_->findChild<ui::SweepView*>();
    QVERIFY(view);
    view->setChoice({{"increment=1,3"}, {}, {"iop"}});
    const DocumentState before(*window_->document());
    QSignalSpy finished(view, &ui::SweepView::sweepFinished);
    {
      const Armed fault;
      QVERIFY(view->run());
      QVERIFY(view->waitForSweep(kWaitMs));
    }
    QVERIFY(!finished.isEmpty());
    QVERIFY2(view->statusText().contains(kFault), qPrintable(view->statusText()));
    QVERIFY(!view->isRunning());
    checkIntact(before);
  }

  void logLoaderShowsTheError() {
    // The loader reads and does not map: its failure is a file it cannot read.
    QTemporaryDir dir;
    const QString bad = dir.filePath(QStringLiteral("garbage.sglog"));
    {
      QFile f(bad);
      QVERIFY(f.open(QIODevice::WriteOnly));
      f.write("\x01\x02 not a log\n");
    }
    const DocumentState before(*window_->document());
    QSignalSpy failed(window_.get(), &app::MainWindow::loadFailed);
    QVERIFY(!window_->openLog(bad, true));
    QCOMPARE(failed.count(), 1);
    QVERIFY2(failed.at(0).at(1).toString().contains(QStringLiteral("garbage.sglog")),
             qPrintable(failed.at(0).at(1).toString()));
    checkIntact(before);
  }

  void liveMapShowsTheError() {
    lastGoodMap_.reset();  // the live map replaces the room's
    auto* dock = window_->findChild<app::RobotDock*>();
    QVERIFY(dock);
    app::RobotSession* session = dock->session();
    dock->setWorld(QStringLiteral(SONARGRID_DATASETS "/raschke-single/world.json"));
    app::VirtualRobotHost::Options options = dock->virtualRobotOptions();
    options.timeScale = 5.0;  // a few simulated seconds pass quickly
    QVERIFY(dock->startVirtualRobot(options));
    QTRY_COMPARE_WITH_TIMEOUT(session->state(), app::RobotSession::State::Connected, kWaitMs);
    QTRY_VERIFY_WITH_TIMEOUT(session->scansReceived() >= 10, kWaitMs);
    ui::RemapController* remap = window_->remapController();
    QSignalSpy failed(remap, &ui::RemapController::failed);
    std::size_t atFault = 0;
    {
      const Armed fault;
      QVERIFY(failed.wait(kWaitMs));  // the next scans' append run fails
      atFault = session->scansReceived();
    }
    QVERIFY2(failed.at(0).at(0).toString().contains(kFault),
             qPrintable(failed.at(0).at(0).toString()));
    // The link goes on: scans keep arriving and are kept, and with the fault gone a re-map maps
    // every one of them.
    QCOMPARE(session->state(), app::RobotSession::State::Connected);
    QTRY_VERIFY_WITH_TIMEOUT(session->scansReceived() >= atFault + 10, kWaitMs);
    session->disconnectLink();
    remap->remap();
    QVERIFY(window_->waitForMap(kWaitMs));
    QCOMPARE(session->source()->size(), session->scansReceived());
  }

 private:
  // The document as it was, the last good map still shown, and a re-map without the fault works.
  void checkIntact(const DocumentState& before) {
    QVERIFY(DocumentState(*window_->document()) == before);
    QVERIFY(window_->document()->dataset());
    QVERIFY(window_->gridView()->map());
    QVERIFY(!lastGoodMap_ || window_->gridView()->map() == lastGoodMap_);
    window_->remapController()->remap();
    QVERIFY(window_->waitForMap(kWaitMs));
    QVERIFY(DocumentState(*window_->document()) == before);
  }

  std::unique_ptr<app::MainWindow> window_;
  std::shared_ptr<const OccupancyMap> lastGoodMap_;  // the map shown before the fault
};

QTEST_MAIN(TestBackgroundErrors)
#include "tst_background_errors.moc"
