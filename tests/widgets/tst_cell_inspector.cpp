// SPDX-License-Identifier: GPL-3.0-or-later
// The cell inspector in the window, offscreen: a Shift+click on a cell of the grid view traces it,
// the list holds as many readings as the core trace (sg::traceCell) of that cell, its last value
// is the map's, choosing a reading moves the timeline to its scan and shows it in the beam view,
// and a re-map with other settings traces the cell again.

#include <QDockWidget>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTreeWidget>
#include <QtTest>

#include "beam_model_view.h"
#include "cell_inspector.h"
#include "grid_view.h"
#include "main_window.h"
#include "sonargrid/engine/cell_trace.h"
#include "sonargrid/io/sglog.h"
#include "timeline.h"

using namespace sg;

namespace {

const QString kRoom = QStringLiteral(SONARGRID_DATASETS "/room/room.sglog");

MapperSettings settingsOf(const char* model, const char* rule) {
  MapperSettings s;
  s.model = model;
  s.rule = rule;
  s.parameters = defaultParameters(s.model, s.rule);
  s.pose = PoseSource::Truth;
  return s;
}

}  // namespace

class TestCellInspector : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() {
    QStandardPaths::setTestModeEnabled(true);  // QSettings go to a scratch location
    QCoreApplication::setOrganizationName("SonarGridTest");
    QCoreApplication::setApplicationName("tst_cell_inspector");
    QSettings().clear();
  }

  void shiftClickTracesTheCell_data() {
    QTest::addColumn<QString>("model");
    QTest::addColumn<QString>("rule");
    QTest::addColumn<double>("x");
    QTest::addColumn<double>("y");
    // The south wall of the room (room.json: walls from (0, 0) to (6, 0)), seen by the side
    // sonars on both laps; and a point of open floor between the path and the box. Both are the
    // centres of 0.1 m cells (the fitting grid's origin is a multiple of the cell size).
    QTest::newRow("himm x himm, south wall") << "himm"
                                             << "himm" << 3.05 << 0.05;
    QTest::newRow("parameterized x bayes, south wall") << "parameterized"
                                                       << "bayes" << 3.05 << 0.05;
    QTest::newRow("hpf x addition, open floor") << "hpf"
                                                << "addition" << 2.05 << 1.25;
  }

  void shiftClickTracesTheCell() {
    QFETCH(QString, model);
    QFETCH(QString, rule);
    QFETCH(double, x);
    QFETCH(double, y);
    app::MainWindow window;
    window.setCellSize(0.1);
    const MapperSettings settings = settingsOf(qPrintable(model), qPrintable(rule));
    window.setMapperSettings(settings);
    window.resize(1100, 800);
    window.show();
    QVERIFY(window.openLog(kRoom, true));
    QVERIFY(window.waitForMap(60000));
    ui::CellInspector* inspector = window.cellInspector();
    QVERIFY(inspector);
    auto* dock = window.findChild<QDockWidget*>(QStringLiteral("cellInspectorDock"));
    QVERIFY(dock);
    QVERIFY(dock->isHidden());

    // A plain click pans (nothing inspected); Shift+click at the world point inspects its cell.
    ui::GridView* view = window.gridView();
    const QPoint pixel = view->view().toPixel(Position(x, y), view->size()).toPoint();
    QTest::mouseClick(view, Qt::LeftButton, Qt::NoModifier, pixel);
    QVERIFY(!inspector->cell());
    QSignalSpy traced(inspector, &ui::CellInspector::traced);
    QTest::mouseClick(view, Qt::LeftButton, Qt::ShiftModifier, pixel);
    QVERIFY(dock->isVisible());
    const std::shared_ptr<const OccupancyMap> map = view->map();
    // The cell of the point aimed at (half a cell, several pixels, from its edges). The view is
    // smaller now: the dock that opened took room from it.
    const CellIndex cell = map->spec.worldToCell(Position(x, y));
    QVERIFY(inspector->cell());
    QCOMPARE(inspector->cell()->x(), cell.x());
    QCOMPARE(inspector->cell()->y(), cell.y());
    QVERIFY(traced.wait(60000));

    // The core's trace of the same cell, map grid and settings.
    const Dataset data = readSglog(kRoom.toStdString());
    QCOMPARE(map->spec, data.fittingGrid(PoseSource::Truth, 0.1));
    const CellTrace expected = traceCell(data, map->spec, settings, cell);
    QVERIFY(expected.steps.size() > 5);  // a cell many readings wrote
    const auto rows = static_cast<std::size_t>(inspector->readingList()->topLevelItemCount());
    QCOMPARE(rows, expected.steps.size());
    QCOMPARE(inspector->trace()->steps.size(), expected.steps.size());
    // The map's value at the cell is the trace's last one.
    const std::size_t i = map->spec.linear(cell);
    QCOMPARE(inspector->trace()->final().native, map->native[i]);
    QCOMPARE(inspector->trace()->final().probability, map->probability[i]);

    // Choosing a reading in the list: the timeline goes to its scan, the beam view shows it.
    const std::size_t pick = expected.steps.size() / 2;
    const CellTraceStep& step = expected.steps[pick];
    QTreeWidget* list = inspector->readingList();
    // As the keyboard or a click in the list does: the list's current row changes.
    list->setCurrentItem(list->topLevelItem(0));
    QCOMPARE(window.timeline()->currentScan(), expected.steps[0].scan);
    list->setCurrentItem(list->topLevelItem(static_cast<int>(pick)));
    QCOMPARE(window.timeline()->currentScan(), step.scan);
    QVERIFY(window.beamSonar());
    QCOMPARE(*window.beamSonar(), std::size_t{step.sonar});
    const double shown = std::isfinite(step.range) ? step.range : data.ring.maxRange;
    QCOMPARE(window.beamModelView()->range(), std::clamp(shown, 0.05, data.ring.maxRange));
    // The list keeps every reading of the whole log: the time moved, the trace did not.
    QCOMPARE(static_cast<std::size_t>(list->topLevelItemCount()), expected.steps.size());
  }

  void remapTracesAgain() {
    app::MainWindow window;
    window.setCellSize(0.1);
    window.setMapperSettings(settingsOf("himm", "himm"));
    window.show();
    QVERIFY(window.openLog(kRoom, true));
    QVERIFY(window.waitForMap(60000));
    ui::CellInspector* inspector = window.cellInspector();
    QSignalSpy traced(inspector, &ui::CellInspector::traced);
    QVERIFY(inspector->inspectAt(Position(3.0, 0.02)));
    QVERIFY(traced.wait(60000));
    const CellIndex cell = *inspector->cell();
    const double himmValue = inspector->trace()->final().native;

    // Another rule re-maps; the same cell is traced with it, and ends at the new map's value.
    window.setMapperSettings(settingsOf("himm", "logodds"));
    QVERIFY(window.waitForMap(60000));
    QVERIFY(traced.count() >= 2 || traced.wait(60000));
    QTRY_VERIFY_WITH_TIMEOUT(!inspector->busy(), 60000);
    QCOMPARE(*inspector->cell(), cell);
    const std::shared_ptr<const OccupancyMap> map = window.gridView()->map();
    QCOMPARE(inspector->trace()->final().native, map->native[map->spec.linear(cell)]);
    QVERIFY(inspector->trace()->final().native != himmValue);
    QCOMPARE(inspector->trace()->nativeName, updateRuleInfo("logodds").nativeName);
  }
};

QTEST_MAIN(TestCellInspector)
#include "tst_cell_inspector.moc"
