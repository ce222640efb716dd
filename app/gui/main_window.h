// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The desktop app's window: the grid view in the centre, docks around it, the File / View /
// Mapping / Help menus, and the wiring between the document (log, reference, mapper settings), the
// RemapController and the views. The window never parses a file or evaluates a model: the core
// does (DESIGN.md, "Data flow").

#include <QElapsedTimer>
#include <QMainWindow>
#include <QStringList>
#include <memory>
#include <optional>
#include <vector>

#include "grid_view.h"
#include "sonargrid/dataset.h"
#include "sonargrid/io/log_options.h"
#include "sonargrid/mapper.h"
#include "sonargrid/reference/reference_map.h"

class QAction;
class QActionGroup;
class QComboBox;
class QLabel;
class QMenu;
class QProgressBar;
class QPushButton;
class QThread;
class QTimer;

namespace sg::ui {
class BeamModelView;
class ParameterPanel;
class RemapController;
class Timeline;
}  // namespace sg::ui

namespace sg::app {

class MainWindow : public QMainWindow {
  Q_OBJECT

 public:
  explicit MainWindow(ui::GridView::Backend backend = ui::GridView::Backend::Automatic,
                      QWidget* parent = nullptr);
  ~MainWindow() override;

  // Each returns false after telling the user (a message box naming file:line) what was wrong; the
  // previous document then stays loaded. `quiet` reports on stderr instead (screenshots, tests).
  // openLog loads on a worker thread: without `quiet` it returns true once the load has started
  // (a CSV file first asks for its columns in the CsvImportDialog; false when the user cancels
  // it); with `quiet` it waits for the load and returns whether it succeeded.
  bool openLog(const QString& path, bool quiet = false);
  // Starts loading `path` with `options` on a worker thread, cancelling a load still running. The
  // previous document stays shown until the new one is complete: loaded(), or loadFailed() /
  // loadCancelled() leaving it untouched. Progress shows in the status bar (Cancel button, Esc).
  void loadLog(const QString& path, const sg::LogOptions& options, bool quiet = false);
  // Abandons the running load at once (loadCancelled); the worker stops at its next block.
  void cancelLoad();
  bool loading() const { return load_ != nullptr; }
  // Blocks (running the event loop) until no load is running; true when the last one loaded.
  // timeoutMs < 0 waits as long as the load takes.
  bool waitForLoad(int timeoutMs = -1);
  // Asks for a CSV file's columns (CsvImportDialog) and loads it; false when the user cancels.
  bool importCsv(const QString& path);
  const std::shared_ptr<const sg::Dataset>& dataset() const { return data_; }
  const QString& logPath() const { return logPath_; }
  bool openReference(const QString& path, bool quiet = false);
  bool hasReference() const { return reference_.has_value(); }
  // Forgets the open log (a live robot's map takes its place); the reference map stays.
  void closeLog();

  // Model, rule, parameters and pose: re-maps the log (not when they equal the settings of the
  // current map), and shows them in the menus, the title, the parameter panel and the beam view.
  void setMapperSettings(const sg::MapperSettings& settings);
  const sg::MapperSettings& mapperSettings() const { return settings_; }
  void setCellSize(double metres);

  ui::GridView* gridView() const { return view_; }
  ui::Timeline* timeline() const { return timeline_; }
  ui::RemapController* remapController() const { return remap_; }
  ui::ParameterPanel* parameterPanel() const { return panel_; }
  ui::BeamModelView* beamModelView() const { return beamView_; }
  // The sonar whose reading of the current scan the beam view shows (highlighted in the grid).
  std::optional<std::size_t> beamSonar() const { return beamSonar_; }
  // Shows sonar `sonar`'s reading of the current scan in the beam view from now on (while the
  // scans hold one); false when the current scan has no reading of it.
  bool chooseBeamSonar(std::size_t sonar);
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
  void createActions();
  void createMenus();
  // Every dock of the window is made here (the parameter panel joins them).
  void createDocks();
  void restoreWindowState();
  void rememberRecent(const QString& path);
  void rebuildRecentMenu();
  void rebuildMappingMenu();
  void chooseModel(const QString& model);
  void chooseRule(const QString& rule);
  void choosePose(sg::PoseSource pose);
  // Shows settings_ in the menus, title, summary, panel and beam view, and remembers it soon.
  void showSettings();
  // Hands settings_ to the beam view (showSettings defers it).
  void showBeamSettings();
  // Writes settings_ to QSettings now.
  void rememberSettings();
  void updateSummary();
  void updateTitle();
  void onMapped(double elapsedMs);
  void onTimeChanged(double t, std::size_t scan);
  // The robot, beams and beam-view reading of the timeline's current scan.
  void showCurrentScan();
  bool reportError(const QString& title, const QString& message, bool quiet);

  struct LoadJob;
  // On the GUI thread, when a worker has finished `job` (superseded jobs are ignored).
  void finishLoad(const std::shared_ptr<LoadJob>& job, std::shared_ptr<const sg::Dataset> dataset,
                  const QString& error, bool cancelled);
  // Makes `loaded` the document: timeline, views, re-map.
  void adoptLog(const QString& path, std::shared_ptr<const sg::Dataset> dataset);
  void showLoadProgress(const std::shared_ptr<LoadJob>& job, int percent);
  void hideLoadProgress();

  void openLogDialog();
  void importCsvDialog();
  void openReferenceDialog();
  void openExample();
  void exportViewPng();
  void exportViewSvg();
  // Waits for a re-map in progress; false (and says so) unless the view shows the full map of the
  // current settings, not a preview.
  bool mapComplete();
  void exportMapPng();
  void exportRosMap();
  void showUserGuide();
  void showShortcuts();
  void showAbout();
  QString saveFileName(const QString& title, const QString& filter, const QString& suffix);

  ui::GridView* view_;
  ui::Timeline* timeline_ = nullptr;
  ui::ParameterPanel* panel_ = nullptr;
  ui::BeamModelView* beamView_ = nullptr;
  QComboBox* readingChooser_ = nullptr;
  std::optional<std::size_t> chosenSonar_;  // the user's pick; none: the first reading with echo
  std::optional<std::size_t> beamSonar_;    // what the beam view shows now
  ui::RemapController* remap_;
  QLabel* hoverLabel_;
  QLabel* remapLabel_;
  QLabel* summary_ = nullptr;
  QProgressBar* loadBar_ = nullptr;
  QPushButton* loadCancelButton_ = nullptr;
  QAction* cancelLoadAction_ = nullptr;
  QAction* importCsvAction_ = nullptr;
  std::shared_ptr<LoadJob> load_;  // the running load, if any
  std::vector<QThread*> loaders_;  // workers still running (a cancelled one ends soon)
  bool lastLoadSucceeded_ = false;

  std::shared_ptr<const sg::Dataset> data_;
  QString logPath_;
  std::optional<sg::ReferenceMap> reference_;
  QString referencePath_;
  sg::MapperSettings settings_;
  sg::MapperSettings menuSettings_;  // what the Mapping menu was last built for
  QTimer* rememberSettingsTimer_ = nullptr;
  QTimer* beamSettingsTimer_ = nullptr;
  bool beamSettingsPending_ = false;
  QElapsedTimer beamShown_;                      // since the beam view last took new settings
  std::optional<PoseSource> scanShownPose_;      // the pose source of the scan drawn, if any
  std::shared_ptr<const OccupancyMap> fullMap_;  // the last map delivered by mapped()
  static constexpr int kBeamIntervalMs = 150;
  QTimer* summaryTimer_ = nullptr;
  static constexpr int kSummaryIntervalMs = 250;
  static constexpr int kPreviewFactor = 2;
  static constexpr double kPreviewAboveMs = 30.0;
  double cellSize_ = 0.05;
  double lastRemapMs_ = 0.0;
  QStringList recent_;

  QMenu* recentMenu_ = nullptr;
  QMenu* modelMenu_ = nullptr;
  QMenu* ruleMenu_ = nullptr;
  QActionGroup* poseGroup_ = nullptr;
  QAction* openAction_ = nullptr;
  QAction* openReferenceAction_ = nullptr;
  QAction* exportViewPngAction_ = nullptr;
  QAction* exportViewSvgAction_ = nullptr;
  QAction* exportMapPngAction_ = nullptr;
  QAction* exportRosAction_ = nullptr;
  QAction* playAction_ = nullptr;
  QAction* stepForwardAction_ = nullptr;
  QAction* stepBackAction_ = nullptr;
  QAction* fitAction_ = nullptr;
  QList<QAction*> overlayActions_;
};

}  // namespace sg::app
