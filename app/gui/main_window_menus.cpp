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
#include "sonargrid/forward/catalog.h"
#include "start_pose_picker.h"
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
  ParameterSet out = forward::mapDefaultParameters(model, rule);
  for (const auto& [name, value] : previous.values())
    if (out.has(name)) out.set(name, value);
  return out;
}

}  // namespace

void MainWindow::createActions() {
  actions_.open = new QAction(tr("&Open Log…"), this);
  actions_.open->setShortcut(QKeySequence::Open);
  connect(actions_.open, &QAction::triggered, this, &MainWindow::openLogDialog);
  actions_.importCsv = new QAction(tr("&Import CSV…"), this);
  connect(actions_.importCsv, &QAction::triggered, this, &MainWindow::importCsvDialog);
  actions_.cancelLoad = new QAction(tr("Cancel Loading"), this);
  actions_.cancelLoad->setShortcut(QKeySequence(Qt::Key_Escape));
  actions_.cancelLoad->setShortcutContext(Qt::WindowShortcut);
  actions_.cancelLoad->setEnabled(false);
  connect(actions_.cancelLoad, &QAction::triggered, this, &MainWindow::cancelLoad);
  actions_.openReference = new QAction(tr("Open &Reference Map…"), this);
  actions_.openReference->setShortcut(QKeySequence(tr("Ctrl+Shift+O")));
  connect(actions_.openReference, &QAction::triggered, this, &MainWindow::openReferenceDialog);
  actions_.exportViewPng = new QAction(tr("Export View as &PNG…"), this);
  actions_.exportViewPng->setShortcut(QKeySequence(tr("Ctrl+E")));
  connect(actions_.exportViewPng, &QAction::triggered, this, &MainWindow::exportViewPng);
  actions_.exportViewSvg = new QAction(tr("Export View as &SVG…"), this);
  actions_.exportViewSvg->setShortcut(QKeySequence(tr("Ctrl+Shift+E")));
  connect(actions_.exportViewSvg, &QAction::triggered, this, &MainWindow::exportViewSvg);
  actions_.exportMapPng = new QAction(tr("Export &Map as PNG…"), this);
  connect(actions_.exportMapPng, &QAction::triggered, this, &MainWindow::exportMapPng);
  actions_.exportRos = new QAction(tr("Export Map as &ROS map_server…"), this);
  connect(actions_.exportRos, &QAction::triggered, this, &MainWindow::exportRosMap);

  actions_.openProject = new QAction(tr("Open &Project…"), this);
  connect(actions_.openProject, &QAction::triggered, this, &MainWindow::openProjectDialog);
  actions_.saveProject = new QAction(tr("&Save Project"), this);
  actions_.saveProject->setShortcut(QKeySequence::Save);
  connect(actions_.saveProject, &QAction::triggered, this, &MainWindow::saveProject);
  actions_.saveProjectAs = new QAction(tr("Save Project &As…"), this);
  actions_.saveProjectAs->setShortcut(QKeySequence(tr("Ctrl+Shift+S")));
  connect(actions_.saveProjectAs, &QAction::triggered, this, [this] {
    const QString path = saveFileName(tr("Save Project As"), tr("SonarGrid projects (*.sgproj)"),
                                      QStringLiteral(".sgproj"));
    if (!path.isEmpty()) saveProjectAs(path);
  });
  actions_.undo = document_->undoStack()->createUndoAction(this, tr("&Undo"));
  actions_.undo->setShortcut(QKeySequence::Undo);
  actions_.redo = document_->undoStack()->createRedoAction(this, tr("&Redo"));
  // Redo's platform keys (Ctrl+Shift+Z on X11) and Ctrl+Y, which the user guide names.
  QList<QKeySequence> redoKeys = QKeySequence::keyBindings(QKeySequence::Redo);
  if (!redoKeys.contains(QKeySequence(Qt::CTRL | Qt::Key_Y)))
    redoKeys << QKeySequence(Qt::CTRL | Qt::Key_Y);
  actions_.redo->setShortcuts(redoKeys);
  actions_.cellSize = new QAction(tr("&Cell Size…"), this);
  connect(actions_.cellSize, &QAction::triggered, this, &MainWindow::askCellSize);

  actions_.fit = new QAction(tr("&Fit to Map"), this);
  actions_.fit->setShortcut(QKeySequence(tr("Ctrl+0")));
  connect(actions_.fit, &QAction::triggered, view_, &ui::GridView::fitToMap);

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
    actions_.overlays << a;
  }

  actions_.play = new QAction(tr("&Play / Pause"), this);
  actions_.play->setCheckable(true);
  actions_.play->setShortcut(QKeySequence(Qt::Key_Space));
  actions_.stepForward = new QAction(tr("&Next Scan"), this);
  actions_.stepForward->setShortcut(QKeySequence(Qt::Key_Period));
  actions_.stepBack = new QAction(tr("Pre&vious Scan"), this);
  actions_.stepBack->setShortcut(QKeySequence(Qt::Key_Comma));
}

void MainWindow::createMenus() {
  QMenu* file = menuBar()->addMenu(tr("&File"));
  file->addAction(actions_.open);
  file->addAction(actions_.importCsv);
  file->addAction(actions_.cancelLoad);
  actions_.recentMenu = file->addMenu(tr("Open &Recent"));
  QAction* example = file->addAction(tr("Open &Example…"));
  connect(example, &QAction::triggered, this, &MainWindow::openExample);
  file->addAction(actions_.openReference);
  file->addSeparator();
  file->addAction(actions_.openProject);
  file->addAction(actions_.saveProject);
  file->addAction(actions_.saveProjectAs);
  file->addSeparator();
  file->addAction(actions_.exportViewPng);
  file->addAction(actions_.exportViewSvg);
  file->addAction(actions_.exportMapPng);
  file->addAction(actions_.exportRos);
  // Nothing to export before a map is shown (a log or a live robot's map).
  auto updateExports = [this] {
    const bool any = view_->map() != nullptr;
    for (QAction* a : {actions_.exportViewPng, actions_.exportViewSvg, actions_.exportMapPng,
                       actions_.exportRos})
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
  edit->addAction(actions_.undo);
  edit->addAction(actions_.redo);

  QMenu* view = menuBar()->addMenu(tr("&View"));
  view->setObjectName(QStringLiteral("viewMenu"));
  view->addAction(actions_.fit);
  view->addAction(actions_.cellSize);
  view->addSeparator();
  for (QAction* a : actions_.overlays) view->addAction(a);
  view->addSeparator();
  for (QDockWidget* dock : findChildren<QDockWidget*>()) view->addAction(dock->toggleViewAction());

  QMenu* time = menuBar()->addMenu(tr("&Timeline"));
  time->addAction(actions_.play);
  time->addAction(actions_.stepForward);
  time->addAction(actions_.stepBack);

  QMenu* mapping = menuBar()->addMenu(tr("&Mapping"));
  actions_.modelMenu = mapping->addMenu(tr("Sensor &Model"));
  actions_.ruleMenu = mapping->addMenu(tr("Update &Rule"));
  QMenu* pose = mapping->addMenu(tr("&Pose"));
  actions_.poseGroup = new QActionGroup(this);
  for (PoseSource p : {PoseSource::Odometry, PoseSource::Truth}) {
    QAction* a = pose->addAction(p == PoseSource::Truth ? tr("&True pose") : tr("&Odometry"));
    a->setCheckable(true);
    a->setData(poseName(p));
    actions_.poseGroup->addAction(a);
    connect(a, &QAction::triggered, this, [this, p] { choosePose(p); });
  }
  mapping->addSeparator();
  new StartPosePicker(document_, view_, mapping, statusBar(), this);
  rebuildMappingMenu();

  QMenu* settings = menuBar()->addMenu(tr("&Settings"));
  QAction* preferences = settings->addAction(tr("&Preferences…"));
  preferences->setMenuRole(QAction::PreferencesRole);
  preferences->setShortcut(QKeySequence::Preferences);
  connect(preferences, &QAction::triggered, this, [this] {
    PreferencesDialog(this).exec();
    applyEngine();
  });

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
  addActions({actions_.play, actions_.stepForward, actions_.stepBack});
}

void MainWindow::rebuildMappingMenu() {
  actions_.menuSettings = document_->mapperSettings();
  const MapperSettings& settings = document_->mapperSettings();
  actions_.modelMenu->clear();
  actions_.ruleMenu->clear();
  // The previous groups go with their actions (clear() deletes only the actions).
  qDeleteAll(actions_.modelMenu->findChildren<QActionGroup*>(Qt::FindDirectChildrenOnly));
  qDeleteAll(actions_.ruleMenu->findChildren<QActionGroup*>(Qt::FindDirectChildrenOnly));
  auto* models = new QActionGroup(actions_.modelMenu);
  for (const std::string& name : forward::mapModelNames()) {
    QAction* a =
        actions_.modelMenu->addAction(QString::fromStdString(forward::mapModelTitle(name)));
    a->setCheckable(true);
    a->setChecked(name == settings.model);
    models->addAction(a);
    connect(a, &QAction::triggered, this,
            [this, n = QString::fromStdString(name)] { chooseModel(n); });
  }
  auto* rules = new QActionGroup(actions_.ruleMenu);
  for (const std::string& name : forward::mapRuleNames()) {
    QAction* a = actions_.ruleMenu->addAction(QString::fromStdString(forward::mapRuleTitle(name)));
    a->setCheckable(true);
    a->setChecked(name == settings.rule);
    const Compatibility c = forward::mapCompatibility(settings.model, name);
    a->setEnabled(c.allowed);
    if (!c.allowed) a->setToolTip(QString::fromStdString(c.reason));
    rules->addAction(a);
    connect(a, &QAction::triggered, this,
            [this, n = QString::fromStdString(name)] { chooseRule(n); });
  }
  actions_.ruleMenu->setToolTipsVisible(true);
  for (QAction* a : actions_.poseGroup->actions())
    a->setChecked(a->data() == poseName(settings.pose));
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
  if (!actions_.recentMenu) return;
  actions_.recentMenu->clear();
  for (int i = 0; i < recent_.size(); ++i) {
    const QString path = recent_[i];
    QAction* a = actions_.recentMenu->addAction(QStringLiteral("&%1 %2").arg(i + 1).arg(path));
    connect(a, &QAction::triggered, this, [this, path] { openAny(path); });
  }
  actions_.recentMenu->setEnabled(!recent_.isEmpty());
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
      tr("Sonar logs (*.sglog *.clf *.carmen *.log *.playerlog *.csv *.txt *.tsv *.bag *.mcap "
         "*.db3 metadata.yaml);;ROS bags (*.bag *.mcap *.db3 metadata.yaml);;All files (*)"));
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
