// SPDX-License-Identifier: GPL-3.0-or-later
#include "document.h"

#include <QUndoStack>
#include <algorithm>

#include "document_commands.h"
#include "sonargrid/io/start_pose.h"

namespace sg::app {

Document::Document(QObject* parent) : QObject(parent), undo_(new QUndoStack(this)) {
  connect(undo_, &QUndoStack::cleanChanged, this, [this] { setDirty(dirty_); });
}

Document::~Document() = default;

void Document::restore(const ProjectState& state, bool modified) {
  endDrag();
  state_ = state;
  state_.cellSize = std::clamp(state_.cellSize, kMinCellSize, kMaxCellSize);
  referenceLog_ = state_.reference ? state_.logPath : QString();
  placeSource();  // the state's start pose
  undo_->clear();
  setDirty(modified);
  emit logChanged();
  emit secondLogChanged();
  emit referenceChanged();
  emit settingsChanged();
  emit cellSizeChanged(state_.cellSize);
  emit overlaysChanged(state_.overlays);
  emit viewChanged();
  emit pinnedRowsChanged();
  emit sweepChanged();
}

void Document::setLog(const QString& path, std::shared_ptr<const Dataset> dataset) {
  setLog(path, dataset ? std::make_shared<const ScanSource>(std::move(dataset)) : nullptr);
}

void Document::setLog(const QString& path, std::shared_ptr<const ScanSource> source,
                      const LogReading& reading) {
  const bool changed = path != state_.logPath || reading != state_.logReading;
  state_.logPath = path;
  state_.logReading = reading;
  loadedSource_ = std::move(source);
  placeSource();
  if (changed && !projectPath_.isEmpty()) setDirty(true);
  emit logChanged();
}

void Document::setSecondLog(const QString& path, std::shared_ptr<const Dataset> dataset) {
  const bool changed = path != state_.secondLogPath;
  state_.secondLogPath = path;
  secondDataset_ = std::move(dataset);
  if (changed) setDirty(true);
  emit secondLogChanged();
}

void Document::setReference(std::optional<ReferenceMap> map, QString path) {
  const bool modified = map.has_value();
  auto* command = new SetReferenceCommand(
      this, {state_.reference, state_.referencePath, state_.referenceModified},
      {std::move(map), std::move(path), modified},
      modified ? tr("Edit Reference Map") : tr("Close Reference Map"));
  endDrag();
  undo_->push(command);
}

void Document::setReferenceFromFile(ReferenceMap map, QString path) {
  auto* command = new SetReferenceCommand(
      this, {state_.reference, state_.referencePath, state_.referenceModified},
      {std::move(map), std::move(path), false}, tr("Open Reference Map"));
  endDrag();
  undo_->push(command);
}

void Document::setMapperSettings(const MapperSettings& settings, bool drag) {
  if (settings == state_.settings) return;
  undo_->push(new SetSettingsCommand(this, state_.settings, settings, dragFor(drag)));
}

void Document::setCellSize(double metres, bool drag) {
  metres = std::clamp(metres, kMinCellSize, kMaxCellSize);
  if (metres == state_.cellSize) return;
  undo_->push(new SetCellSizeCommand(this, state_.cellSize, metres, dragFor(drag)));
}

void Document::endDrag() {
  dragOpen_ = false;
}

quint64 Document::dragFor(bool drag) {
  if (!drag) {
    dragOpen_ = false;
    return 0;
  }
  if (!dragOpen_) {
    dragId_ = nextDrag_++;
    dragOpen_ = true;
  }
  return dragId_;
}

void Document::adjustMapperSettings(const MapperSettings& settings) {
  applySettings(settings);
}

void Document::setOverlays(ui::Overlays overlays) {
  if (overlays == state_.overlays) return;
  state_.overlays = overlays;
  setDirty(true);
  emit overlaysChanged(overlays);
}

void Document::setView(const ui::ViewTransform& view) {
  if (state_.view == view) return;
  state_.view = view;
  emit viewChanged();
}

void Document::setPinnedRows(std::vector<PinnedRow> rows, const QString& text) {
  if (rows == state_.pinnedRows) return;
  endDrag();
  undo_->push(new SetPinnedRowsCommand(this, state_.pinnedRows, std::move(rows),
                                       text.isEmpty() ? tr("Change Pinned Rows") : text));
}

void Document::pinRow(PinnedRow row) {
  std::vector<PinnedRow> rows = state_.pinnedRows;
  const QString text = tr("Pin %1").arg(row.label);
  rows.push_back(std::move(row));
  setPinnedRows(std::move(rows), text);
}

void Document::removePinnedRow(std::size_t index) {
  if (index >= state_.pinnedRows.size()) return;
  std::vector<PinnedRow> rows = state_.pinnedRows;
  const QString text = tr("Unpin %1").arg(rows[index].label);
  rows.erase(rows.begin() + static_cast<std::ptrdiff_t>(index));
  setPinnedRows(std::move(rows), text);
}

void Document::setSweep(const SweepPlan& sweep) {
  if (sweep == state_.sweep) return;
  endDrag();
  undo_->push(new SetSweepCommand(this, state_.sweep, sweep));
}

void Document::setStartPose(std::optional<Pose2D> pose) {
  if (pose == state_.logReading.startPose) return;
  endDrag();
  undo_->push(new SetStartPoseCommand(this, state_.logReading.startPose, pose));
}

void Document::placeSource() {
  source_ = loadedSource_;
  const std::optional<Pose2D>& start = state_.logReading.startPose;
  if (start && loadedSource_ && loadedSource_->complete()) {
    Dataset placed = *loadedSource_->view();
    placeOdometryAt(placed, *start);
    source_ = std::make_shared<const ScanSource>(std::move(placed));
  }
  dataset_ = source_ ? source_->view() : nullptr;
}

void Document::setProjectPath(const QString& path) {
  if (path == projectPath_) return;
  projectPath_ = path;
  emit projectPathChanged(path);
}

bool Document::isModified() const {
  return dirty_ || !undo_->isClean();
}

void Document::markSaved() {
  endDrag();
  undo_->setClean();
  setDirty(false);
}

void Document::startNewHistory() {
  // What was unsaved stays unsaved (settings carry over to the next log, and a session's
  // command-line settings are edits): only the steps back are gone.
  const bool modified = isModified();
  endDrag();
  undo_->clear();
  setDirty(modified);
}

void Document::applySettings(const MapperSettings& settings) {
  state_.settings = settings;
  emit settingsChanged();
}

void Document::applyCellSize(double metres) {
  state_.cellSize = metres;
  emit cellSizeChanged(metres);
}

void Document::applyReference(const std::optional<ReferenceMap>& map, const QString& path,
                              bool modified) {
  state_.reference = map;
  state_.referencePath = path;
  state_.referenceModified = map.has_value() && modified;
  if (!map)
    referenceLog_.clear();
  else if (referenceLog_.isEmpty())
    referenceLog_ = state_.logPath;
  emit referenceChanged();
}

void Document::applyPinnedRows(const std::vector<PinnedRow>& rows) {
  state_.pinnedRows = rows;
  emit pinnedRowsChanged();
}

void Document::applySweep(const SweepPlan& sweep) {
  state_.sweep = sweep;
  emit sweepChanged();
}

void Document::applyStartPose(const std::optional<Pose2D>& pose) {
  state_.logReading.startPose = pose;
  placeSource();
  emit startPoseChanged();
  emit logChanged();
}

void Document::setDirty(bool dirty) {
  dirty_ = dirty;
  const bool modified = isModified();
  if (modified == lastModified_) return;
  lastModified_ = modified;
  emit modifiedChanged(modified);
}

}  // namespace sg::app
