// SPDX-License-Identifier: GPL-3.0-or-later
#include "reference_editing.h"

#include <QAction>
#include <QDockWidget>
#include <QMenu>
#include <QMenuBar>
#include <QStatusBar>
#include <QUndoStack>
#include <memory>

#include "document.h"
#include "grid_view.h"
#include "main_window.h"
#include "reference_editor.h"

namespace sg::app {

ui::ReferenceEditor* installReferenceEditor(MainWindow* window) {
  Document* document = window->document();
  auto* editor = new ui::ReferenceEditor(document->undoStack(), window->gridView(), window);
  editor->adoptReference(document->reference(), document->referencePath());

  // The editor's own command is the undo step; the Document only takes the result. While it
  // does, its referenceChanged must not hand the same map back to the editor mid-edit.
  auto syncing = std::make_shared<bool>(false);
  QObject::connect(editor, &ui::ReferenceEditor::referenceEdited, document,
                   [document, editor, syncing] {
                     *syncing = true;
                     document->applyReference(editor->reference(), editor->path(), true);
                     *syncing = false;
                   });
  QObject::connect(document, &Document::referenceChanged, editor, [document, editor, syncing] {
    if (!*syncing) editor->adoptReference(document->reference(), document->referencePath());
  });

  QMenu* edit = window->menuBar()->findChild<QMenu*>(QStringLiteral("editMenu"));
  if (edit) {
    edit->addSeparator();
    edit->addAction(editor->editModeAction());
    edit->addAction(editor->newAction());
    edit->addAction(editor->openAction());
    edit->addAction(editor->saveAction());
    edit->addAction(editor->saveAsAction());
    edit->addAction(editor->dock()->toggleViewAction());
  }
  // The edit-mode key works while the menu bar is hidden or the dock is closed.
  window->addAction(editor->editModeAction());

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
