// SPDX-License-Identifier: GPL-3.0-or-later
#include "reference_edit_model.h"

#include <QUndoCommand>
#include <QUndoStack>
#include <algorithm>
#include <set>

namespace sg::ui {
namespace {

// Merge ids of the commands (QUndoCommand::id); only a corner drag merges.
constexpr int kDragCornerId = 0x5e0f;

// One object before and after: absent before is an insertion, absent after a removal.
class ObjectCommand : public QUndoCommand {
 public:
  ObjectCommand(ReferenceEditModel* model, int index, std::optional<ReferenceObject> before,
                std::optional<ReferenceObject> after, const QString& text, int dragId)
      : QUndoCommand(text),
        model_(model),
        index_(index),
        before_(std::move(before)),
        after_(std::move(after)),
        dragId_(dragId) {}

  void redo() override { model_->putObject(index_, before_, after_); }
  void undo() override { model_->putObject(index_, after_, before_); }
  int id() const override { return dragId_ != 0 ? kDragCornerId : -1; }
  bool mergeWith(const QUndoCommand* other) override {
    const auto* o = dynamic_cast<const ObjectCommand*>(other);
    if (!o || o->dragId_ != dragId_ || o->index_ != index_) return false;
    after_ = o->after_;
    // A drag back to where it started leaves nothing to undo.
    if (before_ && after_ && before_->corners == after_->corners) setObsolete(true);
    return true;
  }

 private:
  ReferenceEditModel* model_;
  int index_;
  std::optional<ReferenceObject> before_, after_;
  int dragId_;
};

class ReferenceCommand : public QUndoCommand {
 public:
  ReferenceCommand(ReferenceEditModel* model, std::optional<ReferenceMap> before,
                   QString beforePath, std::optional<ReferenceMap> after, QString afterPath,
                   const QString& text)
      : QUndoCommand(text),
        model_(model),
        before_(std::move(before)),
        after_(std::move(after)),
        beforePath_(std::move(beforePath)),
        afterPath_(std::move(afterPath)) {}
  void redo() override { model_->putReference(after_, afterPath_); }
  void undo() override { model_->putReference(before_, beforePath_); }

 private:
  ReferenceEditModel* model_;
  std::optional<ReferenceMap> before_, after_;
  QString beforePath_, afterPath_;
};

const ReferenceMap& emptyMap() {
  static const ReferenceMap empty;
  return empty;
}

}  // namespace

ReferenceEditModel::ReferenceEditModel(QObject* parent) : QObject(parent) {}

const ReferenceMap& ReferenceEditModel::map() const {
  return reference_ ? *reference_ : emptyMap();
}

void ReferenceEditModel::setPath(const QString& path) {
  path_ = path;
}

const ReferenceObject* ReferenceEditModel::object(int index) const {
  if (index < 0 || index >= objectCount()) return nullptr;
  return &map().objects[static_cast<std::size_t>(index)];
}

int ReferenceEditModel::findObject(const std::string& name) const {
  for (int i = 0; i < objectCount(); ++i)
    if (map().objects[static_cast<std::size_t>(i)].name == name) return i;
  return -1;
}

std::string ReferenceEditModel::freeName() const {
  std::set<std::string> used;
  for (const ReferenceObject& o : map().objects) used.insert(o.name);
  for (int n = 1;; ++n) {
    std::string name = "object " + std::to_string(n);
    if (!used.count(name)) return name;
  }
}

Eigen::Vector2d ReferenceEditModel::worldToUnit(const Position& world) const {
  return world / map().metresPerUnit();
}

Position ReferenceEditModel::unitToWorld(const Eigen::Vector2d& corner) const {
  return corner * map().metresPerUnit();
}

void ReferenceEditModel::push(QUndoCommand* command) {
  if (stack_) {
    stack_->push(command);
  } else {
    command->redo();
    delete command;
  }
}

void ReferenceEditModel::replaceReference(std::optional<ReferenceMap> reference,
                                          const QString& path, const QString& text) {
  push(new ReferenceCommand(this, reference_, path_, std::move(reference), path, text));
}

int ReferenceEditModel::addObject(ReferenceObject object) {
  if (!reference_) {
    ReferenceMap map;  // a new reference is in metres (docs/metrics.md, "Reference maps")
    map.objects.push_back(std::move(object));
    replaceReference(std::move(map), path_, tr("Add Object"));
    select(0);
    return 0;
  }
  const int index = objectCount();
  push(new ObjectCommand(this, index, std::nullopt, std::move(object), tr("Add Object"), 0));
  select(index);
  return index;
}

void ReferenceEditModel::removeObject(int index) {
  const ReferenceObject* o = object(index);
  if (!o) return;
  push(new ObjectCommand(this, index, *o, std::nullopt, tr("Delete Object"), 0));
}

void ReferenceEditModel::replaceObject(int index, ReferenceObject after, const QString& text,
                                       int mergeId) {
  const ReferenceObject* o = object(index);
  if (!o) return;
  push(new ObjectCommand(this, index, *o, std::move(after), text, mergeId));
}

bool ReferenceEditModel::renameObject(int index, const std::string& name) {
  const ReferenceObject* o = object(index);
  if (!o || name.empty() || o->name == name || findObject(name) >= 0) return false;
  ReferenceObject after = *o;
  after.name = name;
  replaceObject(index, std::move(after), tr("Rename Object"));
  return true;
}

bool ReferenceEditModel::setClosed(int index, bool closed) {
  const ReferenceObject* o = object(index);
  if (!o || o->circle || o->closed == closed) return false;
  if (closed && o->corners.size() < 3) return false;
  ReferenceObject after = *o;
  after.closed = closed;
  replaceObject(index, std::move(after), closed ? tr("Close Object") : tr("Open Object"));
  return true;
}

void ReferenceEditModel::moveCorner(int index, int corner, const Eigen::Vector2d& position,
                                    int dragId) {
  const ReferenceObject* o = object(index);
  if (!o || corner < 0 || corner >= static_cast<int>(o->corners.size())) return;
  if (o->corners[static_cast<std::size_t>(corner)] == position) return;
  ReferenceObject after = *o;
  after.corners[static_cast<std::size_t>(corner)] = position;
  after.circle.reset();  // its polygon is edited now: it is saved as corners
  replaceObject(index, std::move(after), tr("Move Corner"), dragId);
}

void ReferenceEditModel::insertCorner(int index, int at, const Eigen::Vector2d& position) {
  const ReferenceObject* o = object(index);
  if (!o || at < 0 || at > static_cast<int>(o->corners.size())) return;
  ReferenceObject after = *o;
  after.corners.insert(after.corners.begin() + at, position);
  after.circle.reset();
  replaceObject(index, std::move(after), tr("Insert Corner"));
  select(index, at);
}

void ReferenceEditModel::removeCorner(int index, int corner) {
  const ReferenceObject* o = object(index);
  if (!o || corner < 0 || corner >= static_cast<int>(o->corners.size())) return;
  if (o->corners.size() <= 2) {
    push(new ObjectCommand(this, index, *o, std::nullopt, tr("Delete Corner"), 0));
    return;
  }
  ReferenceObject after = *o;
  after.corners.erase(after.corners.begin() + corner);
  after.circle.reset();
  if (after.corners.size() < 3) after.closed = false;
  replaceObject(index, std::move(after), tr("Delete Corner"));
  select(index, std::min(corner, static_cast<int>(after.corners.size()) - 1));
}

void ReferenceEditModel::select(int object, int corner) {
  if (object == selectedObject_ && corner == selectedCorner_) return;
  selectedObject_ = object;
  selectedCorner_ = corner;
  clampSelection();
  emit selectionChanged();
}

void ReferenceEditModel::clampSelection() {
  if (selectedObject_ < 0 || selectedObject_ >= objectCount()) {
    selectedObject_ = -1;
    selectedCorner_ = -1;
    return;
  }
  const int corners = static_cast<int>(object(selectedObject_)->corners.size());
  if (selectedCorner_ >= corners) selectedCorner_ = corners - 1;
}

void ReferenceEditModel::putObject(int index, const std::optional<ReferenceObject>& from,
                                   const std::optional<ReferenceObject>& to) {
  if (!reference_) return;
  auto& objects = reference_->objects;
  // Only a stack shared with commands that replace the map behind this model's back could get
  // here out of range; ignoring the step is better than a crash.
  const auto size = static_cast<int>(objects.size());
  if (index < 0 || index > size || (from && index == size)) return;
  const auto at = objects.begin() + index;
  if (!from && to) {
    objects.insert(at, *to);
  } else if (from && !to) {
    objects.erase(at);
  } else if (to) {
    *at = *to;
  }
  const int before = selectedObject_, beforeCorner = selectedCorner_;
  clampSelection();
  emit changed(from && to ? index : -1);
  if (before != selectedObject_ || beforeCorner != selectedCorner_) emit selectionChanged();
}

void ReferenceEditModel::putReference(const std::optional<ReferenceMap>& reference,
                                      const QString& path) {
  reference_ = reference;
  path_ = path;
  const int before = selectedObject_;
  clampSelection();
  emit changed(-1);
  if (before != selectedObject_) emit selectionChanged();
}

}  // namespace sg::ui
