// SPDX-License-Identifier: GPL-3.0-or-later
// The document's undo stack, alone and in the window offscreen: a settings change and a cell-size
// change undo and redo to exactly the maps Mapper::mapDataset builds with those values; a slider
// dragged across many positions is one undo step; saving makes the document clean; a new log closes
// a reference drawn for another log, and Undo brings it back.

#include <QDoubleSpinBox>
#include <QSignalSpy>
#include <QSlider>
#include <QStandardPaths>
#include <QUndoStack>
#include <QtTest>

#include "document.h"
#include "main_window.h"
#include "parameter_panel.h"
#include "remap_controller.h"
#include "sonargrid/io/sglog.h"

using namespace sg;
using namespace sg::app;

namespace {

const QString kRoom = QStringLiteral(SONARGRID_DATASETS "/room/room.sglog");
const QString kOffice = QStringLiteral(SONARGRID_DATASETS "/office/office.sglog");

MapperSettings hpfAddition() {
  MapperSettings s;
  s.model = "hpf";
  s.rule = "addition";
  s.parameters = defaultParameters(s.model, s.rule);
  s.pose = PoseSource::Truth;
  return s;
}

MapperSettings withEpsilon(double epsilon) {
  MapperSettings s = hpfAddition();
  s.parameters.set("epsilon", epsilon);
  return s;
}

// What `sonargrid-cli map --log room.sglog --pose truth --cell CELL` maps with these settings.
OccupancyMap batchMap(const Dataset& data, const MapperSettings& settings, double cell = 0.05) {
  Mapper m(data.ring, data.fittingGrid(PoseSource::Truth, cell), settings);
  m.mapDataset(data);
  return m.snapshot();
}

bool openRoom(MainWindow& window) {
  window.setCellSize(0.05);
  window.setMapperSettings(hpfAddition());
  window.show();
  return window.openLog(kRoom, true) && window.waitForMap(60000);
}

}  // namespace

class TestDocument : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() {
    QStandardPaths::setTestModeEnabled(true);  // QSettings go to a scratch location
    QCoreApplication::setOrganizationName("SonarGridTest");
    QCoreApplication::setApplicationName("tst_document");
    QSettings().clear();
    data_ = readSglog(kRoom.toStdString());
  }

  void settingsUndoAndRedoAlone() {
    Document d;
    d.restore(ProjectState{});
    QVERIFY(!d.isModified());
    QSignalSpy settings(&d, &Document::settingsChanged);
    QSignalSpy modified(&d, &Document::modifiedChanged);
    d.setMapperSettings(withEpsilon(0.2));
    d.setMapperSettings(withEpsilon(0.2));  // the same again: no step
    QCOMPARE(d.undoStack()->count(), 1);
    QCOMPARE(settings.count(), 1);
    QVERIFY(d.isModified());
    QCOMPARE(modified.count(), 1);
    d.undoStack()->undo();
    QVERIFY(sameSettings(d.mapperSettings(), ProjectState{}.settings));
    QVERIFY(!d.isModified());  // back at the clean state
    d.undoStack()->redo();
    QCOMPARE(d.mapperSettings().parameters.get("epsilon"), 0.2);
    d.markSaved();
    QVERIFY(!d.isModified());
    // Steps of one drag merge; a drag that ends where it began leaves no step.
    d.setMapperSettings(withEpsilon(0.3), true);
    d.setMapperSettings(withEpsilon(0.4), true);
    QCOMPARE(d.undoStack()->count(), 2);
    d.setMapperSettings(withEpsilon(0.2), true);
    d.endDrag();
    QCOMPARE(d.undoStack()->count(), 1);
    QVERIFY(!d.isModified());
  }

  void cellSizePinnedRowsAndReferenceUndo() {
    Document d;
    d.restore(ProjectState{});
    d.setCellSize(0.1);
    d.setCellSize(5.0);  // clamped to the largest cell, 1 m
    QCOMPARE(d.cellSize(), kMaxCellSize);
    d.undoStack()->undo();
    QCOMPARE(d.cellSize(), 0.1);
    d.pinRow(PinnedRow{QStringLiteral("a"), hpfAddition(), 0.1});
    d.pinRow(PinnedRow{QStringLiteral("b"), withEpsilon(0.3), 0.05});
    d.removePinnedRow(0);
    QCOMPARE(d.pinnedRows().size(), std::size_t(1));
    QCOMPARE(d.pinnedRows().front().label, QStringLiteral("b"));
    d.undoStack()->undo();
    QCOMPARE(d.pinnedRows().size(), std::size_t(2));
    QCOMPARE(d.pinnedRows().front().label, QStringLiteral("a"));

    ReferenceMap map;
    ReferenceObject wall;
    wall.name = "wall";
    wall.corners = {{0.0, 0.0}, {2.0, 0.0}};
    map.objects = {wall};
    QSignalSpy reference(&d, &Document::referenceChanged);
    d.setReference(map, QString());
    QVERIFY(d.reference().has_value());
    QVERIFY(d.referenceModified());  // drawn, never saved: a project holds it inline
    d.undoStack()->undo();
    QVERIFY(!d.reference().has_value());
    QCOMPARE(reference.count(), 2);
  }

  void settingsChangeUndoesToTheMapOfTheOldSettings() {
    MainWindow window;
    QVERIFY(openRoom(window));
    QUndoStack* undo = window.document()->undoStack();
    const int steps = undo->count();
    window.setMapperSettings(withEpsilon(0.2));
    QVERIFY(window.waitForMap(60000));
    QVERIFY(window.gridView()->map()->level == batchMap(data_, withEpsilon(0.2)).level);
    QCOMPARE(undo->count(), steps + 1);
    QVERIFY(window.isWindowModified());

    undo->undo();
    QCOMPARE(window.mapperSettings().parameters.get("epsilon"), 0.1);  // HPF's default ε
    QCOMPARE(window.parameterPanel()->settings().parameters.get("epsilon"), 0.1);
    QVERIFY(window.waitForMap(60000));
    QVERIFY(window.gridView()->map()->level == batchMap(data_, hpfAddition()).level);
    undo->redo();
    QVERIFY(window.waitForMap(60000));
    QVERIFY(window.gridView()->map()->level == batchMap(data_, withEpsilon(0.2)).level);
  }

  void cellSizeUndoesToTheMapOfTheOldCell() {
    MainWindow window;
    QVERIFY(openRoom(window));
    auto* spin = window.findChild<QDoubleSpinBox*>("cellSize");
    QVERIFY(spin);
    QCOMPARE(spin->value(), 0.05);
    spin->setValue(0.1);  // as typing 0.1 and Enter does (keyboard tracking is off)
    QCOMPARE(window.document()->cellSize(), 0.1);
    QVERIFY(window.waitForMap(60000));
    QCOMPARE(window.gridView()->map()->spec.cellSize, 0.1);
    QVERIFY(window.gridView()->map()->level == batchMap(data_, hpfAddition(), 0.1).level);

    window.document()->undoStack()->undo();
    QCOMPARE(spin->value(), 0.05);
    QVERIFY(window.waitForMap(60000));
    QCOMPARE(window.remapController()->cellSize(), 0.05);
    QVERIFY(window.gridView()->map()->level == batchMap(data_, hpfAddition()).level);
    window.document()->undoStack()->redo();
    QCOMPARE(spin->value(), 0.1);
    QVERIFY(window.waitForMap(60000));
    QCOMPARE(window.gridView()->map()->spec.cellSize, 0.1);
  }

  void sliderDragIsOneUndoStep() {
    MainWindow window;
    QVERIFY(openRoom(window));
    QUndoStack* undo = window.document()->undoStack();
    const int steps = undo->count();
    QSlider* slider = window.parameterPanel()->sliderFor("epsilon");
    QVERIFY(slider);
    // ε moves in 1 mm steps from 0.100 m at position 95 (tst_main_window_panel): position p is
    // 0.005 + p mm, so a drag over 20 positions ends at 0.120 m, the second drag at 0.125 m.
    slider->setSliderDown(true);
    for (int p = 96; p <= 115; ++p) slider->setValue(p);
    slider->setSliderDown(false);
    QCOMPARE(window.mapperSettings().parameters.get("epsilon"), 0.120);
    QCOMPARE(undo->count(), steps + 1);
    // A second drag is a step of its own.
    slider->setSliderDown(true);
    for (int p = 116; p <= 120; ++p) slider->setValue(p);
    slider->setSliderDown(false);
    QCOMPARE(undo->count(), steps + 2);
    // So is a key press.
    slider->setFocus();
    QTest::keyClick(slider, Qt::Key_Right);
    QCOMPARE(window.mapperSettings().parameters.get("epsilon"), 0.126);
    QCOMPARE(undo->count(), steps + 3);

    undo->undo();
    QCOMPARE(window.mapperSettings().parameters.get("epsilon"), 0.125);
    undo->undo();
    QCOMPARE(window.mapperSettings().parameters.get("epsilon"), 0.120);
    undo->undo();
    QCOMPARE(window.mapperSettings().parameters.get("epsilon"), 0.1);
    QCOMPARE(slider->value(), 95);
    QVERIFY(window.waitForMap(60000));
    QVERIFY(window.gridView()->map()->level == batchMap(data_, hpfAddition()).level);
  }

  void newLogClosesAReferenceOfAnotherLog() {
    MainWindow window;
    QVERIFY(openRoom(window));
    // room.json beside room.sglog came along with the log.
    QVERIFY(window.document()->reference().has_value());
    const std::size_t objects = window.document()->reference()->objects.size();
    const QString roomReference = window.document()->referencePath();
    QVERIFY(window.openLog(kOffice, true));
    // The room's reference is closed; the office dataset's manifest (datasets/office/dataset.json)
    // names its own, which comes along instead.
    QVERIFY(window.document()->referencePath() != roomReference);
    QVERIFY(window.document()->reference().has_value());
    QVERIFY(window.document()->reference()->objects.size() != objects);
    // The office log is a new document with its own history (issue 49: an undo put the room's
    // walls over the next log): nothing to undo brings the room's reference back.
    QVERIFY(!window.document()->undoStack()->canUndo());
    QVERIFY(window.waitForMap(60000));
  }

 private:
  Dataset data_;
};

QTEST_MAIN(TestDocument)
#include "tst_document.moc"
