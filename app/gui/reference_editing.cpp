// SPDX-License-Identifier: GPL-3.0-or-later
#include "reference_editing.h"

#include <QAction>
#include <QDockWidget>
#include <QMainWindow>
#include <QMenu>
#include <QMenuBar>
#include <QStatusBar>
#include <QUndoStack>

#include "grid_view.h"
#include "reference_editor.h"

namespace sg::app {

ui::ReferenceEditor* installReferenceEditor(QMainWindow* window, ui::GridView* view) {
  auto* stack = new QUndoStack(window);
  stack->setObjectName(QStringLiteral("undoStack"));
  auto* editor = new ui::ReferenceEditor(stack, view, window);

  auto* edit = new QMenu(QMainWindow::tr("&Edit"), window);
  edit->setObjectName(QStringLiteral("editMenu"));
  QAction* undo = stack->createUndoAction(edit, QMainWindow::tr("&Undo"));
  undo->setShortcuts(QKeySequence::Undo);
  QAction* redo = stack->createRedoAction(edit, QMainWindow::tr("&Redo"));
  redo->setShortcuts(QKeySequence::Redo);
  edit->addAction(undo);
  edit->addAction(redo);
  edit->addSeparator();
  edit->addAction(editor->editModeAction());
  edit->addAction(editor->newAction());
  edit->addAction(editor->openAction());
  edit->addAction(editor->saveAction());
  edit->addAction(editor->saveAsAction());
  edit->addAction(editor->dock()->toggleViewAction());
  // After File, before View, where users look for it.
  const QList<QAction*> menus = window->menuBar()->actions();
  window->menuBar()->insertMenu(menus.value(1), edit);
  // Shortcuts work while the menu bar is hidden or the dock is closed.
  window->addActions({undo, redo, editor->editModeAction()});

  window->addDockWidget(Qt::RightDockWidgetArea, editor->dock());
  if (auto* parameters = window->findChild<QDockWidget*>(QStringLiteral("parametersDock")))
    window->tabifyDockWidget(parameters, editor->dock());
  editor->dock()->hide();  // shown by edit mode
  QObject::connect(editor, &ui::ReferenceEditor::message, window->statusBar(),
                   [window](const QString& text) {
                     if (text.isEmpty())
                       window->statusBar()->clearMessage();
                     else
                       window->statusBar()->showMessage(text, 8000);
                   });
  return editor;
}

}  // namespace sg::app
