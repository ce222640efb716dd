// SPDX-License-Identifier: GPL-3.0-or-later
// The reference editor in the window on the OpenGL surface (xcb, under xvfb-run): edit mode puts
// the tool on the grid view, the tool's drawing reaches the GL framebuffer, and an object drawn
// with clicks becomes the window's reference lines. With SONARGRID_SCREENSHOT_DIR set it also
// writes the user guide's pictures of the editor there (docs/user-guide.md).

#include <QAction>
#include <QDockWidget>
#include <QScreen>
#include <QtTest>

#include "grid_view.h"
#include "main_window.h"
#include "reference_edit_model.h"
#include "reference_edit_tool.h"
#include "reference_editor.h"
#include "reference_editor_panel.h"

using namespace sg;
using namespace sg::ui;

namespace {

bool reddish(QRgb c) {
  return qRed(c) > 200 && qGreen(c) < 80 && qBlue(c) < 80;
}

void settle() {
  for (int i = 0; i < 10; ++i) QApplication::processEvents(QEventLoop::AllEvents, 20);
}

void shoot(app::MainWindow& window, const char* name) {
  const QString dir = qEnvironmentVariable("SONARGRID_SCREENSHOT_DIR");
  if (dir.isEmpty()) return;
  settle();
  const QPixmap shot = window.screen()->grabWindow(window.winId());
  QVERIFY(shot.save(dir + QLatin1Char('/') + QLatin1String(name)));
}

}  // namespace

class TestGlReferenceEditor : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() {
    if (QGuiApplication::platformName() != QLatin1String("xcb"))
      QSKIP("needs the xcb platform (run under xvfb-run, ctest label gl)");
  }

  void editModeDrawsOnTheGlSurface() {
    app::MainWindow window(GridView::Backend::OpenGL);
    window.resize(1280, 800);
    QVERIFY(window.openReference(SONARGRID_DATASETS "/room/room.json", true));
    QVERIFY(window.openLog(SONARGRID_DATASETS "/room/room.sglog", true));
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QVERIFY(window.waitForMap(60000));
    GridView* view = window.gridView();
    QCOMPARE(view->backend(), GridView::Backend::OpenGL);

    auto* editor = window.findChild<ReferenceEditor*>();
    auto* action = window.findChild<QAction*>(QStringLiteral("editReferenceMode"));
    QVERIFY(editor && action);
    QCOMPARE(editor->reference()->objects.size(), std::size_t{3});  // room.json: walls, box, pole
    action->trigger();
    QVERIFY(editor->editing());
    QCOMPARE(view->tool(), static_cast<GridTool*>(editor->tool()));
    QVERIFY(editor->dock()->isVisible());

    // The box's first corner (3.2, 1.8) selected: its handle is filled red, a colour neither the
    // grey levels nor the green reference lines have.
    editor->model()->select(1, 0);
    settle();
    const QPoint corner = view->view().toPixel({3.2, 1.8}, view->size()).toPoint();
    QVERIFY(reddish(view->grabSurface().pixel(corner)));

    // Tape measurements: in cm, from the walls' corner (0, 0).
    editor->panel()->setEntryUnit(LengthUnit::Centimetre);
    editor->panel()->setDatum(0, 0);
    // A shelf near the top wall (clear of it: a click within 5 px of an edge selects that
    // object), snapped to the cell lines: three corners clicked, the pointer at the fourth.
    const auto pixel = [&](double x, double y) {
      return view->view().toPixel({x, y}, view->size()).toPoint();
    };
    // Pictures for the guide: the grid larger, the beams out of the way.
    if (auto* beams = window.findChild<QDockWidget*>(QStringLiteral("beamModelDock")))
      beams->hide();
    view->setOverlay(Overlay::Beams, false);
    view->setFocus();
    QTest::keyClick(view, Qt::Key_S);
    QVERIFY(editor->tool()->snapping());
    QTest::mouseClick(view, Qt::LeftButton, {}, pixel(0.6, 3.7));
    QTest::mouseClick(view, Qt::LeftButton, {}, pixel(2.2, 3.7));
    QTest::mouseClick(view, Qt::LeftButton, {}, pixel(2.2, 3.3));
    QTest::mouseMove(view, pixel(0.6, 3.3));
    QCOMPARE(editor->tool()->pendingCorners().size(), std::size_t{3});
    shoot(window, "reference-editor-drawing.png");

    QTest::mouseClick(view, Qt::LeftButton, {}, pixel(0.6, 3.3));
    QTest::keyClick(view, Qt::Key_C);
    QCOMPARE(editor->reference()->objects.size(), std::size_t{4});
    // Snapped to the 5 cm cells as typed numbers: exactly 0.6, 3.7, 2.2, 3.3.
    const std::vector<Eigen::Vector2d> shelf = {{0.6, 3.7}, {2.2, 3.7}, {2.2, 3.3}, {0.6, 3.3}};
    QCOMPARE(editor->reference()->objects[3].corners, shelf);
    QVERIFY(editor->reference()->objects[3].closed);
    QCOMPARE(view->scene().referenceLines.size(), std::size_t{4});  // the window shows it
    editor->model()->select(3, 2);
    shoot(window, "reference-editor-table.png");

    action->trigger();
    QVERIFY(!editor->editing());
    settle();
    QVERIFY(!reddish(view->grabSurface().pixel(pixel(2.2, 3.3))));
  }
};

QTEST_MAIN(TestGlReferenceEditor)
#include "tst_gl_reference_editor.moc"
