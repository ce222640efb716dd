// SPDX-License-Identifier: GPL-3.0-or-later
#include "main_window.h"

#include <QAction>
#include <QActionGroup>
#include <QApplication>
#include <QBuffer>
#include <QCloseEvent>
#include <QComboBox>
#include <QDialog>
#include <QDialogButtonBox>
#include <QDir>
#include <QDockWidget>
#include <QDragEnterEvent>
#include <QElapsedTimer>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QPainter>
#include <QProgressBar>
#include <QPushButton>
#include <QSettings>
#include <QStatusBar>
#include <QSvgGenerator>
#include <QTableWidget>
#include <QTextBrowser>
#include <QThread>
#include <QTimer>
#include <QVBoxLayout>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <iostream>

#include "beam_model_view.h"
#include "csv_import_dialog.h"
#include "datasets_location.h"
#include "export_file.h"
#include "parameter_panel.h"
#include "preferences.h"
#include "reference_editing.h"
#include "reference_editor.h"
#include "remap_controller.h"
#include "sonargrid/export/map_export.h"
#include "sonargrid/io/log_reader.h"
#include "sonargrid/models/sensor_model.h"
#include "sonargrid/reference/read_reference.h"
#include "sonargrid/rules/update_rule.h"
#include "timeline.h"

// The window's resources live in this static library; a static library's resource initialiser
// must be called by name (and outside any namespace).
static void initialiseResources() {
  Q_INIT_RESOURCE(sonargrid);
}

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

// A .csv / .txt / .tsv file whose content is not another format: it needs a column mapping.
bool needsColumns(const QString& path) {
  const QString suffix = QFileInfo(path).suffix().toLower();
  if (suffix != QLatin1String("csv") && suffix != QLatin1String("txt") &&
      suffix != QLatin1String("tsv"))
    return false;
  QFile f(path);
  if (!f.open(QIODevice::ReadOnly)) return false;  // readLog names the file and the problem
  const QByteArray head = f.read(static_cast<qint64>(kDetectBytes));
  const LogFormat detected = detectLogFormat(std::string_view(head.constData(), head.size()));
  return detected == LogFormat::Csv || detected == LogFormat::Auto;
}

}  // namespace

// One load on a worker thread. The window forgets a job it cancelled or replaced; the worker still
// holds it until it notices `cancel`.
struct MainWindow::LoadJob {
  QString path;
  bool quiet = false;
  std::atomic<bool> cancel{false};
  std::atomic<int> lastPercent{-1};
};

MainWindow::MainWindow(ui::GridView::Backend backend, QWidget* parent)
    : QMainWindow(parent),
      view_(new ui::GridView(backend, this)),
      remap_(new ui::RemapController(this)),
      hoverLabel_(new QLabel(this)),
      remapLabel_(new QLabel(this)) {
  initialiseResources();
  setWindowIcon(QIcon(QStringLiteral(":/sonargrid/sonargrid.svg")));
  setCentralWidget(view_);
  setAcceptDrops(true);
  settings_ = lastSettings();
  cellSize_ = lastCellSize();
  rememberSettingsTimer_ = new QTimer(this);
  rememberSettingsTimer_->setSingleShot(true);
  rememberSettingsTimer_->setInterval(1000);
  connect(rememberSettingsTimer_, &QTimer::timeout, this, &MainWindow::rememberSettings);
  beamSettingsTimer_ = new QTimer(this);
  beamSettingsTimer_->setSingleShot(true);
  beamSettingsTimer_->setInterval(kBeamIntervalMs);
  connect(beamSettingsTimer_, &QTimer::timeout, this, &MainWindow::showBeamSettings);
  beamShown_.start();
  summaryTimer_ = new QTimer(this);
  summaryTimer_->setSingleShot(true);
  summaryTimer_->setInterval(kSummaryIntervalMs);
  connect(summaryTimer_, &QTimer::timeout, this, &MainWindow::updateSummary);

  remapLabel_->setObjectName(QStringLiteral("remapStatus"));
  // Wide enough for its longest text, so a new time does not lay the status bar out again.
  remapLabel_->setMinimumWidth(
      remapLabel_->fontMetrics().horizontalAdvance(tr("preview at 99.9 cm (9999 ms)…")) + 8);
  statusBar()->addWidget(hoverLabel_, 1);
  statusBar()->addPermanentWidget(remapLabel_);
  loadBar_ = new QProgressBar(this);
  loadBar_->setRange(0, 100);
  loadBar_->setFixedWidth(loadBar_->fontMetrics().horizontalAdvance(QLatin1Char('x')) * 40);
  loadBar_->setVisible(false);
  loadCancelButton_ = new QPushButton(tr("Cancel"), this);
  loadCancelButton_->setObjectName(QStringLiteral("cancelLoading"));
  loadCancelButton_->setToolTip(tr("Stop loading (Esc); the open log stays"));
  loadCancelButton_->setVisible(false);
  connect(loadCancelButton_, &QPushButton::clicked, this, &MainWindow::cancelLoad);
  statusBar()->addPermanentWidget(loadBar_);
  statusBar()->addPermanentWidget(loadCancelButton_);
  hoverLabel_->setText(tr("Open a log (Ctrl+O) or drop one on the window."));

  createActions();
  createDocks();
  createMenus();
  restoreWindowState();
  // The reference editor (its undo stack moves to the Document): its edits are the reference.
  ui::ReferenceEditor* editor = installReferenceEditor(this, view_);
  connect(editor, &ui::ReferenceEditor::referenceEdited, this, [this, editor] {
    reference_ = editor->reference();
    referencePath_ = editor->path();
    view_->setReferenceLines(reference_ ? ui::referencePolylines(*reference_)
                                        : std::vector<std::vector<Position>>{});
    updateSummary();
  });

  connect(view_, &ui::GridView::hoverText, hoverLabel_, &QLabel::setText);
  connect(view_, &ui::GridView::repainted, this, [this] {
    if (beamSettingsPending_ && !remap_->busy() && beamShown_.elapsed() >= kBeamIntervalMs)
      showBeamSettings();
  });
  connect(remap_, &ui::RemapController::mapped, this,
          [this](std::shared_ptr<const OccupancyMap> map, double ms, quint64, bool incremental) {
            fullMap_ = map;
            view_->setMap(std::move(map));
            onMapped(ms);
            // The panel shows what a re-map of the log costs, not a continuation while playing.
            if (!incremental) panel_->showRemapTime(ms);
          });
  // While a slow log re-maps, a change first shows a map on cells twice as large (a quarter of the
  // work); the full map replaces it (RemapController::setPreview).
  remap_->setPreview(kPreviewFactor, kPreviewAboveMs);
  connect(remap_, &ui::RemapController::previewed, this,
          [this](std::shared_ptr<const OccupancyMap> map, double ms, quint64) {
            view_->setMap(std::move(map));
            remapLabel_->setText(tr("preview at %1 cm (%2 ms)…")
                                     .arg(cellSize_ * kPreviewFactor * 100.0, 0, 'g', 3)
                                     .arg(ms, 0, 'f', 0));
          });
  connect(remap_, &ui::RemapController::failed, this, [this](const QString& message, quint64) {
    remapLabel_->setText(tr("mapping failed"));
    reportError(tr("Mapping failed"), logPath_ + QStringLiteral(": ") + message, false);
  });
  connect(remap_, &ui::RemapController::busyChanged, this, [this](bool busy) {
    if (busy) remapLabel_->setText(tr("mapping…"));
  });
  connect(timeline_, &ui::Timeline::timeChanged, this, &MainWindow::onTimeChanged);
  connect(timeline_, &ui::Timeline::playingChanged, this,
          [this](bool playing) { playAction_->setChecked(playing); });
  updateTitle();
}

MainWindow::~MainWindow() {
  if (rememberSettingsTimer_->isActive()) rememberSettings();
  if (load_) load_->cancel = true;
  // Every worker posts to this window: let each end (at its next block) before the window goes.
  for (QThread* t : loaders_) {
    t->wait();
    delete t;
  }
}

sg::MapperSettings MainWindow::lastSettings() {
  QSettings s;
  sg::MapperSettings out;
  const std::string model = s.value("mapping/model", "himm").toString().toStdString();
  const std::string rule = s.value("mapping/rule", "himm").toString().toStdString();
  if (makeSensorModel(model) && makeUpdateRule(rule) && compatibility(model, rule).allowed) {
    out.model = model;
    out.rule = rule;
  } else {
    out.model = "himm";
    out.rule = "himm";
  }
  out.parameters = defaultParameters(out.model, out.rule);
  s.beginGroup("mapping/parameters");
  for (const QString& key : s.childKeys()) {
    try {
      if (out.parameters.has(key.toStdString()))
        out.parameters.set(key.toStdString(), s.value(key).toDouble());
    } catch (const ParameterError&) {
      // A value saved by another version may be out of today's range: keep the default.
    }
  }
  s.endGroup();
  out.pose = s.value("mapping/pose").toString() == QLatin1String("truth") ? PoseSource::Truth
                                                                          : PoseSource::Odometry;
  return out;
}

double MainWindow::lastCellSize() {
  const double c = QSettings().value("mapping/cell", 0.05).toDouble();
  return c >= 0.005 && c <= 1.0 ? c : 0.05;
}

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

  fitAction_ = new QAction(tr("&Fit to Map"), this);
  fitAction_->setShortcut(QKeySequence(tr("Ctrl+0")));
  connect(fitAction_, &QAction::triggered, view_, &ui::GridView::fitToMap);

  const std::pair<ui::Overlay, QString> overlays[] = {
      {ui::Overlay::Reference, tr("&Reference Map")},
      {ui::Overlay::Path, tr("Robot &Path")},
      {ui::Overlay::Robot, tr("R&obot")},
      {ui::Overlay::Beams, tr("Current &Beams")},
      {ui::Overlay::Ring, tr("Sonar R&ing")},
      {ui::Overlay::Legend, tr("&Legend")}};
  const auto saved = QSettings().value("view/overlays", int(ui::kAllOverlays)).toInt();
  view_->setOverlays(ui::Overlays::fromInt(saved));
  int key = 1;
  for (const auto& [overlay, title] : overlays) {
    auto* a = new QAction(title, this);
    a->setCheckable(true);
    a->setChecked(view_->overlays().testFlag(overlay));
    a->setShortcut(QKeySequence(QStringLiteral("Alt+%1").arg(key++)));
    connect(a, &QAction::toggled, this, [this, o = overlay](bool on) {
      view_->setOverlay(o, on);
      QSettings().setValue("view/overlays", int(view_->overlays().toInt()));
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

void MainWindow::createDocks() {
  timeline_ = new ui::Timeline(this);
  auto* timelineDock = new QDockWidget(tr("Timeline"), this);
  timelineDock->setObjectName(QStringLiteral("timelineDock"));
  timelineDock->setWidget(timeline_);
  timelineDock->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable |
                            QDockWidget::DockWidgetClosable);
  addDockWidget(Qt::BottomDockWidgetArea, timelineDock);
  connect(playAction_, &QAction::toggled, timeline_, &ui::Timeline::setPlaying);
  connect(stepForwardAction_, &QAction::triggered, timeline_, &ui::Timeline::stepForward);
  connect(stepBackAction_, &QAction::triggered, timeline_, &ui::Timeline::stepBackward);

  summary_ = new QLabel(this);
  summary_->setTextFormat(Qt::RichText);
  summary_->setAlignment(Qt::AlignTop | Qt::AlignLeft);
  summary_->setMargin(8);
  summary_->setMinimumWidth(220);
  summary_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  auto* summaryDock = new QDockWidget(tr("Map"), this);
  summaryDock->setObjectName(QStringLiteral("mapDock"));
  summaryDock->setWidget(summary_);

  // The parameter panel: its changes come back through setMapperSettings, which shows them
  // everywhere else (the panel itself ignores settings it already holds).
  panel_ = new ui::ParameterPanel(this);
  panel_->setSettings(settings_);
  connect(panel_, &ui::ParameterPanel::settingsChanged, this, &MainWindow::setMapperSettings);
  auto* panelDock = new QDockWidget(tr("Parameters"), this);
  panelDock->setObjectName(QStringLiteral("parametersDock"));
  panelDock->setWidget(panel_);
  panelDock->toggleViewAction()->setShortcut(QKeySequence(tr("Ctrl+Shift+P")));

  // The beam-model view of one reading of the current scan, with the panel's model.
  auto* beamHost = new QWidget(this);
  beamView_ = new ui::BeamModelView(beamHost);
  beamView_->setSettings(settings_);
  readingChooser_ = new QComboBox(beamHost);
  readingChooser_->setObjectName(QStringLiteral("readingChooser"));
  readingChooser_->setToolTip(
      tr("The reading of the current scan whose beam is drawn; its beam "
         "is highlighted in the grid view"));
  readingChooser_->setSizeAdjustPolicy(QComboBox::AdjustToContents);
  connect(readingChooser_, &QComboBox::activated, this, [this](int index) {
    chooseBeamSonar(readingChooser_->itemData(index).value<std::size_t>());
  });
  auto* readingLabel = new QLabel(tr("Current scan's r&eading:"), beamHost);
  readingLabel->setBuddy(readingChooser_);
  auto* readingRow = new QHBoxLayout;
  // Lined up with the beam view's own controls below.
  const QMargins inner = beamView_->layout()->contentsMargins();
  readingRow->setContentsMargins(inner.left(), 0, inner.right(), 0);
  readingRow->addWidget(readingLabel);
  readingRow->addWidget(readingChooser_);
  readingRow->addStretch(1);
  auto* beamLayout = new QVBoxLayout(beamHost);
  beamLayout->setContentsMargins(0, 4, 0, 0);
  beamLayout->addLayout(readingRow);
  beamLayout->addWidget(beamView_, 1);
  auto* beamDock = new QDockWidget(tr("Beam Model"), this);
  beamDock->setObjectName(QStringLiteral("beamModelDock"));
  beamDock->setWidget(beamHost);
  beamDock->toggleViewAction()->setShortcut(QKeySequence(tr("Ctrl+Shift+B")));

  // Right of the grid: the beam view (the map summary tabbed behind it), then the panel.
  addDockWidget(Qt::RightDockWidgetArea, beamDock);
  splitDockWidget(beamDock, panelDock, Qt::Horizontal);
  tabifyDockWidget(beamDock, summaryDock);
  beamDock->raise();
  resizeDocks({beamDock, panelDock}, {350, 340}, Qt::Horizontal);
  updateSummary();
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
  file->addAction(exportViewPngAction_);
  file->addAction(exportViewSvgAction_);
  file->addAction(exportMapPngAction_);
  file->addAction(exportRosAction_);
  file->addSeparator();
  QAction* quit = file->addAction(tr("&Quit"));
  quit->setShortcut(QKeySequence::Quit);
  connect(quit, &QAction::triggered, this, &QWidget::close);
  recent_ = QSettings().value("files/recent").toStringList();
  rebuildRecentMenu();

  QMenu* view = menuBar()->addMenu(tr("&View"));
  view->addAction(fitAction_);
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
  connect(guide, &QAction::triggered, this, &MainWindow::showUserGuide);
  QAction* keys = help->addAction(tr("&Keyboard Shortcuts"));
  keys->setShortcut(QKeySequence(tr("Ctrl+/")));
  connect(keys, &QAction::triggered, this, &MainWindow::showShortcuts);
  connect(help->addAction(tr("&About SonarGrid")), &QAction::triggered, this,
          &MainWindow::showAbout);
  // Shortcuts of hidden docks' actions still work when they live on the window.
  addActions({playAction_, stepForwardAction_, stepBackAction_});
}

void MainWindow::rebuildMappingMenu() {
  menuSettings_ = settings_;
  modelMenu_->clear();
  ruleMenu_->clear();
  // The previous groups go with their actions (clear() deletes only the actions).
  qDeleteAll(modelMenu_->findChildren<QActionGroup*>(Qt::FindDirectChildrenOnly));
  qDeleteAll(ruleMenu_->findChildren<QActionGroup*>(Qt::FindDirectChildrenOnly));
  auto* models = new QActionGroup(modelMenu_);
  for (const std::string& name : sensorModelNames()) {
    QAction* a = modelMenu_->addAction(QString::fromStdString(sensorModelInfo(name).title));
    a->setCheckable(true);
    a->setChecked(name == settings_.model);
    models->addAction(a);
    connect(a, &QAction::triggered, this,
            [this, n = QString::fromStdString(name)] { chooseModel(n); });
  }
  auto* rules = new QActionGroup(ruleMenu_);
  for (const std::string& name : updateRuleNames()) {
    QAction* a = ruleMenu_->addAction(QString::fromStdString(updateRuleInfo(name).title));
    a->setCheckable(true);
    a->setChecked(name == settings_.rule);
    const Compatibility c = compatibility(settings_.model, name);
    a->setEnabled(c.allowed);
    if (!c.allowed) a->setToolTip(QString::fromStdString(c.reason));
    rules->addAction(a);
    connect(a, &QAction::triggered, this,
            [this, n = QString::fromStdString(name)] { chooseRule(n); });
  }
  ruleMenu_->setToolTipsVisible(true);
  for (QAction* a : poseGroup_->actions()) a->setChecked(a->data() == poseName(settings_.pose));
}

void MainWindow::chooseModel(const QString& model) {
  MapperSettings s = settings_;
  s.model = model.toStdString();
  if (!compatibility(s.model, s.rule).allowed) {
    for (const std::string& rule : updateRuleNames())
      if (compatibility(s.model, rule).allowed) {
        s.rule = rule;
        break;
      }
  }
  s.parameters = carryParameters(s.model, s.rule, settings_.parameters);
  setMapperSettings(s);
}

void MainWindow::chooseRule(const QString& rule) {
  MapperSettings s = settings_;
  s.rule = rule.toStdString();
  s.parameters = carryParameters(s.model, s.rule, settings_.parameters);
  setMapperSettings(s);
}

void MainWindow::choosePose(PoseSource pose) {
  MapperSettings s = settings_;
  s.pose = pose;
  setMapperSettings(s);
}

namespace {
bool sameSettings(const MapperSettings& a, const MapperSettings& b) {
  return a.model == b.model && a.rule == b.rule && a.pose == b.pose && a.parameters == b.parameters;
}
}  // namespace

void MainWindow::setMapperSettings(const MapperSettings& settings) {
  settings_ = settings;
  showSettings();
  // The same settings again (a menu item that is already checked, a panel echo) map nothing new.
  if (data_ && sameSettings(settings, remap_->settings())) return;
  remap_->setSettings(settings);
}

void MainWindow::showSettings() {
  const MapperSettings& settings = settings_;
  // Writing QSettings syncs the file to disk, tens of ms on a busy machine: a slider dragged
  // across its range would stall the GUI thread on every step. Remembered once the user pauses.
  rememberSettingsTimer_->start();
  if (modelMenu_ && (settings.model != menuSettings_.model || settings.rule != menuSettings_.rule ||
                     settings.pose != menuSettings_.pose))
    rebuildMappingMenu();
  view_->setNativeName(QString::fromStdString(updateRuleInfo(settings.rule).nativeName));
  panel_->setSettings(settings);
  // The beam view's picture costs 5-10 ms of GUI thread, and on two cores every ms of it is taken
  // from the re-map: drawn once the grid shows the new map, or kBeamIntervalMs after the change
  // (a long re-map of a big log), but not more often than every kBeamIntervalMs, so a dragged
  // slider moves it several times a second without slowing the map.
  if (data_) {
    beamSettingsPending_ = true;
    if (!beamSettingsTimer_->isActive()) beamSettingsTimer_->start();
  } else {
    beamView_->setSettings(settings);
  }
  // The robot, its path and the current beams depend on the pose source only: a parameter change
  // must not redraw them (and the grid's overlays) on every step of a dragged slider.
  if (scanShownPose_ != settings.pose) showCurrentScan();
  if (!summaryTimer_->isActive()) summaryTimer_->start();
  updateTitle();
}

void MainWindow::showBeamSettings() {
  beamSettingsTimer_->stop();
  beamSettingsPending_ = false;
  beamShown_.restart();
  beamView_->setSettings(settings_);
}

void MainWindow::rememberSettings() {
  rememberSettingsTimer_->stop();
  QSettings s;
  s.setValue("mapping/model", QString::fromStdString(settings_.model));
  s.setValue("mapping/rule", QString::fromStdString(settings_.rule));
  s.setValue("mapping/pose", poseName(settings_.pose));
  s.remove("mapping/parameters");
  s.beginGroup("mapping/parameters");
  for (const auto& [name, value] : settings_.parameters.values())
    s.setValue(QString::fromStdString(name), value);
  s.endGroup();
}

void MainWindow::setCellSize(double metres) {
  cellSize_ = metres;
  QSettings().setValue("mapping/cell", metres);
  if (data_) remap_->setDataset(data_, cellSize_);
}

bool MainWindow::reportError(const QString& title, const QString& message, bool quiet) {
  if (quiet || QApplication::platformName() == QLatin1String("offscreen"))
    std::cerr << "sonargrid: " << message.toStdString() << '\n';
  else
    QMessageBox::critical(this, title, message);
  return false;
}

bool MainWindow::openLog(const QString& path, bool quiet) {
  if (!quiet && needsColumns(path)) return importCsv(path);
  loadLog(path, LogOptions{}, quiet);
  return !quiet || waitForLoad();
}

bool MainWindow::importCsv(const QString& path) {
  ui::CsvImportDialog dialog(path, this);
  if (dialog.exec() != QDialog::Accepted || !dialog.options()) return false;
  loadLog(path, *dialog.options());
  return true;
}

void MainWindow::loadLog(const QString& path, const LogOptions& options, bool quiet) {
  cancelLoad();
  auto job = std::make_shared<LoadJob>();
  job->path = path;
  job->quiet = quiet;
  load_ = job;
  LogOptions o = options;
  o.cancel = &job->cancel;
  // Called on the worker after each block: post a whole-percent change to the GUI thread.
  o.progress = [this, job](std::uint64_t done, std::uint64_t total) {
    if (total == 0) return;
    const int percent = static_cast<int>(done * 100 / total);
    if (job->lastPercent.exchange(percent) == percent) return;
    QMetaObject::invokeMethod(
        this, [this, job, percent] { showLoadProgress(job, percent); }, Qt::QueuedConnection);
  };
  QThread* worker = QThread::create([this, job, o, file = QDir::toNativeSeparators(path),
                                     pose = settings_.pose, cell = cellSize_] {
    std::shared_ptr<const Dataset> loaded;
    QString error;
    bool cancelled = false;
    try {
      loaded = std::make_shared<const Dataset>(readLog(file.toStdString(), o));
      // A log no grid can hold (a pose at 1e12 m) is refused here, so that the document open
      // before stays; the pose source is the one adoptLog will map with.
      try {
        loaded->fittingGrid(pose == PoseSource::Truth && loaded->hasTruth() ? PoseSource::Truth
                                                                            : PoseSource::Odometry,
                            cell);
      } catch (const GridLimitError& e) {
        throw e.inFile(file.toStdString());
      }
    } catch (const LoadCancelled&) {
      cancelled = true;
    } catch (const std::exception& e) {
      error = QString::fromStdString(e.what());
    }
    QMetaObject::invokeMethod(
        this,
        [this, job, loaded = std::move(loaded), error, cancelled]() mutable {
          finishLoad(job, std::move(loaded), error, cancelled);
        },
        Qt::QueuedConnection);
  });
  loaders_.push_back(worker);
  connect(worker, &QThread::finished, this, [this, worker] {
    loaders_.erase(std::remove(loaders_.begin(), loaders_.end(), worker), loaders_.end());
    worker->deleteLater();
  });
  loadBar_->setValue(0);
  const QString name = loadBar_->fontMetrics().elidedText(QFileInfo(path).fileName(),
                                                          Qt::ElideMiddle, loadBar_->width() / 2);
  loadBar_->setFormat(tr("Loading %1: %p%").arg(name));
  loadBar_->setVisible(true);
  loadCancelButton_->setVisible(true);
  cancelLoadAction_->setEnabled(true);
  worker->start();
}

void MainWindow::cancelLoad() {
  if (!load_) return;
  const QString path = load_->path;
  load_->cancel = true;
  load_.reset();
  hideLoadProgress();
  statusBar()->showMessage(tr("Loading %1 cancelled").arg(QFileInfo(path).fileName()), 5000);
  emit loadCancelled(path);
}

bool MainWindow::waitForLoad(int timeoutMs) {
  QElapsedTimer clock;
  clock.start();
  while (load_ && (timeoutMs < 0 || clock.elapsed() < timeoutMs))
    QCoreApplication::processEvents(QEventLoop::AllEvents | QEventLoop::WaitForMoreEvents, 50);
  return !load_ && lastLoadSucceeded_;
}

void MainWindow::showLoadProgress(const std::shared_ptr<LoadJob>& job, int percent) {
  if (job != load_) return;
  loadBar_->setValue(percent);
  emit loadProgress(percent);
}

void MainWindow::hideLoadProgress() {
  loadBar_->setVisible(false);
  loadCancelButton_->setVisible(false);
  cancelLoadAction_->setEnabled(false);
}

void MainWindow::finishLoad(const std::shared_ptr<LoadJob>& job,
                            std::shared_ptr<const Dataset> dataset, const QString& error,
                            bool cancelled) {
  if (job != load_) return;  // cancelled or replaced: its outcome no longer matters
  load_.reset();
  hideLoadProgress();
  lastLoadSucceeded_ = false;
  if (cancelled) {  // cancel flag set by someone holding the job (the window clears load_ first)
    emit loadCancelled(job->path);
    return;
  }
  QString message = error;
  if (message.isEmpty() && dataset->scans.empty())
    message = job->path + tr(": the log holds no scans");
  if (!message.isEmpty()) {
    reportError(tr("Cannot open log"), message, job->quiet);
    emit loadFailed(job->path, message);
    return;
  }
  lastLoadSucceeded_ = true;
  adoptLog(job->path, std::move(dataset));
  emit loaded(job->path);
}

void MainWindow::adoptLog(const QString& path, std::shared_ptr<const Dataset> dataset) {
  data_ = std::move(dataset);
  logPath_ = path;
  rememberRecent(path);
  QSettings().setValue("files/lastDirectory", QFileInfo(path).absolutePath());

  // A reference map beside the log (room.sglog + room.json) is taken along unless one is loaded.
  const QString sibling = QFileInfo(path).path() + QDir::separator() +
                          QFileInfo(path).completeBaseName() + QStringLiteral(".json");
  if (!reference_ && QFileInfo::exists(sibling)) openReference(sibling, true);

  if (settings_.pose == PoseSource::Truth && !data_->hasTruth())
    settings_.pose = PoseSource::Odometry;
  std::vector<double> times;
  double end = 0.0;
  times.reserve(data_->scans.size());
  for (const Scan& scan : data_->scans) {
    times.push_back(scan.time);
    end = std::max(end, scan.time);
    for (const Reading& r : scan.readings) end = std::max(end, r.time);
  }
  {
    const QSignalBlocker block(timeline_);
    timeline_->setScanTimes(std::move(times), end);
  }
  hoverLabel_->setText(tr("Hover over the grid to read a cell; drag to pan, wheel to zoom."));
  chosenSonar_.reset();
  beamView_->setMaxRange(data_->ring.maxRange);
  scanShownPose_.reset();  // a new log: its scan must be drawn
  showSettings();
  remap_->start(data_, cellSize_, settings_, timeline_->time());
}

bool MainWindow::openReference(const QString& path, bool quiet) {
  try {
    reference_ = readReference(QDir::toNativeSeparators(path).toStdString());
  } catch (const std::exception& e) {
    return reportError(tr("Cannot open reference map"), QString::fromStdString(e.what()), quiet);
  }
  referencePath_ = path;
  view_->setReferenceLines(ui::referencePolylines(*reference_));
  updateSummary();
  if (auto* editor = findChild<ui::ReferenceEditor*>()) editor->setReference(reference_, path);
  return true;
}

bool MainWindow::waitForMap(int timeoutMs) {
  QElapsedTimer clock;
  clock.start();
  bool done = false, failed = false;
  const auto a =
      connect(remap_, &ui::RemapController::mapped, this,
              [&](auto, double, quint64 g, bool) { done = g == remap_->latestGeneration(); });
  const auto b = connect(remap_, &ui::RemapController::failed, this,
                         [&](const QString&, quint64) { failed = true; });
  while (!done && !failed && clock.elapsed() < timeoutMs && (remap_->busy() || !view_->map())) {
    QCoreApplication::processEvents(QEventLoop::AllEvents, 50);
  }
  disconnect(a);
  disconnect(b);
  return !failed && view_->map() && !remap_->busy();
}

void MainWindow::onMapped(double elapsedMs) {
  lastRemapMs_ = elapsedMs;
  remapLabel_->setText(tr("re-mapped in %1 ms").arg(elapsedMs, 0, 'f', 1));
  // The summary's rich text is laid out again on every change (a few ms): a few times a second is
  // all a reader needs while a slider is dragged.
  if (!summaryTimer_->isActive()) summaryTimer_->start();
}

void MainWindow::onTimeChanged(double t, std::size_t) {
  if (!data_) return;
  showCurrentScan();
  remap_->setUntil(t);
}

void MainWindow::showCurrentScan() {
  if (!data_) return;
  scanShownPose_ = settings_.pose;
  const std::size_t scan = timeline_->currentScan();
  view_->setRobotAt(data_.get(), settings_.pose, scan);
  const std::vector<Reading>& readings = data_->scans[scan].readings;
  // The user's sonar while this scan has a reading of it, else the first reading with an echo.
  const Reading* shown = nullptr;
  for (const Reading& r : readings)
    if (chosenSonar_ == static_cast<std::size_t>(r.sonar)) shown = &r;
  for (const Reading& r : readings)
    if (!shown && r.echo()) shown = &r;
  if (!shown && !readings.empty()) shown = &readings.front();

  const QSignalBlocker block(readingChooser_);
  readingChooser_->clear();
  for (const Reading& r : readings) {
    readingChooser_->addItem(r.echo() ? tr("sonar %1: %2 m").arg(r.sonar).arg(r.range, 0, 'f', 2)
                                      : tr("sonar %1: no echo").arg(r.sonar),
                             QVariant::fromValue(static_cast<std::size_t>(r.sonar)));
    if (&r == shown) readingChooser_->setCurrentIndex(readingChooser_->count() - 1);
  }
  readingChooser_->setEnabled(!readings.empty());
  beamSonar_ = shown ? std::optional<std::size_t>(shown->sonar) : std::nullopt;
  view_->setHighlightedSonar(beamSonar_);
  // No echo: the model's picture of a reading at the maximum range.
  if (shown) beamView_->setRange(shown->echo() ? shown->range : data_->ring.maxRange);
}

bool MainWindow::chooseBeamSonar(std::size_t sonar) {
  if (!data_) return false;
  for (const Reading& r : data_->scans[timeline_->currentScan()].readings)
    if (r.sonar == sonar) {
      chosenSonar_ = sonar;
      showCurrentScan();
      return true;
    }
  return false;
}

void MainWindow::updateSummary() {
  if (!summary_) return;
  QString html;
  if (!data_) {
    html =
        tr("<p>No log loaded.</p><p>File ▸ Open Log (Ctrl+O), File ▸ Open Example, or drop a "
           "<code>.sglog</code> file on the window.</p>");
  } else {
    const auto map = view_->map();
    html = QStringLiteral("<b>%1</b><br>%2 scans, %3 readings<br>%4 sonars (%5)")
               .arg(QFileInfo(logPath_).fileName().toHtmlEscaped())
               .arg(data_->scans.size())
               .arg(data_->readingCount())
               .arg(data_->ring.size())
               .arg(QString::fromStdString(data_->ring.robot).toHtmlEscaped());
    html += QStringLiteral("<hr><b>%1</b><br>× <b>%2</b><br>pose: %3")
                .arg(QString::fromStdString(sensorModelInfo(settings_.model).title).toHtmlEscaped())
                .arg(QString::fromStdString(updateRuleInfo(settings_.rule).title).toHtmlEscaped())
                .arg(settings_.pose == PoseSource::Truth ? tr("true pose") : tr("odometry"));
    if (map) {
      html += QStringLiteral("<hr>grid %1 × %2 cells of %3 m<br>%4 cells filled<br>re-map %5 ms")
                  .arg(map->spec.width)
                  .arg(map->spec.height)
                  .arg(map->spec.cellSize)
                  .arg(map->filledCount())
                  .arg(lastRemapMs_, 0, 'f', 1);
    }
    if (reference_)
      html += QStringLiteral("<hr>reference: %1 (%2 objects)")
                  .arg(QFileInfo(referencePath_).fileName().toHtmlEscaped())
                  .arg(reference_->objects.size());
  }
  summary_->setText(html);
}

void MainWindow::updateTitle() {
  setWindowTitle(data_ ? QStringLiteral("%1 — %2 × %3 — SonarGrid")
                             .arg(QFileInfo(logPath_).fileName(),
                                  QString::fromStdString(settings_.model),
                                  QString::fromStdString(settings_.rule))
                       : QStringLiteral("SonarGrid"));
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
    connect(a, &QAction::triggered, this, [this, path] { openLog(path); });
  }
  recentMenu_->setEnabled(!recent_.isEmpty());
}

void MainWindow::restoreWindowState() {
  QSettings s;
  if (!restoreGeometry(s.value("window/geometry").toByteArray())) resize(1280, 800);
  restoreState(s.value("window/state").toByteArray());
}

void MainWindow::closeEvent(QCloseEvent* event) {
  if (rememberSettingsTimer_->isActive()) rememberSettings();
  QSettings s;
  s.setValue("window/geometry", saveGeometry());
  s.setValue("window/state", saveState());
  QMainWindow::closeEvent(event);
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
    if (isReferenceFile(path))
      openReference(path);
    else
      openLog(path);
  }
  event->acceptProposedAction();
}

void MainWindow::openLogDialog() {
  const QString dir = QSettings().value("files/lastDirectory", QDir::homePath()).toString();
  const QString path = QFileDialog::getOpenFileName(
      this, tr("Open Log"), dir,
      tr("Sonar logs (*.sglog *.clf *.carmen *.log *.playerlog *.csv *.txt *.tsv);;"
         "All files (*)"));
  if (!path.isEmpty()) openLog(path);
}

void MainWindow::importCsvDialog() {
  const QString dir = QSettings().value("files/lastDirectory", QDir::homePath()).toString();
  const QString path = QFileDialog::getOpenFileName(
      this, tr("Import CSV"), dir, tr("CSV and text logs (*.csv *.txt *.tsv);;All files (*)"));
  if (!path.isEmpty()) importCsv(path);
}

void MainWindow::openReferenceDialog() {
  const QString dir = QSettings().value("files/lastDirectory", QDir::homePath()).toString();
  const QString path =
      QFileDialog::getOpenFileName(this, tr("Open Reference Map"), dir,
                                   tr("Reference maps (*.json *.map *.yaml *.yml);;All files (*)"));
  if (!path.isEmpty()) openReference(path);
}

void MainWindow::openExample() {
  const QString dir = bundledDatasetsDirectory();
  if (dir.isEmpty()) {
    reportError(tr("No examples"), tr("The bundled datasets were not found."), false);
    return;
  }
  const QString path =
      QFileDialog::getOpenFileName(this, tr("Open Example"), dir, tr("SonarGrid logs (*.sglog)"));
  if (!path.isEmpty()) openLog(path);
}

QString MainWindow::saveFileName(const QString& title, const QString& filter,
                                 const QString& suffix) {
  QSettings s;
  const QString base = data_ ? QFileInfo(logPath_).completeBaseName() + QStringLiteral("-") +
                                   QString::fromStdString(settings_.model)
                             : QStringLiteral("sonargrid");
  const QString dir = s.value("files/exportDirectory", QDir::homePath()).toString();
  QString path =
      QFileDialog::getSaveFileName(this, title, dir + QDir::separator() + base + suffix, filter);
  if (path.isEmpty()) return path;
  if (!path.endsWith(suffix, Qt::CaseInsensitive)) path += suffix;
  s.setValue("files/exportDirectory", QFileInfo(path).absolutePath());
  return path;
}

bool MainWindow::mapComplete() {
  // A preview (coarser cells) or a run still going must not end up in a file: wait for the map of
  // the current settings.
  if (remap_->busy()) {
    QApplication::setOverrideCursor(Qt::WaitCursor);
    waitForMap(10 * 60 * 1000);
    QApplication::restoreOverrideCursor();
  }
  if (view_->map() && view_->map() == fullMap_) return true;
  reportError(tr("Export"),
              tr("The map of the current settings is not complete (only its preview is shown, or "
                 "mapping failed). Export again once the status bar says \"re-mapped\"."),
              false);
  return false;
}

void MainWindow::exportViewPng() {
  if (data_ && !mapComplete()) return;
  const QString path = saveFileName(tr("Export View as PNG"), tr("PNG images (*.png)"), ".png");
  if (path.isEmpty()) return;
  const QByteArray png = app::encodedImage(view_->renderImage(), "PNG");
  const QString error = png.isEmpty() ? path + tr(": the image cannot be encoded as PNG")
                                      : app::writeFileBytes(path, png);
  if (!error.isEmpty()) reportError(tr("Export failed"), error, false);
}

void MainWindow::exportViewSvg() {
  if (data_ && !mapComplete()) return;
  const QString path = saveFileName(tr("Export View as SVG"), tr("SVG drawings (*.svg)"), ".svg");
  if (path.isEmpty()) return;
  QByteArray bytes;
  QBuffer buffer(&bytes);
  buffer.open(QIODevice::WriteOnly);
  QSvgGenerator svg;
  svg.setOutputDevice(&buffer);
  svg.setSize(view_->size());
  svg.setViewBox(QRect(QPoint(0, 0), view_->size()));
  svg.setTitle(windowTitle());
  svg.setDescription(tr("Occupancy grid exported by SonarGrid"));
  QPainter painter;
  if (!painter.begin(&svg)) {
    reportError(tr("Export failed"), path + tr(": the drawing cannot be made"), false);
    return;
  }
  view_->paintVector(painter);
  painter.end();
  if (const QString error = app::writeFileBytes(path, bytes); !error.isEmpty())
    reportError(tr("Export failed"), error, false);
}

void MainWindow::exportMapPng() {
  if (!view_->map() || !mapComplete()) return;
  const QString path = saveFileName(tr("Export Map as PNG"), tr("PNG images (*.png)"), ".png");
  if (!path.isEmpty()) exportMapPngTo(path);
}

bool MainWindow::exportMapPngTo(const QString& path) {
  if (!view_->map() || !mapComplete()) return false;
  try {
    PngOptions o;
    o.legend = true;
    o.scale = std::max(1, static_cast<int>(std::lround(0.2 / fullMap_->spec.cellSize)));
    writeMapPng(*fullMap_, QDir::toNativeSeparators(path).toStdString(), o);
    return true;
  } catch (const std::exception& e) {
    return reportError(tr("Export failed"), QString::fromStdString(e.what()), false);
  }
}

void MainWindow::exportRosMap() {
  if (!view_->map() || !mapComplete()) return;
  QString path =
      saveFileName(tr("Export Map for ROS map_server"), tr("map_server YAML (*.yaml)"), ".yaml");
  if (path.isEmpty()) return;
  path.chop(5);  // writeRosMap adds .yaml and .pgm
  try {
    writeRosMap(*view_->map(), QDir::toNativeSeparators(path).toStdString());
  } catch (const std::exception& e) {
    reportError(tr("Export failed"), QString::fromStdString(e.what()), false);
  }
}

void MainWindow::showUserGuide() {
  QFile file(QStringLiteral(":/sonargrid/user-guide.md"));
  file.open(QIODevice::ReadOnly);
  auto* dialog = new QDialog(this);
  dialog->setAttribute(Qt::WA_DeleteOnClose);
  dialog->setWindowTitle(tr("SonarGrid User Guide"));
  auto* text = new QTextBrowser(dialog);
  text->setOpenExternalLinks(true);
  text->setMarkdown(QString::fromUtf8(file.readAll()));
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Close, dialog);
  connect(buttons, &QDialogButtonBox::rejected, dialog, &QDialog::close);
  auto* layout = new QVBoxLayout(dialog);
  layout->addWidget(text);
  layout->addWidget(buttons);
  dialog->resize(720, 640);
  dialog->show();
}

void MainWindow::showShortcuts() {
  // Every menu action with a shortcut, read from the menus so that the list cannot go stale, then
  // the keys and gestures the grid view handles itself.
  QList<QPair<QString, QString>> rows;
  for (QAction* menu : menuBar()->actions()) {
    if (!menu->menu()) continue;
    for (QAction* a : menu->menu()->actions())
      if (!a->shortcut().isEmpty())
        rows.append({a->text().remove('&'), a->shortcut().toString(QKeySequence::NativeText)});
  }
  rows.append({tr("Zoom in / out"), tr("+ / −, mouse wheel, pinch")});
  rows.append({tr("Pan"), tr("arrow keys, drag with the left or middle button")});
  rows.append({tr("Fit to map"), tr("F, Home, double-click")});
  rows.append({tr("Move a parameter slider"), tr("arrows, Page Up / Down, Home / End")});
  auto* dialog = new QDialog(this);
  dialog->setAttribute(Qt::WA_DeleteOnClose);
  dialog->setWindowTitle(tr("Keyboard Shortcuts"));
  auto* table = new QTableWidget(static_cast<int>(rows.size()), 2, dialog);
  table->setHorizontalHeaderLabels({tr("Action"), tr("Keys")});
  table->verticalHeader()->hide();
  table->setEditTriggers(QAbstractItemView::NoEditTriggers);
  for (int i = 0; i < rows.size(); ++i) {
    table->setItem(i, 0, new QTableWidgetItem(rows[i].first));
    table->setItem(i, 1, new QTableWidgetItem(rows[i].second));
  }
  table->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Close, dialog);
  connect(buttons, &QDialogButtonBox::rejected, dialog, &QDialog::close);
  auto* layout = new QVBoxLayout(dialog);
  layout->addWidget(table);
  layout->addWidget(buttons);
  dialog->resize(520, 560);
  dialog->show();
}

void MainWindow::showAbout() {
  QMessageBox::about(
      this, tr("About SonarGrid"),
      tr("<b>SonarGrid %1</b><p>A workbench for sonar occupancy-grid mapping: five inverse sensor "
         "models, seven update rules, 16 certainty levels.</p>")
          .arg(QApplication::applicationVersion()));
}

}  // namespace sg::app
