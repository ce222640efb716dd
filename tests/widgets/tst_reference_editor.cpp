// SPDX-License-Identifier: GPL-3.0-or-later
// The reference editor offscreen (raster surface): corners clicked in the grid view make the
// object and its actual position grid, corners typed in cm equal those typed in m, every edit is
// one undo step (a drag too) and undo/redo restore the exact corner lists, corners are inserted and
// deleted, and a saved reference reads back equal.

#include <QCheckBox>
#include <QComboBox>
#include <QLineEdit>
#include <QPushButton>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QUndoStack>
#include <QtTest>

#include "grid_view.h"
#include "reference_edit_model.h"
#include "reference_edit_tool.h"
#include "reference_editor.h"
#include "reference_editor_panel.h"
#include "sonargrid/reference/actual_position_grid.h"
#include "sonargrid/reference/reference_json.h"
#include "typed_length.h"

using namespace sg;
using namespace sg::ui;

namespace {

using Corners = std::vector<Eigen::Vector2d>;

// 16 x 12 cells of 0.5 m from (0, 0): the world box [0, 8] x [0, 6].
GridSpec testSpec() {
  GridSpec spec;
  spec.origin = {0.0, 0.0};
  spec.cellSize = 0.5;
  spec.width = 16;
  spec.height = 12;
  return spec;
}

// A 400 x 300 view at 40 px/m centred on (4, 3): pixel = (200 + 40 (x - 4), 150 - 40 (y - 3)),
// so every world point used below falls on a whole pixel and reads back exactly.
struct Fixture {
  QUndoStack stack;
  GridView view{GridView::Backend::Raster};
  ReferenceEditor editor{&stack, &view};

  Fixture() {
    view.resize(400, 300);
    view.setMap(std::make_shared<OccupancyMap>(OccupancyMap::unobserved(testSpec())));
    view.show();
    view.setView(ViewTransform{Position(4.0, 3.0), 40.0});
    editor.setEditing(true);
  }
  static QPoint pixel(double x, double y) {
    return {static_cast<int>(200 + 40 * (x - 4.0)), static_cast<int>(150 - 40 * (y - 3.0))};
  }
  void click(double x, double y, Qt::KeyboardModifiers modifiers = {}) {
    QTest::mouseClick(&view, Qt::LeftButton, modifiers, pixel(x, y));
  }
  const ReferenceObject& object(int i) const {
    return editor.reference()->objects[static_cast<std::size_t>(i)];
  }
};

bool sameReference(const ReferenceMap& a, const ReferenceMap& b) {
  if (a.unit != b.unit || a.objects.size() != b.objects.size()) return false;
  for (std::size_t i = 0; i < a.objects.size(); ++i) {
    const ReferenceObject& x = a.objects[i];
    const ReferenceObject& y = b.objects[i];
    if (x.name != y.name || x.closed != y.closed || x.corners != y.corners) return false;
  }
  return true;
}

ReferenceMap square(LengthUnit unit = LengthUnit::Metre) {
  ReferenceMap map;
  map.unit = unit;
  ReferenceObject o;
  o.name = "box";
  o.closed = true;
  o.corners = {{1.0, 1.0}, {3.0, 1.0}, {3.0, 2.5}, {1.0, 2.5}};
  map.objects.push_back(o);
  return map;
}

}  // namespace

class TestReferenceEditor : public QObject {
  Q_OBJECT

 private slots:
  void clickedCornersMakeAClosedObject_data() {
    QTest::addColumn<bool>("closeByKey");
    QTest::newRow("click on the first corner") << false;
    QTest::newRow("key C") << true;
  }
  void clickedCornersMakeAClosedObject() {
    QFETCH(bool, closeByKey);
    Fixture f;
    QVERIFY(QTest::qWaitForWindowExposed(&f.view));
    QSignalSpy edited(&f.editor, &ReferenceEditor::referenceEdited);
    const Corners corners = {{1.25, 1.25}, {3.25, 1.25}, {3.25, 2.75}, {1.25, 2.75}};
    for (const Eigen::Vector2d& c : corners) f.click(c.x(), c.y());
    QVERIFY(f.editor.tool()->drawing());
    QVERIFY(!f.editor.reference());  // nothing is added before the object is finished
    if (closeByKey)
      QTest::keyClick(&f.view, Qt::Key_C);
    else
      f.click(1.25, 1.25);
    QVERIFY(!f.editor.tool()->drawing());
    QVERIFY(f.editor.reference());
    QCOMPARE(f.editor.reference()->objects.size(), std::size_t{1});
    QVERIFY(f.object(0).closed);
    QCOMPARE(f.object(0).corners, corners);  // pixel -> world is exact at these pixels
    QCOMPARE(f.stack.count(), 1);
    QVERIFY(edited.count() >= 1);

    // By hand, with 0.5 m cells from (0, 0): x = 1.25 and 3.25 lie in columns 2 and 6, y = 1.25
    // and 2.75 in rows 2 and 5, none on a cell boundary. The bottom and top edges mark columns
    // 2..6 of rows 2 and 5, the sides rows 2..5 of columns 2 and 6: the border of the 5 x 4 block,
    // 2 * 5 + 2 * 2 = 14 cells, and nothing else.
    const GridSpec spec = testSpec();
    const ActualPositionGrid apg = ActualPositionGrid::rasterise(*f.editor.reference(), spec);
    QCOMPARE(apg.count(), std::size_t{14});
    for (int iy = 0; iy < spec.height; ++iy)
      for (int ix = 0; ix < spec.width; ++ix) {
        const bool inBlock = ix >= 2 && ix <= 6 && iy >= 2 && iy <= 5;
        const bool border = inBlock && (ix == 2 || ix == 6 || iy == 2 || iy == 5);
        QVERIFY2(apg.cells[spec.linear({ix, iy})] == (border ? 1 : 0),
                 qPrintable(QStringLiteral("cell (%1, %2)").arg(ix).arg(iy)));
      }
  }

  void snappingPutsCornersOnCellLines() {
    Fixture f;
    QVERIFY(QTest::qWaitForWindowExposed(&f.view));
    QTest::keyClick(&f.view, Qt::Key_S);
    QVERIFY(f.editor.tool()->snapping());
    QVERIFY(f.editor.panel()->findChild<QCheckBox*>("snap")->isChecked());
    // Pixels (201, 149) and (261, 149) are (4.025, 3.025) and (5.525, 3.025) m: the nearest
    // multiples of the 0.5 m cell are (4, 3) and (5.5, 3).
    QTest::mouseClick(&f.view, Qt::LeftButton, {}, QPoint(201, 149));
    QTest::mouseClick(&f.view, Qt::LeftButton, {}, QPoint(261, 149));
    QTest::keyClick(&f.view, Qt::Key_Return);
    QCOMPARE(f.object(0).corners, (Corners{{4.0, 3.0}, {5.5, 3.0}}));
    QVERIFY(!f.object(0).closed);
  }

  void typedUnitsGiveTheSameReference_data() {
    QTest::addColumn<LengthUnit>("stored");
    QTest::addColumn<LengthUnit>("typed");
    QTest::addColumn<QStringList>("values");  // x0 y0 as absolute, then x y offsets from corner 1
    // The survey: a datum corner at (0.57, 1.13) m, then 4.563 m along x and 3.2 m along y from
    // it. 57 * 0.01 is 0.5700000000000001 and 456.3 * 0.01 is 4.563000000000001, not 0.57 and
    // 4.563: multiplying by the unit's size would not give equality, a decimal conversion does.
    const QStringList m = {"0.57", "1.13", "4.563", "0", "4.563", "3.2", "0", "3.2"};
    const QStringList cm = {"57", "113", "456.3", "0", "456.3", "320", "0", "320"};
    const QStringList mm = {"570", "1130", "4563", "0", "4563", "3200", "0", "3200"};
    for (LengthUnit stored : {LengthUnit::Metre, LengthUnit::Centimetre, LengthUnit::Millimetre}) {
      const QString s = QString::fromLatin1(lengthUnitName(stored));
      QTest::newRow(qPrintable(s + " map, typed in m")) << stored << LengthUnit::Metre << m;
      QTest::newRow(qPrintable(s + " map, typed in cm")) << stored << LengthUnit::Centimetre << cm;
      QTest::newRow(qPrintable(s + " map, typed in mm")) << stored << LengthUnit::Millimetre << mm;
    }
  }
  void typedUnitsGiveTheSameReference() {
    QFETCH(LengthUnit, stored);
    QFETCH(LengthUnit, typed);
    QFETCH(QStringList, values);
    // The traps the decimal conversion avoids (volatile: computed at run time, as the app does).
    volatile double cmPerMetre = 0.01;
    QVERIFY(57 * cmPerMetre != 0.57 && 456.3 * cmPerMetre != 4.563);

    // Typed through the dock's widgets, as a user does: unit, first corner, datum, offsets.
    const auto typeSurvey = [&](LengthUnit unit, const QStringList& v) {
      auto f = std::make_unique<Fixture>();
      ReferenceMap empty;
      empty.unit = stored;
      f->editor.setReference(empty, QString());
      ReferenceEditorPanel* panel = f->editor.panel();
      panel->show();
      auto* unitBox = panel->findChild<QComboBox*>("entryUnit");
      unitBox->setCurrentText(QString::fromLatin1(lengthUnitName(unit)));
      auto* x = panel->findChild<QLineEdit*>("entryX");
      auto* y = panel->findChild<QLineEdit*>("entryY");
      for (int k = 0; k < v.size(); k += 2) {
        if (k == 2) panel->setDatum(0, 0);  // offsets from the first corner from here on
        QTest::keyClicks(x, v[k]);
        QTest::keyClick(x, Qt::Key_Return);  // to y
        QTest::keyClicks(y, v[k + 1]);
        QTest::keyClick(y, Qt::Key_Return);  // adds the corner
      }
      panel->findChild<QPushButton*>("closeObject")->click();
      return *f->editor.reference();
    };
    const ReferenceMap inMetres =
        typeSurvey(LengthUnit::Metre, {"0.57", "1.13", "4.563", "0", "4.563", "3.2", "0", "3.2"});
    const ReferenceMap got = typeSurvey(typed, values);
    QCOMPARE(got.unit, stored);  // the map keeps its unit
    QCOMPARE(got.objects.size(), std::size_t{1});
    QCOMPARE(got.objects[0].corners.size(), std::size_t{4});
    QVERIFY(got.objects[0].closed);
    QVERIFY2(sameReference(got, inMetres), "typed in another unit, the corners differ");
    // And the numbers are the ones the survey means, in the map's unit: the datum exactly.
    const double perMetre = stored == LengthUnit::Metre        ? 1.0
                            : stored == LengthUnit::Centimetre ? 100.0
                                                               : 1000.0;
    QCOMPARE(got.objects[0].corners[0],
             Eigen::Vector2d(*parseTypedLength("0.57", LengthUnit::Metre, stored),
                             *parseTypedLength("1.13", LengthUnit::Metre, stored)));
    QVERIFY(std::abs(got.objects[0].corners[2].x() - (0.57 + 4.563) * perMetre) < 1e-9 * perMetre);
  }

  void typedLengths_data() {
    QTest::addColumn<QString>("text");
    QTest::addColumn<LengthUnit>("typed");
    QTest::addColumn<LengthUnit>("stored");
    QTest::addColumn<bool>("valid");
    QTest::addColumn<double>("expected");  // the double the decimal written in `stored` reads as
    QTest::newRow("7 cm in m") << "7" << LengthUnit::Centimetre << LengthUnit::Metre << true
                               << 0.07;
    QTest::newRow("0,5 m in mm") << "0,5" << LengthUnit::Metre << LengthUnit::Millimetre << true
                                 << 500.0;
    QTest::newRow("1e3 mm in m") << "1e3" << LengthUnit::Millimetre << LengthUnit::Metre << true
                                 << 1.0;
    QTest::newRow("-12.34 cm in m")
        << " -12.34 " << LengthUnit::Centimetre << LengthUnit::Metre << true << -0.1234;
    QTest::newRow("4563 mm in cm")
        << "4563" << LengthUnit::Millimetre << LengthUnit::Centimetre << true << 456.3;
    QTest::newRow("empty") << "" << LengthUnit::Metre << LengthUnit::Metre << false << 0.0;
    QTest::newRow("letters") << "1.2m" << LengthUnit::Metre << LengthUnit::Metre << false << 0.0;
    QTest::newRow("two points") << "1.2.3" << LengthUnit::Metre << LengthUnit::Metre << false
                                << 0.0;
    QTest::newRow("overflow") << "1e400" << LengthUnit::Metre << LengthUnit::Metre << false << 0.0;
  }
  void typedLengths() {
    QFETCH(QString, text);
    QFETCH(LengthUnit, typed);
    QFETCH(LengthUnit, stored);
    QFETCH(bool, valid);
    QFETCH(double, expected);
    const auto v = parseTypedLength(text, typed, stored);
    QCOMPARE(v.has_value(), valid);
    if (!valid) return;
    QCOMPARE(*v, expected);  // exact: the same double as the literal
    // Shown back in the typed unit, the text reads back to the same double.
    QCOMPARE(*parseTypedLength(typedLengthText(*v, stored, typed), typed, stored), *v);
  }

  void lengthTextAndSnapping() {
    QCOMPARE(typedLengthText(0.07, LengthUnit::Metre, LengthUnit::Centimetre), QString("7"));
    QCOMPARE(typedLengthText(4563, LengthUnit::Millimetre, LengthUnit::Metre), QString("4.563"));
    QCOMPARE(typedLengthText(0.0005, LengthUnit::Metre, LengthUnit::Metre), QString("0.0005"));
    QCOMPARE(roundedLengthText(1.23 - 0.5, LengthUnit::Metre, LengthUnit::Centimetre),
             QString("73"));
    // Three 5 cm cells: 0.15, as typed, where 3 * 0.05 = 0.15000000000000002.
    QVERIFY(3 * 0.05 != 0.15);
    QCOMPARE(snappedToCells(0.149, 0.05, LengthUnit::Metre), 0.15);
    QCOMPARE(snappedToCells(0.149, 0.05, LengthUnit::Millimetre), 150.0);
    QCOMPARE(snappedToCells(-0.26, 0.05, LengthUnit::Centimetre), -25.0);
  }

  void undoRedoRestoreExactCorners() {
    Fixture f;
    QVERIFY(QTest::qWaitForWindowExposed(&f.view));
    f.editor.setReference(square(), QString());
    QCOMPARE(f.stack.count(), 1);  // opening is a step too: the stack never outlives its map
    std::vector<Corners> history = {f.object(0).corners};

    // A drag of corner 2 (3, 1) through three moves is one step; the corner ends where released.
    const int before = f.stack.count();
    QTest::mousePress(&f.view, Qt::LeftButton, {}, Fixture::pixel(3.0, 1.0));
    QTest::mouseMove(&f.view, Fixture::pixel(3.5, 1.0));
    QTest::mouseMove(&f.view, Fixture::pixel(4.0, 0.5));
    QTest::mouseMove(&f.view, Fixture::pixel(4.5, 0.75));
    QTest::mouseRelease(&f.view, Qt::LeftButton, {}, Fixture::pixel(4.5, 0.75));
    QCOMPARE(f.stack.count(), before + 1);
    QCOMPARE(f.object(0).corners[1], Eigen::Vector2d(4.5, 0.75));
    history.push_back(f.object(0).corners);

    // Ctrl+click on the middle of the edge (1, 2.5)-(1, 1) inserts a corner there, after corner 4.
    f.click(1.0, 1.75, Qt::ControlModifier);
    QCOMPARE(f.object(0).corners,
             (Corners{{1.0, 1.0}, {4.5, 0.75}, {3.0, 2.5}, {1.0, 2.5}, {1.0, 1.75}}));
    QCOMPARE(f.editor.model()->selectedCorner(), 4);
    history.push_back(f.object(0).corners);

    // Del deletes the selected corner: a click on corner (3, 2.5) selects it.
    f.click(3.0, 2.5);
    QCOMPARE(f.editor.model()->selectedCorner(), 2);
    QTest::keyClick(&f.view, Qt::Key_Delete);
    QCOMPARE(f.object(0).corners, (Corners{{1.0, 1.0}, {4.5, 0.75}, {1.0, 2.5}, {1.0, 1.75}}));
    history.push_back(f.object(0).corners);

    // C opens the selected object: one step that keeps the corners.
    QTest::keyClick(&f.view, Qt::Key_C);
    QVERIFY(!f.object(0).closed);
    QCOMPARE(f.stack.count(), before + 4);

    f.stack.undo();  // the open
    QVERIFY(f.object(0).closed);
    for (int k = static_cast<int>(history.size()) - 2; k >= 0; --k) {
      f.stack.undo();
      QCOMPARE(f.object(0).corners, history[static_cast<std::size_t>(k)]);
    }
    for (std::size_t k = 1; k < history.size(); ++k) {
      f.stack.redo();
      QCOMPARE(f.object(0).corners, history[k]);
    }
    f.stack.redo();
    QVERIFY(!f.object(0).closed);
  }

  void deletingCornersDownToNothing() {
    Fixture f;
    f.editor.setReference(square(), QString());
    ReferenceEditModel* m = f.editor.model();
    m->removeCorner(0, 0);  // 3 corners left: still closed
    QVERIFY(f.object(0).closed);
    m->removeCorner(0, 0);  // 2 left: a closed object needs 3, so it is open now (same step)
    QVERIFY(!f.object(0).closed);
    QCOMPARE(f.object(0).corners, (Corners{{3.0, 2.5}, {1.0, 2.5}}));
    m->removeCorner(0, 1);  // 1 left: not an object any more
    QCOMPARE(f.editor.reference()->objects.size(), std::size_t{0});
    f.stack.undo();
    f.stack.undo();
    QVERIFY(f.object(0).closed);
    QCOMPARE(f.object(0).corners, (Corners{{3.0, 1.0}, {3.0, 2.5}, {1.0, 2.5}}));
  }

  void dragBackToTheStartLeavesNoStep() {
    Fixture f;
    QVERIFY(QTest::qWaitForWindowExposed(&f.view));
    f.editor.setReference(square(), QString());
    const int before = f.stack.count();
    QTest::mousePress(&f.view, Qt::LeftButton, {}, Fixture::pixel(1.0, 1.0));
    QTest::mouseMove(&f.view, Fixture::pixel(2.0, 0.5));
    QTest::mouseMove(&f.view, Fixture::pixel(1.0, 1.0));
    QTest::mouseRelease(&f.view, Qt::LeftButton, {}, Fixture::pixel(1.0, 1.0));
    QCOMPARE(f.stack.count(), before);
    QCOMPARE(f.object(0).corners, square().objects[0].corners);
  }

  void renameAndCloseFromTheDock() {
    Fixture f;
    f.editor.setReference(square(), QString());
    ReferenceEditModel* m = f.editor.model();
    QVERIFY(m->renameObject(0, "north wall"));
    QVERIFY(!m->renameObject(0, ""));
    ReferenceObject other;
    other.name = "pillar";
    other.corners = {{5, 5}, {6, 5}};
    m->addObject(other);
    QVERIFY(!m->renameObject(1, "north wall"));  // names are unique (the file requires it)
    QVERIFY(!m->setClosed(1, true));             // 2 corners cannot close
    QCOMPARE(f.object(0).name, std::string("north wall"));
    f.stack.undo();
    f.stack.undo();
    QCOMPARE(f.object(0).name, std::string("box"));
  }

  void adoptingIsNoStepAndNoSignal() {
    Fixture f;
    QSignalSpy edited(&f.editor, &ReferenceEditor::referenceEdited);
    f.editor.adoptReference(square(LengthUnit::Millimetre), "room.json");
    QCOMPARE(f.stack.count(), 0);
    QCOMPARE(edited.count(), 0);
    QVERIFY(sameReference(*f.editor.reference(), square(LengthUnit::Millimetre)));
    QCOMPARE(f.editor.panel()->entryUnit(), LengthUnit::Millimetre);
    f.editor.model()->moveCorner(0, 0, {0, 0});  // edits after it are steps, and signalled
    QCOMPARE(f.stack.count(), 1);
    QCOMPARE(edited.count(), 1);
  }

  void saveAndLoadRoundTrip() {
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    Fixture f;
    ReferenceMap map = square(LengthUnit::Centimetre);
    map.objects[0].corners = {{7, 110}, {463.3, 110}, {463.3, 430}, {7, 430}};
    f.editor.setReference(map, QString());
    f.editor.model()->moveCorner(0, 1, {470.25, 110});
    const QString path = dir.filePath("room.json");
    QString error;
    QVERIFY2(f.editor.save(path, &error), qPrintable(error));
    QCOMPARE(f.editor.path(), path);

    Fixture g;
    QVERIFY2(g.editor.open(path, &error), qPrintable(error));
    QVERIFY(sameReference(*g.editor.reference(), *f.editor.reference()));
    QCOMPARE(g.editor.reference()->unit, LengthUnit::Centimetre);
    QCOMPARE(g.editor.panel()->entryUnit(), LengthUnit::Centimetre);
  }

  void importArMapThenEditAndSave() {
    QTemporaryDir dir;
    const QString armap = dir.filePath("lab.map");
    {
      QFile file(armap);
      QVERIFY(file.open(QIODevice::WriteOnly));
      file.write(
          "2D-Map\nLineMinPos: 0 0\nLineMaxPos: 4000 3000\nNumLines: 2\nLINES\n"
          "0 0 4000 0\n4000 0 4000 3000\nDATA\n");
    }
    Fixture f;
    QString error;
    QVERIFY2(f.editor.open(armap, &error), qPrintable(error));
    QCOMPARE(f.editor.reference()->unit, LengthUnit::Millimetre);  // ArMap's integers stay
    QCOMPARE(f.object(1).name, std::string("line 2"));
    f.editor.model()->moveCorner(1, 1, {4000, 3200});
    const QString json = dir.filePath("lab.json");
    QVERIFY2(f.editor.save(json, &error), qPrintable(error));
    Fixture g;
    QVERIFY(g.editor.open(json, &error));
    QVERIFY(sameReference(*g.editor.reference(), *f.editor.reference()));
    QCOMPARE(g.object(1).corners[1], Eigen::Vector2d(4000, 3200));
  }

  void errorsNameTheFileAndLine() {
    QTemporaryDir dir;
    const QString bad = dir.filePath("bad.json");
    {
      QFile file(bad);
      QVERIFY(file.open(QIODevice::WriteOnly));
      file.write(
          "{\"format\": \"sonargrid-reference\", \"version\": 1, \"units\": \"m\",\n"
          "  \"objects\": [\n"
          "    {\"name\": \"box\", \"closed\": true, \"corners\": [[0, 0], [1, 0]]}\n"
          "  ]}\n");
    }
    Fixture f;
    f.editor.setReference(square(), QString());
    QString error;
    QVERIFY(!f.editor.open(bad, &error));
    QVERIFY2(error.contains("bad.json:3:"), qPrintable(error));
    QVERIFY(sameReference(*f.editor.reference(), square()));  // the edited map stays

    // An object still being typed (one corner) cannot be saved; the message names it and the file.
    ReferenceObject half;
    half.name = "half";
    half.corners = {{0, 0}};
    f.editor.model()->addObject(half);
    const QString out = dir.filePath("out.json");
    QVERIFY(!f.editor.save(out, &error));
    QVERIFY2(error.contains("out.json") && error.contains("half") &&
                 error.contains("at least 2 corners"),
             qPrintable(error));
    QVERIFY(!QFile::exists(out));
    QVERIFY(!f.editor.save(dir.filePath("no/such/folder/x.json"), &error));
    QVERIFY2(error.contains("no/such/folder/x.json"), qPrintable(error));
  }
};

QTEST_MAIN(TestReferenceEditor)
#include "tst_reference_editor.moc"
