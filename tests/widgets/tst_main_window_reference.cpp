// SPDX-License-Identifier: GPL-3.0-or-later
// The reference editor in the window, offscreen: the Edit menu holds Undo, Redo and the edit-mode
// action (E); the reference the window draws follows every edit, undo and redo.

#include <QAction>
#include <QMenu>
#include <QMenuBar>
#include <QStandardPaths>
#include <QUndoStack>
#include <QtTest>

#include "document.h"
#include "grid_view.h"
#include "main_window.h"
#include "reference_edit_model.h"
#include "reference_editor.h"

using namespace sg;
using namespace sg::ui;

class TestMainWindowReference : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() {
    QStandardPaths::setTestModeEnabled(true);  // QSettings go to a scratch location
    QCoreApplication::setOrganizationName("SonarGridTests");
    QCoreApplication::setApplicationName("tst_main_window_reference");
  }

  void editMenuAndReferenceLinesFollowEdits() {
    app::MainWindow window(GridView::Backend::Raster);
    QMenu* edit = window.findChild<QMenu*>(QStringLiteral("editMenu"));
    QVERIFY(edit);
    QCOMPARE(window.menuBar()->actions().at(1)->menu(), edit);  // after File
    QStringList shortcuts;
    for (QAction* a : edit->actions()) shortcuts << a->shortcut().toString();
    QVERIFY2(shortcuts.contains(QKeySequence(QKeySequence::Undo).toString()) &&
                 shortcuts.contains(QKeySequence(QKeySequence::Redo).toString()) &&
                 shortcuts.contains(QStringLiteral("E")),
             qPrintable(shortcuts.join(", ")));

    QVERIFY(window.openReference(SONARGRID_DATASETS "/room/room.json", true));
    auto* editor = window.findChild<ReferenceEditor*>();
    QUndoStack* stack = window.document()->undoStack();
    QVERIFY(editor && stack);
    QCOMPARE(editor->reference()->objects.size(), std::size_t{3});
    QCOMPARE(window.gridView()->scene().referenceLines.size(), std::size_t{3});

    editor->editModeAction()->trigger();
    QCOMPARE(window.gridView()->tool() != nullptr, true);
    // The box (object 2) loses a corner: its line is drawn with 3 corners + the closing one.
    editor->model()->removeCorner(1, 0);
    QCOMPARE(window.gridView()->scene().referenceLines[1].size(), std::size_t{4});
    // The edit is the Document's: one step on its stack, an edited reference, unsaved changes.
    QCOMPARE(window.document()->reference()->objects[1].corners.size(), std::size_t{3});
    QVERIFY(window.document()->referenceModified());
    QVERIFY(window.document()->isModified());
    stack->undo();
    QCOMPARE(window.document()->reference()->objects[1].corners.size(), std::size_t{4});
    QCOMPARE(window.gridView()->scene().referenceLines[1].size(), std::size_t{5});
    QCOMPARE(window.gridView()->scene().referenceLines[1].front(), Position(3.2, 1.8));
    // Ctrl+Y redoes, as the user guide says, beside the platform's Redo keys (issue 49).
    QAction* redo = nullptr;
    for (QAction* a : edit->actions())
      if (a->shortcuts().contains(QKeySequence(Qt::CTRL | Qt::Key_Y))) redo = a;
    QVERIFY(redo);
    QVERIFY(redo->shortcuts().contains(QKeySequence(QKeySequence::Redo)));
    window.show();
    QVERIFY(QTest::qWaitForWindowActive(&window));
    QTest::keyClick(&window, Qt::Key_Y, Qt::ControlModifier);
    QCOMPARE(stack->index(), stack->count());
    QCOMPARE(window.gridView()->scene().referenceLines[1].size(), std::size_t{4});
    editor->editModeAction()->trigger();
    QVERIFY(!window.gridView()->tool());
  }
};

QTEST_MAIN(TestMainWindowReference)
#include "tst_main_window_reference.moc"
