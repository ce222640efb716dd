// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The reference-map editor: an edit mode of the grid view (ReferenceEditTool) and a dock
// (ReferenceEditorPanel) over one ReferenceEditModel. The window (later the Document) owns the
// undo stack and hands it in; every edit is one step on it. The editor reads every reference
// format the core reads (sonargrid JSON, ArMap .map, ROS map .yaml) and saves sonargrid JSON
// through the atomic file helper.

#include <QObject>
#include <QPointer>
#include <QString>
#include <optional>

#include "sonargrid/reference/reference_map.h"

class QAction;
class QDockWidget;
class QUndoStack;
class QWidget;

namespace sg::ui {

class GridView;
class ReferenceEditModel;
class ReferenceEditTool;
class ReferenceEditorPanel;

class ReferenceEditor : public QObject {
  Q_OBJECT

 public:
  // `stack` is not owned (may be null: edits then cannot be undone); `view` gets the edit tool
  // while edit mode is on. The dock is parented to `parent`.
  ReferenceEditor(QUndoStack* stack, GridView* view, QWidget* parent = nullptr);
  ~ReferenceEditor() override;

  void setUndoStack(QUndoStack* stack);
  // Makes `reference` (read from `path`; empty when it has no file) the one edited: one undo step
  // ("Open Reference"), so the stack never holds edits of a map that is gone.
  void setReference(std::optional<sg::ReferenceMap> reference, const QString& path);
  // Takes `reference` without an undo step and without referenceEdited: for an owner (the
  // Document) whose own command or restore changed the reference. The editor's commands already
  // on the stack stay valid, since undo reaches them only after undoing that change.
  void adoptReference(std::optional<sg::ReferenceMap> reference, const QString& path);
  const std::optional<sg::ReferenceMap>& reference() const;
  QString path() const;

  // Reads any reference format (by extension and content, as `sonargrid-cli score` does) and
  // makes it the one edited. False, with `error` naming the file and line, when it cannot.
  bool open(const QString& path, QString* error = nullptr);
  // Writes sonargrid-reference JSON atomically in the map's unit. False, with `error` naming the
  // file or the object at fault, when it cannot (the reference is then unchanged).
  bool save(const QString& path, QString* error = nullptr);

  // Checkable, shortcut E: puts the edit tool on the grid view and shows the dock.
  QAction* editModeAction() const { return editMode_; }
  bool editing() const;
  void setEditing(bool on);
  // File actions with their dialogs (the dock's buttons trigger them too).
  QAction* newAction() const { return new_; }
  QAction* openAction() const { return open_; }
  QAction* saveAction() const { return save_; }
  QAction* saveAsAction() const { return saveAs_; }

  QDockWidget* dock() const { return dock_; }
  ReferenceEditModel* model() const { return model_; }
  ReferenceEditTool* tool() const { return tool_; }
  ReferenceEditorPanel* panel() const { return panel_; }

 signals:
  // The reference changed (an edit, undo, redo, open, new): whoever draws or scores it reads
  // reference() again.
  void referenceEdited();
  // For the status bar.
  void message(const QString& text);

 private:
  void openDialog();
  bool saveDialog(bool askPath);
  void report(const QString& title, const QString& text);

  QPointer<GridView> view_;  // a window may delete its view before this editor
  QWidget* parent_;
  ReferenceEditModel* model_;
  ReferenceEditTool* tool_;
  ReferenceEditorPanel* panel_;
  QDockWidget* dock_;
  QAction *editMode_, *new_, *open_, *save_, *saveAs_;
  bool adopting_ = false;
};

}  // namespace sg::ui
