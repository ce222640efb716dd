// SPDX-License-Identifier: GPL-3.0-or-later
#include "document_commands.h"

#include <QCoreApplication>

#include "document.h"

namespace sg::app {
namespace {

QString tr(const char* text) {
  return QCoreApplication::translate("sg::app::Document", text);
}

// What a settings change is called in Edit ▸ Undo: the one parameter it moves, else the pair.
QString settingsText(const MapperSettings& before, const MapperSettings& after) {
  if (before.model != after.model || before.rule != after.rule) return tr("Change Model and Rule");
  if (before.pose != after.pose) return tr("Change Pose");
  for (const auto& [name, value] : after.parameters.values())
    if (!before.parameters.has(name) || before.parameters.get(name) != value)
      return tr("Change %1").arg(QString::fromStdString(name));
  return tr("Change Parameters");
}

}  // namespace

SetSettingsCommand::SetSettingsCommand(Document* document, MapperSettings before,
                                       MapperSettings after, quint64 drag)
    : document_(document), before_(std::move(before)), after_(std::move(after)), drag_(drag) {
  setText(settingsText(before_, after_));
}

void SetSettingsCommand::undo() {
  document_->applySettings(before_);
}

void SetSettingsCommand::redo() {
  document_->applySettings(after_);
}

bool SetSettingsCommand::mergeWith(const QUndoCommand* other) {
  const auto* next = static_cast<const SetSettingsCommand*>(other);
  if (drag_ == 0 || next->drag_ != drag_) return false;
  after_ = next->after_;
  setText(settingsText(before_, after_));
  // A drag back to where it started leaves no step (QUndoStack drops an obsolete command).
  setObsolete(before_ == after_);
  return true;
}

SetCellSizeCommand::SetCellSizeCommand(Document* document, double before, double after,
                                       quint64 drag)
    : document_(document), before_(before), after_(after), drag_(drag) {
  setText(tr("Change Cell Size"));
}

void SetCellSizeCommand::undo() {
  document_->applyCellSize(before_);
}

void SetCellSizeCommand::redo() {
  document_->applyCellSize(after_);
}

bool SetCellSizeCommand::mergeWith(const QUndoCommand* other) {
  const auto* next = static_cast<const SetCellSizeCommand*>(other);
  if (drag_ == 0 || next->drag_ != drag_) return false;
  after_ = next->after_;
  setObsolete(before_ == after_);
  return true;
}

SetReferenceCommand::SetReferenceCommand(Document* document, ReferenceValue before,
                                         ReferenceValue after, const QString& text)
    : document_(document), before_(std::move(before)), after_(std::move(after)) {
  setText(text);
}

void SetReferenceCommand::undo() {
  document_->applyReference(before_.map, before_.path, before_.modified);
}

void SetReferenceCommand::redo() {
  document_->applyReference(after_.map, after_.path, after_.modified);
}

SetPinnedRowsCommand::SetPinnedRowsCommand(Document* document, std::vector<PinnedRow> before,
                                           std::vector<PinnedRow> after, const QString& text)
    : document_(document), before_(std::move(before)), after_(std::move(after)) {
  setText(text);
}

void SetPinnedRowsCommand::undo() {
  document_->applyPinnedRows(before_);
}

void SetPinnedRowsCommand::redo() {
  document_->applyPinnedRows(after_);
}

SetSweepCommand::SetSweepCommand(Document* document, SweepPlan before, SweepPlan after)
    : document_(document), before_(std::move(before)), after_(std::move(after)) {
  setText(tr("Change Sweep Settings"));
}

void SetSweepCommand::undo() {
  document_->applySweep(before_);
}

void SetSweepCommand::redo() {
  document_->applySweep(after_);
}

SetStartPoseCommand::SetStartPoseCommand(Document* document, std::optional<Pose2D> before,
                                         std::optional<Pose2D> after)
    : document_(document), before_(before), after_(after) {
  setText(after ? tr("Place Start Pose") : tr("Clear Start Pose"));
}

void SetStartPoseCommand::undo() {
  document_->applyStartPose(before_);
}

void SetStartPoseCommand::redo() {
  document_->applyStartPose(after_);
}

}  // namespace sg::app
