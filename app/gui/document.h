// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The document (as Tiled's MapDocument): what the user works on — the log(s), the reference map,
// the mapper settings, the cell size, the overlays, the view, pinned comparison rows and the sweep
// settings — with one QUndoStack for its edits. Every change emits a signal naming what changed, so
// each view redraws only that. Typed preferences (preferences.h) are not part of it.
//
// Undoable: mapper settings, cell size, reference, pinned rows, sweep settings. A run of changes
// marked as one drag merges into one undo step until endDrag(). Not undoable: the log (loading is
// not an edit), overlays (a view toggle, but saved, so it marks the document modified) and the view
// (saved with the project, never marks it modified).

#include <QObject>
#include <QString>
#include <memory>
#include <optional>

#include "project.h"
#include "sonargrid/data/dataset.h"
#include "sonargrid/engine/scan_source.h"

class QUndoStack;

namespace sg::app {

class Document : public QObject {
  Q_OBJECT

 public:
  explicit Document(QObject* parent = nullptr);
  ~Document() override;

  // Every edit command goes here; other editors (the reference editor) push their own commands.
  QUndoStack* undoStack() const { return undo_; }

  // The whole saved state (what a project file holds).
  const ProjectState& state() const { return state_; }
  // Replaces every part at once (opening a project, recovering an autosave): no undo step, the
  // undo history is cleared, the document is clean unless `modified`. Emits every change signal.
  // The datasets are left as they are (the caller loads the logs the state names).
  void restore(const ProjectState& state, bool modified = false);

  // --- logs ---
  const QString& logPath() const { return state_.logPath; }
  // The log's scans (scan_source.h: the one road for scans) and their complete view.
  const std::shared_ptr<const ScanSource>& source() const { return source_; }
  const std::shared_ptr<const Dataset>& dataset() const { return dataset_; }
  // A loaded log. Marks a saved project modified (its log changed); an untitled one is not
  // (nothing of the user's is lost by not saving it).
  // `reading`: how it was read (a CSV log's columns, a bag's topics), which a project stores.
  void setLog(const QString& path, std::shared_ptr<const ScanSource> source,
              const LogReading& reading = {});
  const LogReading& logReading() const { return state_.logReading; }
  // A log in memory: its complete source.
  void setLog(const QString& path, std::shared_ptr<const Dataset> dataset);
  // Undoable. The robot's pose at the log's first scan in the reference's frame (nullopt: the
  // odometry as logged), kept in logReading(): source() is then the loaded log with its odometry
  // placed there (sonargrid/io/start_pose.h), as `--start-pose` reads it. A live log is not
  // placed.
  void setStartPose(std::optional<Pose2D> pose);
  const std::optional<Pose2D>& startPose() const { return state_.logReading.startPose; }
  const QString& secondLogPath() const { return state_.secondLogPath; }
  const std::shared_ptr<const Dataset>& secondDataset() const { return secondDataset_; }
  void setSecondLog(const QString& path, std::shared_ptr<const Dataset> dataset);

  // --- reference map ---
  const std::optional<ReferenceMap>& reference() const { return state_.reference; }
  const QString& referencePath() const { return state_.referencePath; }
  // True when the reference differs from its file (edits not saved, or no file): the project then
  // holds it inline.
  bool referenceModified() const { return state_.referenceModified; }
  // Undoable. `map` as edited (nullopt: no reference); `path` its file, if any. The reference is
  // taken as differing from its file: the editor calls this for every edit.
  void setReference(std::optional<ReferenceMap> map, QString path);
  // Undoable. A reference just read from (or written to) `path`: equal to its file.
  void setReferenceFromFile(ReferenceMap map, QString path);
  // The log the reference was drawn for (empty: none yet). A new log clears a reference drawn for
  // another log (MainWindow::adoptLog).
  const QString& referenceLog() const { return referenceLog_; }
  void setReferenceLog(const QString& path) { referenceLog_ = path; }

  // --- mapper settings and cell size (undoable) ---
  const MapperSettings& mapperSettings() const { return state_.settings; }
  // `drag`: one step of a continuous gesture (a slider dragged); such steps merge into one undo
  // step until endDrag(). Equal settings push nothing.
  void setMapperSettings(const MapperSettings& settings, bool drag = false);
  double cellSize() const { return state_.cellSize; }
  // Clamped to [kMinCellSize, kMaxCellSize].
  void setCellSize(double metres, bool drag = false);
  // Ends the running drag: the next change is a new undo step.
  void endDrag();
  // Without undo (adjustments the app makes, not the user: a truth pose on a log without truth).
  void adjustMapperSettings(const MapperSettings& settings);

  // --- overlays and view ---
  ui::Overlays overlays() const { return state_.overlays; }
  void setOverlays(ui::Overlays overlays);
  const std::optional<ui::ViewTransform>& view() const { return state_.view; }
  void setView(const ui::ViewTransform& view);

  // --- pinned comparison rows and sweep settings (undoable) ---
  const std::vector<PinnedRow>& pinnedRows() const { return state_.pinnedRows; }
  void setPinnedRows(std::vector<PinnedRow> rows, const QString& text = {});
  void pinRow(PinnedRow row);
  void removePinnedRow(std::size_t index);
  const SweepPlan& sweep() const { return state_.sweep; }
  void setSweep(const SweepPlan& sweep);

  // --- the file ---
  const QString& projectPath() const { return projectPath_; }
  void setProjectPath(const QString& path);
  bool isModified() const;
  // After a save: the undo stack's clean state, nothing modified outside it.
  void markSaved();
  // Opening another log makes a new document: its undo history starts empty, so that an undo
  // never brings back a part of the previous one (its reference over the new log). Unsaved
  // changes stay unsaved.
  void startNewHistory();

  // Used by the undo commands (document_commands.cpp): set a part and announce it, no undo step.
  void applySettings(const MapperSettings& settings);
  void applyCellSize(double metres);
  void applyReference(const std::optional<ReferenceMap>& map, const QString& path, bool modified);
  void applyPinnedRows(const std::vector<PinnedRow>& rows);
  void applySweep(const SweepPlan& sweep);
  void applyStartPose(const std::optional<Pose2D>& pose);
  // The drag the newest command belongs to (0: none): commands merge only within one drag.
  quint64 dragId() const { return dragId_; }

 signals:
  void logChanged();
  void secondLogChanged();
  void referenceChanged();
  void settingsChanged();
  void cellSizeChanged(double metres);
  void overlaysChanged(sg::ui::Overlays overlays);
  void viewChanged();
  void pinnedRowsChanged();
  void sweepChanged();
  // The odometry was placed at a new start pose: source() and dataset() are new (logChanged too).
  void startPoseChanged();
  void projectPathChanged(const QString& path);
  void modifiedChanged(bool modified);

 private:
  void setDirty(bool dirty);
  quint64 dragFor(bool drag);
  // source_ and dataset_ from loadedSource_ and the start pose.
  void placeSource();

  QUndoStack* undo_;
  ProjectState state_;
  std::shared_ptr<const ScanSource> loadedSource_;  // as read, before the start pose
  std::shared_ptr<const ScanSource> source_;
  std::shared_ptr<const Dataset> dataset_;  // source_->view()
  std::shared_ptr<const Dataset> secondDataset_;
  QString referenceLog_;
  QString projectPath_;
  bool dirty_ = false;  // changes outside the undo stack (log, overlays)
  bool lastModified_ = false;
  quint64 dragId_ = 0;
  quint64 nextDrag_ = 1;
  bool dragOpen_ = false;
};

}  // namespace sg::app
