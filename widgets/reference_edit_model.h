// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The reference map being edited. Every edit is a QUndoCommand pushed on the undo stack it is
// given (the document owns the stack; this model never does), each edit one step, and the moves of
// one corner drag merge into one step (as Tiled's ChangePolygon). A command keeps the whole object
// before and after, so undo and redo restore the corner lists exactly.
//
// The map keeps its own unit (a file in mm stays in mm); positions given in world metres are
// converted by worldToUnit().

#include <QObject>
#include <QString>
#include <optional>

#include "sonargrid/reference/reference_map.h"

class QUndoCommand;
class QUndoStack;

namespace sg::ui {

class ReferenceEditModel : public QObject {
  Q_OBJECT

 public:
  explicit ReferenceEditModel(QObject* parent = nullptr);

  // Not owned. Without a stack, edits apply at once and cannot be undone.
  void setUndoStack(QUndoStack* stack) { stack_ = stack; }
  QUndoStack* undoStack() const { return stack_; }

  const std::optional<ReferenceMap>& reference() const { return reference_; }
  bool hasReference() const { return reference_.has_value(); }
  // The map, or an empty one in metres when there is none.
  const ReferenceMap& map() const;
  // Where the reference was read from or last saved to (empty: never saved).
  const QString& path() const { return path_; }
  // After a save: the file the reference now lives in (not an edit).
  void setPath(const QString& path);
  int objectCount() const { return static_cast<int>(map().objects.size()); }
  const ReferenceObject* object(int index) const;
  // Index of the object called `name`, or -1.
  int findObject(const std::string& name) const;
  // "object N" with the smallest N not yet used.
  std::string freeName() const;

  // A world position (metres) in the map's unit, and back.
  Eigen::Vector2d worldToUnit(const Position& world) const;
  Position unitToWorld(const Eigen::Vector2d& corner) const;

  // The edits, each one undo step named by `text` on the stack.
  // Replaces the whole reference (opening or importing a file, New): undoable like the rest.
  void replaceReference(std::optional<ReferenceMap> reference, const QString& path,
                        const QString& text);
  // Appends `object` (a reference in metres is started when there is none); returns its index.
  int addObject(ReferenceObject object);
  void removeObject(int index);
  // False (nothing changes) when the name is empty or another object has it.
  bool renameObject(int index, const std::string& name);
  // False when the object has too few corners to be closed (3).
  bool setClosed(int index, bool closed);
  // Moves a corner (in the map's unit). Moves with the same non-zero `dragId` on the same corner
  // merge into one step: the drag from press to release.
  void moveCorner(int index, int corner, const Eigen::Vector2d& position, int dragId = 0);
  void insertCorner(int index, int at, const Eigen::Vector2d& position);
  // Removes a corner. A closed object left with 2 corners becomes open; an object left with fewer
  // than 2 is removed (one step either way).
  void removeCorner(int index, int corner);
  // A new drag id for moveCorner.
  int beginDrag() { return ++lastDragId_; }

  // Selection: which object and corner the view and the dock show (not an edit, not undone).
  int selectedObject() const { return selectedObject_; }
  int selectedCorner() const { return selectedCorner_; }
  void select(int object, int corner = -1);

  // Used by the commands.
  void putObject(int index, const std::optional<ReferenceObject>& from,
                 const std::optional<ReferenceObject>& to);
  void putReference(const std::optional<ReferenceMap>& reference, const QString& path);

 signals:
  // The reference changed: `object` is the one whose corners, name or flag changed, -1 when
  // objects were added or removed or the whole reference was replaced.
  void changed(int object);
  void selectionChanged();

 private:
  void push(QUndoCommand* command);
  void replaceObject(int index, ReferenceObject after, const QString& text, int mergeId = 0);
  void clampSelection();

  QUndoStack* stack_ = nullptr;
  std::optional<ReferenceMap> reference_;
  QString path_;
  int lastDragId_ = 0;
  int selectedObject_ = -1;
  int selectedCorner_ = -1;
};

}  // namespace sg::ui
