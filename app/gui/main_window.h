// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The desktop app's window: wiring. The Document (document.h) holds what the user works on; the
// window connects its change signals to the grid view, the RemapController, the docks and the
// menus, and the user's gestures back to Document edits. The window never parses a file or
// evaluates a model: the core does (DESIGN.md, "Data flow"). Its parts live by responsibility in
// main_window_*.cpp (menus, docks, projects, exports), log_loader.cpp and help_dialogs.cpp.

#include <QMainWindow>
#include <QStringList>
#include <memory>
#include <optional>
#include <vector>

#include "grid_view.h"
#include "project.h"
#include "sonargrid/data/dataset.h"
#include "sonargrid/engine/mapper.h"
#include "sonargrid/engine/scan_source.h"
#include "sonargrid/io/log_options.h"
#include "sonargrid/reference/reference_map.h"

class QAction;
class QActionGroup;
class QMenu;
class QTimer;

namespace sg::ui {
class BeamModelView;
class CellInspector;
class CellPicker;
class ForwardRangeView;
class ParameterPanel;
class RemapController;
class Timeline;
}  // namespace sg::ui

namespace sg::app {

class Autosave;
class BeamDock;
class Document;
class LogLoader;
class MapDock;
class StatusReport;

class MainWindow : public QMainWindow {
  Q_OBJECT

 public:
  explicit MainWindow(ui::GridView::Backend backend = ui::GridView::Backend::Automatic,
                      QWidget* parent = nullptr);
  ~MainWindow() override;

  // Each returns false after telling the user (a message box naming file:line) what was wrong; the
  // previous document then stays loaded. `quiet` reports on stderr instead (screenshots, tests).
  // openLog loads on a worker thread: without `quiet` it returns true once the load has started
  // (a CSV file first asks for its columns in the CsvImportDialog, a ROS bag for its topics in the
  // BagImportDialog; false when the user cancels it); with `quiet` it waits for the load and
  // returns whether it succeeded (a bag then reads the topics it picks).
  bool openLog(const QString& path, bool quiet = false);
  // Starts loading `path` with `options` on a worker thread, cancelling a load still running. The
  // previous document stays shown until the new one is complete: loaded(), or loadFailed() /
  // loadCancelled() leaving it untouched. Progress shows in the status bar (Cancel button, Esc).
  void loadLog(const QString& path, const sg::LogOptions& options, bool quiet = false);
  // Abandons the running load at once (loadCancelled); the worker stops at its next block.
  void cancelLoad();
  bool loading() const;
  // Blocks (running the event loop) until no load is running; true when the last one loaded.
  // timeoutMs < 0 waits as long as the load takes.
  bool waitForLoad(int timeoutMs = -1);
  // Asks for a bag's topics (BagImportDialog) and loads it; false when the user cancels or the
  // bag cannot be inspected (the error is shown).
  bool importBag(const QString& path);
  // Asks for a CSV file's columns (CsvImportDialog) and loads it; false when the user cancels.
  bool importCsv(const QString& path);
  const std::shared_ptr<const sg::Dataset>& dataset() const;
  const QString& logPath() const;
  // Reads a reference map and makes it the document's (one undo step).
  bool openReference(const QString& path, bool quiet = false);
  bool hasReference() const;
  // Forgets the open log (a live robot's map takes its place); the reference map stays.
  void closeLog();

  // Model, rule, parameters and pose, as one undoable edit of the document: re-maps the log (not
  // when they equal the settings of the current map), and shows them in the menus, the title, the
  // parameter panel and the beam view. `ruleNamed`: the user named the rule (the command line),
  // so the parameter panel does not say that the rule changed with the model.
  void setMapperSettings(const sg::MapperSettings& settings, bool ruleNamed = false);
  const sg::MapperSettings& mapperSettings() const;
  // Maps with the engine Settings ▸ Preferences names (preferences::kFastEngine): at start, and
  // after the dialog; a change re-maps the log.
  void applyEngine();
  // Cell size in metres, clamped to [0.005, 1]; undoable; re-maps.
  void setCellSize(double metres);

  // What the user works on: logs, reference, settings, cell size, overlays, view, pinned rows,
  // sweep settings, and the undo stack every edit goes through.
  Document* document() const { return document_; }

  // Opens a .sgproj project: its log is loaded first, and only when that succeeds does the project
  // replace the document (a bad project or log leaves the current one). `quiet` as openLog.
  bool openProject(const QString& path, bool quiet = false);
  // Saves to `path` (atomically); false, after saying why, when it cannot be written.
  bool saveProjectAs(const QString& path, bool quiet = false);
  // Saves to the project's file, asking for a name when it has none.
  bool saveProject();
  Autosave* autosave() const { return autosave_; }
  // Crashed sessions' autosaves: `answer` "yes" opens the newest (the document stays modified),
  // "no" deletes them, "keep" leaves them; empty asks (or, without a display, reads
  // SONARGRID_RECOVER, else keeps). True when one was recovered.
  bool offerRecovery(const QString& answer = {});

  ui::GridView* gridView() const { return view_; }
  ui::Timeline* timeline() const { return timeline_; }
  ui::RemapController* remapController() const { return remap_; }
  ui::ParameterPanel* parameterPanel() const { return panel_; }
  ui::BeamModelView* beamModelView() const;
  // The beam dock's picture of the forward model's prediction (shown instead of the beam model
  // view while the settings are the forward model's).
  ui::ForwardRangeView* forwardRangeView() const;
  // The sonar whose reading of the current scan the beam view shows (highlighted in the grid).
  std::optional<std::size_t> beamSonar() const;
  // Shows sonar `sonar`'s reading of the current scan in the beam view from now on (while the
  // scans hold one); false when the current scan has no reading of it.
  bool chooseBeamSonar(std::size_t sonar);
  // The cell inspector's dock widget (main_window_inspector.cpp).
  ui::CellInspector* cellInspector() const { return inspector_; }
  // Moves the timeline to scan `scan` and shows its reading of `sonar` in the beam view; false
  // when the log has no such scan or reading.
  bool showReading(std::size_t scan, std::size_t sonar);
  const QStringList& recentFiles() const { return recent_; }

  // Blocks (running the event loop) until the newest requested map has arrived; false on timeout
  // or failure. For --screenshot and tests.
  bool waitForMap(int timeoutMs);
  // File ▸ Export ▸ Map as PNG without the dialog: waits for a re-map in progress, then writes the
  // full map of the current settings (never a preview). False when there is none or it failed.
  bool exportMapPngTo(const QString& path);

  // What the user last chose (model, rule, pose, cell size), as QSettings remembers it.
  static sg::MapperSettings lastSettings();
  static double lastCellSize();

 signals:
  // Percent of the file's bytes read by the running load (throttled: once per whole percent).
  void loadProgress(int percent);
  void loaded(const QString& path);
  void loadFailed(const QString& path, const QString& message);
  void loadCancelled(const QString& path);

 protected:
  void closeEvent(QCloseEvent* event) override;
  void dragEnterEvent(QDragEnterEvent* event) override;
  void dropEvent(QDropEvent* event) override;

 private:
  // main_window.cpp: the wiring between the document and the views.
  void connectDocument();
  void onSettingsChanged();
  void onCellSizeChanged(double metres);
  void onReferenceChanged();
  void onStartPoseChanged();
  // Shows the document's settings in the menus, title, summary, panel and beam view, and
  // remembers them soon.
  void showSettings();
  // Writes the settings to QSettings now (what the next session starts with).
  void rememberSettings();
  void updateSummary();
  void updateTitle();
  void onMapped(double elapsedMs);
  void onTimeChanged(double t, std::size_t scan);
  // The robot, beams and beam-view reading of the timeline's current scan.
  void showCurrentScan();
  // The forward model's predicted range of the beam dock's reading under the map shown
  // (BeamDock::showForward); nothing for an inverse model's map.
  void showForwardPrediction();
  bool reportError(const QString& title, const QString& message, bool quiet);
  // Makes `dataset` the document's log: timeline, views, re-map (or a pending project's state).
  void adoptLog(const QString& path, std::shared_ptr<const sg::ScanSource> source,
                const LogReading& reading = {});
  void onLoadFailed(const QString& path, const QString& message, bool quiet);
  void hideLoadProgress();

  // main_window_menus.cpp: actions, menus, recent files, drops, open dialogs.
  void createActions();
  void createMenus();
  void rememberRecent(const QString& path);
  void rebuildRecentMenu();
  void rebuildMappingMenu();
  void chooseModel(const QString& model);
  void chooseRule(const QString& rule);
  void choosePose(sg::PoseSource pose);
  void openLogDialog();
  void importCsvDialog();
  void openReferenceDialog();
  void openProjectDialog();
  void openExample();
  void askCellSize();
  // Opens a file by its kind: project, reference or log.
  void openAny(const QString& path);

  // main_window_docks.cpp: every dock of the window.
  void createDocks();
  void restoreWindowState();
  // main_window_inspector.cpp: the cell inspector's dock and its links.
  void createInspector();

  // main_window_export.cpp
  // Waits for a re-map in progress; false (and says so) unless the view shows the full map of the
  // current settings, not a preview.
  bool mapComplete();
  void exportViewPng();
  void exportViewSvg();
  void exportMapPng();
  void exportRosMap();
  QString saveFileName(const QString& title, const QString& filter, const QString& suffix);

  // main_window_project.cpp
  // The document's state with the view as shown now (what a project file saves).
  ProjectState projectState() const;
  // Makes a read project the document, once its log (if any) is loaded.
  void adoptProject(const QString& path, const ProjectState& state, bool modified, bool quiet);
  // Unsaved changes: Save, Discard or Cancel. True when the window may close.
  // Names the sweep settings a project left out (readProject()), if any.
  void sayDropped(const QString& path, const QStringList& dropped);
  bool maybeSave();

  Document* document_;
  LogLoader* loader_;
  Autosave* autosave_ = nullptr;
  ui::GridView* view_;
  ui::Timeline* timeline_ = nullptr;
  ui::ParameterPanel* panel_ = nullptr;
  BeamDock* beamDock_ = nullptr;
  MapDock* mapDock_ = nullptr;
  ui::CellInspector* inspector_ = nullptr;
  ui::CellPicker* picker_ = nullptr;
  ui::RemapController* remap_;
  StatusReport* status_;
  bool lastLoadSucceeded_ = false;
  // A project whose log is loading: it becomes the document when the log has loaded.
  struct PendingProject {
    QString path;
    QString logPath;
    std::shared_ptr<ProjectState> state;
    bool modified = false;
  };
  std::optional<PendingProject> pendingProject_;
  std::optional<ui::ViewTransform> pendingView_;  // a project's view, shown with its first map

  QTimer* rememberSettingsTimer_ = nullptr;
  std::optional<PoseSource> scanShownPose_;  // the pose source of the scan drawn, if any
  // The docks right of the grid share one column this wide on first launch: 1280 − 330 leaves
  // the grid more than 60 % of the window.
  static constexpr int kRightColumnWidth = 330;
  // The dock layout's version in the saved window state: a layout saved with another default
  // (version 0: the beam view and the panel side by side right of the grid) gives way to this
  // version's first-launch layout.
  static constexpr int kLayoutVersion = 1;
  // The Cell Inspector's height when it is shown in the row under the grid.
  static constexpr int kInspectorHeight = 250;
  // A settings change on a log whose full re-map takes longer than half a frame is first
  // previewed on cells twice as large, from one scan in N with N chosen so that the preview takes
  // about kPreviewBudgetMs (RemapController::setPreviewBudget): the dragged slider's picture
  // follows within a frame or two on any log, and the full map, delayed by about the budget,
  // replaces it when the slider rests (bench_remap_latency measures both).
  static constexpr int kPreviewFactor = 2;
  static constexpr double kPreviewBudgetMs = 4.0;
  static constexpr double kPreviewAboveMs = 8.0;
  QStringList recent_;
  // The menus' actions (main_window_menus.cpp), held together as Qt Designer's Ui classes hold
  // theirs.
  struct Actions {
    QAction* open = nullptr;
    QAction* openReference = nullptr;
    QAction* openProject = nullptr;
    QAction* saveProject = nullptr;
    QAction* saveProjectAs = nullptr;
    QAction* importCsv = nullptr;
    QAction* cancelLoad = nullptr;
    QAction* undo = nullptr;
    QAction* redo = nullptr;
    QAction* cellSize = nullptr;
    QAction* exportViewPng = nullptr;
    QAction* exportViewSvg = nullptr;
    QAction* exportMapPng = nullptr;
    QAction* exportRos = nullptr;
    QAction* play = nullptr;
    QAction* stepForward = nullptr;
    QAction* stepBack = nullptr;
    QAction* fit = nullptr;
    QList<QAction*> overlays;
    QMenu* recentMenu = nullptr;
    QMenu* modelMenu = nullptr;
    QMenu* ruleMenu = nullptr;
    QActionGroup* poseGroup = nullptr;
    sg::MapperSettings menuSettings;  // what the Mapping menu was last built for
  };
  Actions actions_;
};

}  // namespace sg::app
