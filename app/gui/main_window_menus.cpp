// SPDX-License-Identifier: GPL-3.0-or-later
// The window's actions and menus (File, Edit, View, Timeline, Mapping, Settings, Help), recent
// files, dropped files and the open dialogs.
#include <QAction>
#include <QActionGroup>
#include <QDir>
#include <QDockWidget>
#include <QDragEnterEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QInputDialog>
#include <QMenu>
#include <QMenuBar>
#include <QMimeData>
#include <QSettings>
#include <QTimer>
#include <QUndoStack>

#include "dataset_manifest.h"
#include "datasets_location.h"
#include "document.h"
#include "example_chooser.h"
#include "help_dialogs.h"
#include "main_window.h"
#include "parameter_panel.h"
#include "preferences.h"
#include "project_file.h"
#include "remap_controller.h"
#include "sonargrid/engine/sensor_model.h"
#include "sonargrid/engine/update_rule.h"
#include "tour_dialog.h"

namespace sg::app {
namespace {

constexpr int kMaxRecent = 8;

QString poseName(PoseSource p) {
  return p == PoseSource::Truth ? QStringLiteral("truth") : QStringLiteral("odom");
}

bool isReferenceFile(const QString& path) {
  const QString suffix = QFileInfo(path).suffix().toLower();
  return suffix == QLatin1String("json") || suffix == QLatin1String("map") ||
         suffix == QLatin1String("yaml") || suffix == QLatin1String("yml");
}

// Model and rule parameters at their defaults, then every value of `previous` that the new pair
// still declares: switching the rule keeps the model's tuning.
ParameterSet carryParameters(const std::string& model, const std::string& rule,
                             const ParameterSet& previous) {
  ParameterSet out = defaultParameters(model, rule);
  for (const auto& [name, value] : previous.values())
    if (out.has(name)) out.set(name, value);
  return out;
}

}  // namespace

void MainWindow::createActions() {
  openAction_ = new QAction(tr("&Open Log…"), this);
  openAction_->setShortcut(QKeySequence::Open);
  connect(openAction_, &QAction::triggered, this, &MainWindow::openLogDialog);
  importCsvAction_ = new QAction(tr("&Import CSV…"), this);
  connect(importCsvAction_, &QAction::triggered, this, &MainWindow::importCsvDialog);
  cancelLoadAction_ = new QAction(tr("Cancel Loading"), this);
  cancelLoadAction_->setShortcut(QKeySequence(Qt::Key_Escape));
  cancelLoadAction_->setShortcutContext(Qt::WindowShortcut);
  cancelLoadAction_->setEnabled(false);
  connect(cancelLoadAction_, &QAction::triggered, this, &MainWindow::cancelLoad);
  openReferenceAction_ = new QAction(tr("Open &Reference Map…"), this);
  openReferenceAction_->setShortcut(QKeySequence(tr("Ctrl+Shift+O")));
  connect(openReferenceAction_, &QAction::triggered, this, &MainWindow::openReferenceDialog);
  exportViewPngAction_ = new QAction(tr("Export View as &PNG…"), this);
  exportViewPngAction_->setShortcut(QKeySequence(tr("Ctrl+E")));
  connect(exportViewPngAction_, &QAction::triggered, this, &MainWindow::exportViewPng);
  exportViewSvgAction_ = new QAction(tr("Export View as &SVG…"), this);
  exportViewSvgAction_->setShortcut(QKeySequence(tr("Ctrl+Shift+E")));
  connect(exportViewSvgAction_, &QAction::triggered, this, &MainWindow::exportViewSvg);
  exportMapPngAction_ = new QAction(tr("Export &Map as PNG…"), this);
  connect(exportMapPngAction_, &QAction::triggered, this, &MainWindow::exportMapPng);
  exportRosAction_ = new QAction(tr("Export Map as &ROS map_server…"), this);
  connect(exportRosAction_, &QAction::triggered, this, &MainWindow::exportRosMap);

  openProjectAction_ = new QAction(tr("Open &Project…"), this);
  connect(openProjectAction_, &QAction::triggered, this, &MainWindow::openProjectDialog);
  saveProjectAction_ = new QAction(tr("&Save Project"), this);
  saveProjectAction_->setShortcut(QKeySequence::Save);
  connect(saveProjectAction_, &QAction::triggered, this, &MainWindow::saveProject);
  saveProjectAsAction_ = new QAction(tr("Save Project &As…"), this);
  saveProjectAsAction_->setShortcut(QKeySequence(tr("Ctrl+Shift+S")));
  connect(saveProjectAsAction_, &QAction::triggered, this, [this] {
    const QString path = saveFileName(tr("Save Project As"), tr("SonarGrid projects (*.sgproj)"),
                                      QStringLiteral(".sgproj"));
    if (!path.isEmpty()) saveProjectAs(path);
  });
  undoAction_ = document_->undoStack()->createUndoAction(this, tr("&Undo"));
  undoAction_->setShortcut(QKeySequence::Undo);
  redoAction_ = document_->undoStack()->createRedoAction(this, tr("&Redo"));
  // Redo's platform keys (Ctrl+Shift+Z on X11) and Ctrl+Y, which the user guide names.
  QList<QKeySequence> redoKeys = QKeySequence::keyBindings(QKeySequence::Redo);
  if (!redoKeys.contains(QKeySequence(Qt::CTRL | Qt::Key_Y)))
    redoKeys << QKeySequence(Qt::CTRL | Qt::Key_Y);
  redoAction_->setShortcuts(redoKeys);
  cellSizeAction_ = new QAction(tr("&Cell Size…"), this);
  connect(cellSizeAction_, &QAction::triggered, this, &MainWindow::askCellSize);

  fitAction_ = new QAction(tr("&Fit to Map"), this);
  fitAction_->setShortcut(QKeySequence(tr("Ctrl+0")));
  connect(fitAction_, &QAction::triggered, view_, &ui::GridView::fitToMap);

  const std::pair<ui::Overlay, QString> overlays[] = {
      {ui::Overlay::Reference, tr("&Reference Map")},
      {ui::Overlay::Path, tr("Robot &Path")},
      {ui::Overlay::Robot, tr("R&obot")},
      {ui::Overlay::Beams, tr("Current &Beams")},
      {ui::Overlay::Ring, tr("Sonar R&ing")},
      {ui::Overlay::Legend, tr("&Legend")},
      {ui::Overlay::Dmin, tr("&D_min of Filled Cells")}};
  int key = 1;
  for (const auto& [overlay, title] : overlays) {
    auto* a = new QAction(title, this);
    a->setCheckable(true);
    a->setData(static_cast<int>(overlay));
    a->setChecked(document_->overlays().testFlag(overlay));
    a->setShortcut(QKeySequence(QStringLiteral("Alt+%1").arg(key++)));
    connect(a, &QAction::toggled, this, [this, o = overlay](bool on) {
      document_->setOverlays(document_->overlays().setFlag(o, on));
    });
    overlayActions_ << a;
  }

  playAction_ = new QAction(tr("&Play / Pause"), this);
  playAction_->setCheckable(true);
  playAction_->setShortcut(QKeySequence(Qt::Key_Space));
  stepForwardAction_ = new QAction(tr("&Next Scan"), this);
  stepForwardAction_->setShortcut(QKeySequence(Qt::Key_Period));
  stepBackAction_ = new QAction(tr("Pre&vious Scan"), this);
  stepBackAction_->setShortcut(QKeySequence(Qt::Key_Comma));
}

void MainWindow::createMenus() {
  QMenu* file = menuBar()->addMenu(tr("&File"));
  file->addAction(openAction_);
  file->addAction(importCsvAction_);
  file->addAction(cancelLoadAction_);
  recentMenu_ = file->addMenu(tr("Open &Recent"));
  QAction* example = file->addAction(tr("Open &Example…"));
  connect(example, &QAction::triggered, this, &MainWindow::openExample);
  file->addAction(openReferenceAction_);
  file->addSeparator();
  file->addAction(openProjectAction_);
  file->addAction(saveProjectAction_);
  file->addAction(saveProjectAsAction_);
  file->addSeparator();
  file->addAction(exportViewPngAction_);
  file->addAction(exportViewSvgAction_);
  file->addAction(exportMapPngAction_);
  file->addAction(exportRosAction_);
  // Nothing to export before a map is shown (a log or a live robot's map).
  auto updateExports = [this] {
    const bool any = view_->map() != nullptr;
    for (QAction* a :
         {exportViewPngAction_, exportViewSvgAction_, exportMapPngAction_, exportRosAction_})
      a->setEnabled(any);
  };
  updateExports();
  connect(file, &QMenu::aboutToShow, this, updateExports);
  connect(document_, &Document::logChanged, this, updateExports);
  // After the window has shown the new map.
  connect(remap_, &ui::RemapController::mapped, this,
          [this, updateExports] { QTimer::singleShot(0, this, updateExports); });
  file->addSeparator();
  QAction* quit = file->addAction(tr("&Quit"));
  quit->setShortcut(QKeySequence::Quit);
  connect(quit, &QAction::triggered, this, &QWidget::close);
  recent_ = QSettings().value("files/recent").toStringList();
  rebuildRecentMenu();

  QMenu* edit = menuBar()->addMenu(tr("&Edit"));
  edit->setObjectName(QStringLiteral("editMenu"));
  edit->addAction(undoAction_);
  edit->addAction(redoAction_);

  QMenu* view = menuBar()->addMenu(tr("&View"));
  view->setObjectName(QStringLiteral("viewMenu"));
  view->addAction(fitAction_);
  view->addAction(cellSizeAction_);
  view->addSeparator();
  for (QAction* a : overlayActions_) view->addAction(a);
  view->addSeparator();
  for (QDockWidget* dock : findChildren<QDockWidget*>()) view->addAction(dock->toggleViewAction());

  QMenu* time = menuBar()->addMenu(tr("&Timeline"));
  time->addAction(playAction_);
  time->addAction(stepForwardAction_);
  time->addAction(stepBackAction_);

  QMenu* mapping = menuBar()->addMenu(tr("&Mapping"));
  modelMenu_ = mapping->addMenu(tr("Sensor &Model"));
  ruleMenu_ = mapping->addMenu(tr("Update &Rule"));
  QMenu* pose = mapping->addMenu(tr("&Pose"));
  poseGroup_ = new QActionGroup(this);
  for (PoseSource p : {PoseSource::Odometry, PoseSource::Truth}) {
    QAction* a = pose->addAction(p == PoseSource::Truth ? tr("&True pose") : tr("&Odometry"));
    a->setCheckable(true);
    a->setData(poseName(p));
    poseGroup_->addAction(a);
    connect(a, &QAction::triggered, this, [this, p] { choosePose(p); });
  }
  rebuildMappingMenu();

  QMenu* settings = menuBar()->addMenu(tr("&Settings"));
  QAction* preferences = settings->addAction(tr("&Preferences…"));
  preferences->setMenuRole(QAction::PreferencesRole);
  preferences->setShortcut(QKeySequence::Preferences);
  connect(preferences, &QAction::triggered, this, [this] { PreferencesDialog(this).exec(); });

  QMenu* help = menuBar()->addMenu(tr("&Help"));
  QAction* guide = help->addAction(tr("&User Guide"));
  guide->setShortcut(QKeySequence::HelpContents);
  connect(guide, &QAction::triggered, this, [this] { showUserGuide(this); });
  QAction* tour = help->addAction(tr("Sonar Models in &5 Minutes"));
  tour->setObjectName(QStringLiteral("tourAction"));
  connect(tour, &QAction::triggered, this, [this] {
    if (!maybeSave()) return;  // the tour opens a log of its own
    auto* dialog = new TourDialog(this);
    dialog->setAttribute(Qt::WA_DeleteOnClose);
    dialog->show();
  });
  QAction* keys = help->addAction(tr("&Keyboard Shortcuts"));
  keys->setShortcut(QKeySequence(tr("Ctrl+/")));
  connect(keys, &QAction::triggered, this, [this] { showShortcuts(this); });
  connect(help->addAction(tr("&About SonarGrid")), &QAction::triggered, this,
          [this] { showAbout(this); });
  // Shortcuts of hidden docks' actions still work when they live on the window.
  addActions({playAction_, stepForwardAction_, stepBackAction_});
}

void MainWindow::rebuildMappingMenu() {
  menuSettings_ = document_->mapperSettings();
  const MapperSettings& settings = document_->mapperSettings();
  modelMenu_->clear();
  ruleMenu_->clear();
  // The previous groups go with their actions (clear() deletes only the actions).
  qDeleteAll(modelMenu_->findChildren<QActionGroup*>(Qt::FindDirectChildrenOnly));
  qDeleteAll(ruleMenu_->findChildren<QActionGroup*>(Qt::FindDirectChildrenOnly));
  auto* models = new QActionGroup(modelMenu_);
  for (const std::string& name : sensorModelNames()) {
    QAction* a = modelMenu_->addAction(QString::fromStdString(sensorModelInfo(name).title));
    a->setCheckable(true);
    a->setChecked(name == settings.model);
    models->addAction(a);
    connect(a, &QAction::triggered, this,
            [this, n = QString::fromStdString(name)] { chooseModel(n); });
  }
  auto* rules = new QActionGroup(ruleMenu_);
  for (const std::string& name : updateRuleNames()) {
    QAction* a = ruleMenu_->addAction(QString::fromStdString(updateRuleInfo(name).title));
    a->setCheckable(true);
    a->setChecked(name == settings.rule);
    const Compatibility c = compatibility(settings.model, name);
    a->setEnabled(c.allowed);
    if (!c.allowed) a->setToolTip(QString::fromStdString(c.reason));
    rules->addAction(a);
    connect(a, &QAction::triggered, this,
            [this, n = QString::fromStdString(name)] { chooseRule(n); });
  }
  ruleMenu_->setToolTipsVisible(true);
  for (QAction* a : poseGroup_->actions()) a->setChecked(a->data() == poseName(settings.pose));
}

void MainWindow::chooseModel(const QString& model) {
  MapperSettings s = document_->mapperSettings();
  s.model = model.toStdString();
  // The paper's pairing, as the parameter panel chooses it (its note says so).
  s.rule = ui::ParameterPanel::ruleForModel(s.model, s.rule);
  s.parameters = carryParameters(s.model, s.rule, document_->mapperSettings().parameters);
  setMapperSettings(s);
}

void MainWindow::chooseRule(const QString& rule) {
  MapperSettings s = document_->mapperSettings();
  s.rule = rule.toStdString();
  s.parameters = carryParameters(s.model, s.rule, document_->mapperSettings().parameters);
  setMapperSettings(s);
}

void MainWindow::choosePose(PoseSource pose) {
  MapperSettings s = document_->mapperSettings();
  s.pose = pose;
  setMapperSettings(s);
}

void MainWindow::rememberRecent(const QString& path) {
  const QString absolute = QFileInfo(path).absoluteFilePath();
  recent_.removeAll(absolute);
  recent_.prepend(absolute);
  while (recent_.size() > kMaxRecent) recent_.removeLast();
  QSettings().setValue("files/recent", recent_);
  rebuildRecentMenu();
}

void MainWindow::rebuildRecentMenu() {
  if (!recentMenu_) return;
  recentMenu_->clear();
  for (int i = 0; i < recent_.size(); ++i) {
    const QString path = recent_[i];
    QAction* a = recentMenu_->addAction(QStringLiteral("&%1 %2").arg(i + 1).arg(path));
    connect(a, &QAction::triggered, this, [this, path] { openAny(path); });
  }
  recentMenu_->setEnabled(!recent_.isEmpty());
}

void MainWindow::dragEnterEvent(QDragEnterEvent* event) {
  for (const QUrl& url : event->mimeData()->urls())
    if (url.isLocalFile()) {
      event->acceptProposedAction();
      return;
    }
}

void MainWindow::dropEvent(QDropEvent* event) {
  for (const QUrl& url : event->mimeData()->urls()) {
    if (!url.isLocalFile()) continue;
    const QString path = url.toLocalFile();
    openAny(path);
  }
  event->acceptProposedAction();
}

void MainWindow::openLogDialog() {
  const QString dir = QSettings().value("files/lastDirectory", QDir::homePath()).toString();
  const QString path = QFileDialog::getOpenFileName(
      this, tr("Open Log"), dir,
      tr("Sonar logs (*.sglog *.clf *.carmen *.log *.playerlog *.csv *.txt *.tsv);;"
         "All files (*)"));
  if (!path.isEmpty() && maybeSave()) openLog(path);
}

void MainWindow::importCsvDialog() {
  const QString dir = QSettings().value("files/lastDirectory", QDir::homePath()).toString();
  const QString path = QFileDialog::getOpenFileName(
      this, tr("Import CSV"), dir, tr("CSV and text logs (*.csv *.txt *.tsv);;All files (*)"));
  if (!path.isEmpty() && maybeSave()) importCsv(path);
}

void MainWindow::openReferenceDialog() {
  const QString dir = QSettings().value("files/lastDirectory", QDir::homePath()).toString();
  const QString path =
      QFileDialog::getOpenFileName(this, tr("Open Reference Map"), dir,
                                   tr("Reference maps (*.json *.map *.yaml *.yml);;All files (*)"));
  if (!path.isEmpty()) openReference(path);
}

void MainWindow::openProjectDialog() {
  const QString dir = QSettings().value("files/lastDirectory", QDir::homePath()).toString();
  const QString path = QFileDialog::getOpenFileName(this, tr("Open Project"), dir,
                                                    tr("SonarGrid projects (*.sgproj)"));
  if (!path.isEmpty() && maybeSave()) openProject(path);
}

void MainWindow::openAny(const QString& path) {
  // A log or a project replaces the document: ask first. A reference is an undoable edit of it.
  if (!isReferenceFile(path) && !maybeSave()) return;
  if (QFileInfo(path).suffix().compare(QLatin1String(kProjectSuffix), Qt::CaseInsensitive) == 0)
    openProject(path);
  else if (isReferenceFile(path))
    openReference(path);
  else
    openLog(path);
}

void MainWindow::askCellSize() {
  bool ok = false;
  const double cell = QInputDialog::getDouble(
      this, tr("Cell Size"),
      tr("Cell size in metres (%1 – %2):").arg(kMinCellSize).arg(kMaxCellSize),
      document_->cellSize(), kMinCellSize, kMaxCellSize, 3, &ok, Qt::WindowFlags(), 0.005);
  if (ok) setCellSize(cell);
}

void MainWindow::openExample() {
  const QString dir = bundledDatasetsDirectory();
  QStringList errors;
  std::vector<DatasetManifest> datasets;
  if (!dir.isEmpty()) datasets = datasetManifests(dir, &errors);
  if (datasets.empty()) {
    reportError(tr("No examples"),
                errors.isEmpty() ? tr("The bundled datasets were not found.") : errors.join('\n'),
                false);
    return;
  }
  ExampleChooser chooser(std::move(datasets), this);
  if (chooser.exec() == QDialog::Accepted && !chooser.chosenLog().isEmpty() && maybeSave())
    openLog(chooser.chosenLog());
}

}  // namespace sg::app
