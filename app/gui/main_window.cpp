// SPDX-License-Identifier: GPL-3.0-or-later
#include "main_window.h"

#include <QAction>
#include <QApplication>
#include <QCloseEvent>
#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QFileInfo>
#include <QMessageBox>
#include <QSettings>
#include <QStatusBar>
#include <QTimer>
#include <algorithm>
#include <iostream>

#include "autosave.h"
#include "beam_dock.h"
#include "beam_model_view.h"
#include "csv_import_dialog.h"
#include "document.h"
#include "log_loader.h"
#include "main_window_metrics.h"
#include "main_window_sweep.h"
#include "map_dock.h"
#include "parameter_panel.h"
#include "preferences.h"
#include "reference_editing.h"
#include "remap_controller.h"
#include "robot/robot_dock.h"
#include "sonargrid/engine/sensor_model.h"
#include "sonargrid/engine/update_rule.h"
#include "sonargrid/forward/catalog.h"
#include "sonargrid/io/log_reader.h"
#include "sonargrid/reference/read_reference.h"
#include "status_report.h"
#include "timeline.h"

// The window's resources live in this static library; a static library's resource initialiser
// must be called by name (and outside any namespace).
static void initialiseResources() {
  Q_INIT_RESOURCE(sonargrid);
}

namespace sg::app {
namespace {

QString poseName(PoseSource p) {
  return p == PoseSource::Truth ? QStringLiteral("truth") : QStringLiteral("odom");
}

}  // namespace

MainWindow::MainWindow(ui::GridView::Backend backend, QWidget* parent)
    : QMainWindow(parent),
      document_(new Document(this)),
      loader_(new LogLoader(this)),
      view_(new ui::GridView(backend, this)),
      remap_(new ui::RemapController(this)),
      status_(new StatusReport(statusBar())) {
  initialiseResources();
  setWindowIcon(QIcon(QStringLiteral(":/sonargrid/sonargrid.svg")));
  setCentralWidget(view_);
  setAcceptDrops(true);
  // A new document starts from what the user chose last (the preferences' memory of it).
  ProjectState initial;
  initial.settings = lastSettings();
  initial.cellSize = lastCellSize();
  initial.overlays = ui::Overlays::fromInt(
      QSettings().value("view/overlays", int(ui::kAllOverlays.toInt())).toInt());
  document_->restore(initial);
  view_->setOverlays(initial.overlays);
  rememberSettingsTimer_ = new QTimer(this);
  rememberSettingsTimer_->setSingleShot(true);
  rememberSettingsTimer_->setInterval(1000);
  connect(rememberSettingsTimer_, &QTimer::timeout, this, &MainWindow::rememberSettings);

  connect(status_, &StatusReport::cancelLoadClicked, this, &MainWindow::cancelLoad);
  status_->setHint(tr("Open a log (Ctrl+O) or drop one on the window."));

  createActions();
  createDocks();
  createInspector();
  createMenus();
  installRobotMenu(this);
  installReferenceEditor(this);
  installMetrics(this);
  installSweepView(this);
  restoreWindowState();
  connectDocument();

  connect(loader_, &LogLoader::progress, this, [this](int percent) {
    status_->loadProgress(percent);
    emit loadProgress(percent);
  });
  connect(loader_, &LogLoader::loaded, this,
          [this](const QString& path, std::shared_ptr<const ScanSource> source,
                 const LogReading& reading, bool) {
            hideLoadProgress();
            lastLoadSucceeded_ = true;
            adoptLog(path, std::move(source), reading);
            emit loaded(path);
          });
  connect(loader_, &LogLoader::failed, this, &MainWindow::onLoadFailed);
  connect(loader_, &LogLoader::cancelled, this, [this](const QString& path) {
    hideLoadProgress();
    lastLoadSucceeded_ = false;
    pendingProject_.reset();
    emit loadCancelled(path);
  });

  connect(view_, &ui::GridView::hoverText, status_, &StatusReport::setHint);
  connect(view_, &ui::GridView::repainted, this,
          [this] { beamDock_->gridRepainted(remap_->busy()); });
  connect(view_, &ui::GridView::viewChanged, this, [this] { document_->setView(view_->view()); });
  connect(remap_, &ui::RemapController::mapped, this,
          [this](std::shared_ptr<const OccupancyMap> map, double ms, quint64, bool incremental) {
            view_->setMap(std::move(map));
            // A project's saved view replaces the fit of its first map.
            if (pendingView_) view_->setView(*std::exchange(pendingView_, std::nullopt));
            onMapped(ms);
            showForwardPrediction();  // the forward model's picture follows its new map
            // The panel shows what a re-map of the log costs, not a continuation while playing.
            if (!incremental) panel_->showRemapTime(ms);
          });
  // While a slow log re-maps, a change first shows a preview: cells twice as large, one scan in
  // N; the full map replaces it (RemapController::setPreview).
  remap_->setPreview(kPreviewFactor, kPreviewAboveMs);
  remap_->setPreviewBudget(kPreviewBudgetMs);
  applyEngine();
  connect(remap_, &ui::RemapController::previewed, this,
          [this](std::shared_ptr<const OccupancyMap> map, double ms, quint64, int stride) {
            view_->setMap(std::move(map));
            status_->previewed(document_->cellSize() * kPreviewFactor * 100.0, stride, ms);
          });
  connect(remap_, &ui::RemapController::failed, this, [this](const QString& message, quint64) {
    status_->mappingFailed();
    // A live robot's map has no file yet: the message says which map failed.
    const QString where =
        document_->logPath().isEmpty() ? tr("the live map") : document_->logPath();
    reportError(tr("Mapping failed"), where + QStringLiteral(": ") + message, false);
  });
  connect(remap_, &ui::RemapController::busyChanged, this, [this](bool busy) {
    if (busy) status_->mapping();
    if (!busy) status_->emEnded();  // done, stopped or failed
  });
  // The forward model's EM: its iterations in the status bar; Stop EM ends it.
  connect(remap_, &ui::RemapController::emProgress, this,
          [this](int iteration, int cap, double logLikelihood, quint64 generation) {
            if (generation == remap_->latestGeneration())
              status_->emProgress(iteration, cap, logLikelihood);
          });
  connect(status_, &StatusReport::stopEmClicked, remap_, &ui::RemapController::stop);
  connect(remap_, &ui::RemapController::cancelled, this, [this](quint64 generation, bool stopped) {
    if (stopped && generation == remap_->latestGeneration() &&
        forward::isForwardModel(remap_->settings().model))
      status_->emStopped();
  });
  connect(timeline_, &ui::Timeline::timeChanged, this, &MainWindow::onTimeChanged);
  connect(timeline_, &ui::Timeline::playingChanged, this,
          [this](bool playing) { actions_.play->setChecked(playing); });

  autosave_ = new Autosave(
      document_, [this] { return projectState(); }, this);
  connect(autosave_, &Autosave::failed, this,
          [this](const QString& message) { statusBar()->showMessage(message, 10000); });
  updateTitle();
}

MainWindow::~MainWindow() {
  if (rememberSettingsTimer_->isActive()) rememberSettings();
  // Its workers post to it: let each end before the window goes.
  delete loader_;
}

bool MainWindow::loading() const {
  return loader_->busy();
}

const std::shared_ptr<const sg::Dataset>& MainWindow::dataset() const {
  return document_->dataset();
}

ui::BeamModelView* MainWindow::beamModelView() const {
  return beamDock_->view();
}

ui::ForwardRangeView* MainWindow::forwardRangeView() const {
  return beamDock_->forwardView();
}

std::optional<std::size_t> MainWindow::beamSonar() const {
  return beamDock_->sonar();
}

const QString& MainWindow::logPath() const {
  return document_->logPath();
}

void MainWindow::applyEngine() {
  remap_->setPrecision(preferences::kFastEngine.value() ? Precision::Fast : Precision::Exact);
}

const sg::MapperSettings& MainWindow::mapperSettings() const {
  return document_->mapperSettings();
}

void MainWindow::setMapperSettings(const MapperSettings& settings, bool ruleNamed) {
  // A rule the user named: the panel shows it first, without saying that the rule changed with
  // the model; the document's change then finds the panel showing it already.
  if (ruleNamed) panel_->setSettings(settings, true);
  document_->setMapperSettings(settings);  // shows them (showSettings) before it returns
}

void MainWindow::setCellSize(double metres) {
  document_->setCellSize(metres);
}

void MainWindow::connectDocument() {
  connect(document_, &Document::settingsChanged, this, &MainWindow::onSettingsChanged);
  connect(document_, &Document::cellSizeChanged, this, &MainWindow::onCellSizeChanged);
  connect(document_, &Document::referenceChanged, this, &MainWindow::onReferenceChanged);
  connect(document_, &Document::startPoseChanged, this, &MainWindow::onStartPoseChanged);
  connect(document_, &Document::overlaysChanged, this, [this](ui::Overlays overlays) {
    view_->setOverlays(overlays);
    for (QAction* a : actions_.overlays) {
      const QSignalBlocker block(a);
      a->setChecked(overlays.testFlag(static_cast<ui::Overlay>(a->data().toInt())));
    }
    QSettings().setValue("view/overlays", int(overlays.toInt()));
  });
  connect(document_, &Document::viewChanged, this, [this] {
    if (document_->view() && *document_->view() != view_->view())
      view_->setView(*document_->view());
  });
  connect(document_, &Document::modifiedChanged, this, &QWidget::setWindowModified);
  connect(document_, &Document::projectPathChanged, this, &MainWindow::updateTitle);
  // The beam view's "Compare with" offers the pinned rows.
  connect(document_, &Document::pinnedRowsChanged, this, [this] {
    std::vector<ui::BeamModelView::NamedSettings> pinned;
    for (const PinnedRow& row : document_->pinnedRows())
      pinned.push_back({row.label, row.settings});
    if (beamDock_) beamDock_->view()->setPinnedConfigurations(std::move(pinned));
  });
}

void MainWindow::onStartPoseChanged() {
  // The loaded log's odometry moved (Document::setStartPose): its path, its scan and its map.
  if (!document_->source() || !document_->source()->complete()) return;
  scanShownPose_.reset();
  showCurrentScan();
  onReferenceChanged();  // the view fits the moved path and the reference
  remap_->start(document_->source(), document_->cellSize(), document_->mapperSettings(),
                timeline_->time());
}

void MainWindow::onSettingsChanged() {
  showSettings();
  // A log being opened: adoptLog() maps it once the document holds all of it.
  if (document_->source() && remap_->source() != document_->source()) return;
  const MapperSettings& settings = document_->mapperSettings();
  // The same settings again (a menu item that is already checked, a panel echo) map nothing new.
  if (document_->dataset() && remap_->mapsWith(settings)) return;
  remap_->setSettings(settings);
}

void MainWindow::onCellSizeChanged(double metres) {
  QSettings().setValue("mapping/cell", metres);
  mapDock_->setCellSize(metres);
  // Not while a log is being opened (adoptLog() maps it), nor for a live robot's map (its session
  // re-maps it).
  if (document_->source() && remap_->source() == document_->source())
    remap_->setSource(document_->source(), metres);
}

void MainWindow::onReferenceChanged() {
  const auto& reference = document_->reference();
  view_->setReferenceLines(reference ? ui::referencePolylines(*reference)
                                     : std::vector<std::vector<Position>>{});
  view_->setFocusArea(ui::focusArea(document_->dataset().get(), document_->mapperSettings().pose,
                                    reference ? &*reference : nullptr));
  updateSummary();
}

void MainWindow::showSettings() {
  const MapperSettings& settings = document_->mapperSettings();
  // Writing QSettings syncs the file to disk, tens of ms on a busy machine: a slider dragged
  // across its range would stall the GUI thread on every step. Remembered once the user pauses.
  rememberSettingsTimer_->start();
  if (actions_.modelMenu &&
      (settings.model != actions_.menuSettings.model ||
       settings.rule != actions_.menuSettings.rule || settings.pose != actions_.menuSettings.pose))
    rebuildMappingMenu();
  view_->setNativeName(QString::fromStdString(forward::mapRuleNativeName(settings.rule)));
  panel_->setSettings(settings);
  // Paced while a log re-maps (BeamDock::setSettings).
  beamDock_->setSettings(settings, document_->dataset() != nullptr);
  // The robot, its path and the current beams depend on the pose source only: a parameter change
  // must not redraw them (and the grid's overlays) on every step of a dragged slider.
  if (scanShownPose_ != settings.pose) showCurrentScan();
  mapDock_->scheduleSummary();
  updateTitle();
}

void MainWindow::rememberSettings() {
  rememberSettingsTimer_->stop();
  const MapperSettings& settings = document_->mapperSettings();
  QSettings s;
  s.setValue("mapping/model", QString::fromStdString(settings.model));
  s.setValue("mapping/rule", QString::fromStdString(settings.rule));
  s.setValue("mapping/pose", poseName(settings.pose));
  s.remove("mapping/parameters");
  s.beginGroup("mapping/parameters");
  for (const auto& [name, value] : settings.parameters.values())
    s.setValue(QString::fromStdString(name), value);
  s.endGroup();
}

sg::MapperSettings MainWindow::lastSettings() {
  QSettings s;
  sg::MapperSettings out;
  const std::string model = s.value("mapping/model", "himm").toString().toStdString();
  const std::string rule = s.value("mapping/rule", "himm").toString().toStdString();
  const std::vector<std::string> models = forward::mapModelNames(), rules = forward::mapRuleNames();
  if (std::find(models.begin(), models.end(), model) != models.end() &&
      std::find(rules.begin(), rules.end(), rule) != rules.end() &&
      forward::mapCompatibility(model, rule).allowed) {
    out.model = model;
    out.rule = rule;
  } else {
    out.model = "himm";
    out.rule = "himm";
  }
  out.parameters = forward::mapDefaultParameters(out.model, out.rule);
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

bool MainWindow::reportError(const QString& title, const QString& message, bool quiet) {
  if (quiet || QApplication::platformName() == QLatin1String("offscreen"))
    std::cerr << "sonargrid: " << message.toStdString() << '\n';
  else
    QMessageBox::critical(this, title, message);
  return false;
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
  status_->mapped(elapsedMs);
  // The summary's rich text is laid out again on every change (a few ms): a few times a second is
  // all a reader needs while a slider is dragged.
  mapDock_->scheduleSummary();
}

void MainWindow::onTimeChanged(double t, std::size_t) {
  if (!document_->dataset()) return;
  showCurrentScan();
  remap_->setUntil(t);
}

void MainWindow::updateSummary() {
  if (!mapDock_) return;
  QString html;
  const Dataset* run = document_->dataset().get();
  const MapperSettings& settings = document_->mapperSettings();
  if (!run) {
    html =
        tr("<p>No log loaded.</p><p>File ▸ Open Log (Ctrl+O), File ▸ Open Example, or drop a "
           "<code>.sglog</code> file on the window.</p>");
  } else {
    const auto map = view_->map();
    html = QStringLiteral("<b>%1</b><br>%2 scans, %3 readings<br>%4 sonars (%5)")
               .arg(QFileInfo(document_->logPath()).fileName().toHtmlEscaped())
               .arg(run->scans.size())
               .arg(run->readingCount())
               .arg(run->ring.size())
               .arg(QString::fromStdString(run->ring.robot).toHtmlEscaped());
    html += QStringLiteral("<hr><b>%1</b><br>× <b>%2</b><br>pose: %3")
                .arg(QString::fromStdString(forward::mapModelTitle(settings.model)).toHtmlEscaped())
                .arg(QString::fromStdString(forward::mapRuleTitle(settings.rule)).toHtmlEscaped())
                .arg(settings.pose == PoseSource::Truth ? tr("true pose") : tr("odometry"));
    if (map) {
      html += QStringLiteral("<hr>grid %1 × %2 cells of %3 m<br>%4 cells filled<br>re-map %5 ms")
                  .arg(map->spec.width)
                  .arg(map->spec.height)
                  .arg(map->spec.cellSize)
                  .arg(map->filledCount())
                  .arg(status_->lastMapMs(), 0, 'f', 1);
    }
    if (const auto& reference = document_->reference())
      html += QStringLiteral("<hr>reference: %1 (%2 objects)%3")
                  .arg(document_->referencePath().isEmpty()
                           ? tr("drawn")
                           : QFileInfo(document_->referencePath()).fileName().toHtmlEscaped())
                  .arg(reference->objects.size())
                  .arg(document_->referenceModified() ? tr(", edited") : QString());
  }
  mapDock_->setSummary(html);
}

void MainWindow::updateTitle() {
  // "[*]" is where Qt shows the unsaved-changes mark (setWindowModified).
  const QString project = QFileInfo(document_->projectPath()).fileName();
  const MapperSettings& s = document_->mapperSettings();
  QString title;
  if (document_->dataset())
    title = QStringLiteral("%1[*] — %2 × %3 — SonarGrid")
                .arg(project.isEmpty() ? QFileInfo(document_->logPath()).fileName() : project,
                     QString::fromStdString(s.model), QString::fromStdString(s.rule));
  else
    title = project.isEmpty() ? QStringLiteral("SonarGrid[*]")
                              : QStringLiteral("%1[*] — SonarGrid").arg(project);
  setWindowTitle(title);
  setWindowModified(document_->isModified());
}

void MainWindow::closeEvent(QCloseEvent* event) {
  if (!maybeSave()) {
    event->ignore();
    return;
  }
  if (rememberSettingsTimer_->isActive()) rememberSettings();
  QSettings s;
  s.setValue("window/geometry", saveGeometry());
  s.setValue("window/state", saveState(kLayoutVersion));
  autosave_->remove();  // a clean exit leaves nothing to recover
  QMainWindow::closeEvent(event);
}

}  // namespace sg::app
