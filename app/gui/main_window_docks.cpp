// SPDX-License-Identifier: GPL-3.0-or-later
// The window's docks: timeline, map summary with the cell size, parameter panel, beam model (and
// the reading of the current scan it shows).
#include <QDockWidget>
#include <QSettings>

#include "beam_dock.h"
#include "beam_model_view.h"
#include "document.h"
#include "grid_view.h"
#include "main_window.h"
#include "map_dock.h"
#include "parameter_panel.h"
#include "sonargrid/data/scan_poses.h"
#include "sonargrid/forward/forward_em.h"
#include "timeline.h"

namespace sg::app {

void MainWindow::createDocks() {
  timeline_ = new ui::Timeline(this);
  auto* timelineDock = new QDockWidget(tr("Timeline"), this);
  timelineDock->setObjectName(QStringLiteral("timelineDock"));
  timelineDock->setWidget(timeline_);
  timelineDock->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable |
                            QDockWidget::DockWidgetClosable);
  addDockWidget(Qt::BottomDockWidgetArea, timelineDock);
  connect(actions_.play, &QAction::toggled, timeline_, &ui::Timeline::setPlaying);
  connect(actions_.stepForward, &QAction::triggered, timeline_, &ui::Timeline::stepForward);
  connect(actions_.stepBack, &QAction::triggered, timeline_, &ui::Timeline::stepBackward);

  mapDock_ = new MapDock(document_->cellSize(), this);
  // Held arrow buttons: one undo step, ended when the button is released.
  connect(mapDock_, &MapDock::cellSizeEdited, this,
          [this](double metres, bool held) { document_->setCellSize(metres, held); });
  connect(mapDock_, &MapDock::cellSizeReleased, document_, &Document::endDrag);
  connect(mapDock_, &MapDock::summaryDue, this, &MainWindow::updateSummary);
  auto* summaryDock = new QDockWidget(tr("Map"), this);
  summaryDock->setObjectName(QStringLiteral("mapDock"));
  summaryDock->setWidget(mapDock_);

  // The parameter panel: its changes come back through setMapperSettings, which shows them
  // everywhere else (the panel itself ignores settings it already holds).
  panel_ = new ui::ParameterPanel(this);
  panel_->setSettings(document_->mapperSettings());
  // A drag's steps merge into one undo step until the slider is let go.
  connect(panel_, &ui::ParameterPanel::settingsChanged, this,
          [this](const MapperSettings& s) { document_->setMapperSettings(s, panel_->dragging()); });
  connect(panel_, &ui::ParameterPanel::dragFinished, document_, &Document::endDrag);
  auto* panelDock = new QDockWidget(tr("Parameters"), this);
  panelDock->setObjectName(QStringLiteral("parametersDock"));
  panelDock->setWidget(panel_);
  panelDock->toggleViewAction()->setShortcut(QKeySequence(tr("Ctrl+Shift+P")));

  // The beam-model view of one reading of the current scan, with the panel's model.
  beamDock_ = new BeamDock(document_->mapperSettings(), this);
  connect(beamDock_, &BeamDock::sonarPicked, this, &MainWindow::chooseBeamSonar);
  auto* beamDock = new QDockWidget(tr("Beam Model"), this);
  beamDock->setObjectName(QStringLiteral("beamModelDock"));
  beamDock->setWidget(beamDock_);
  beamDock->toggleViewAction()->setShortcut(QKeySequence(tr("Ctrl+Shift+B")));

  // One column right of the grid: the beam view (the map summary tabbed behind it) above the
  // panel, so that the grid keeps 60 % of a 1280 px window and the panel's sliders 80 px each.
  // The column runs down to the status bar; the timeline's row spans the grid's width only.
  setCorner(Qt::BottomRightCorner, Qt::RightDockWidgetArea);
  addDockWidget(Qt::RightDockWidgetArea, beamDock);
  splitDockWidget(beamDock, panelDock, Qt::Vertical);
  tabifyDockWidget(beamDock, summaryDock);
  beamDock->raise();
  updateSummary();
}

void MainWindow::restoreWindowState() {
  QSettings s;
  if (!restoreGeometry(s.value("window/geometry").toByteArray())) resize(1280, 800);
  if (restoreState(s.value("window/state").toByteArray(), kLayoutVersion)) return;
  // First launch: the column right of the grid no wider than kRightColumnWidth, and the row
  // under it (the timeline and its tabs) no higher than its controls need.
  if (QDockWidget* beam = findChild<QDockWidget*>(QStringLiteral("beamModelDock")))
    resizeDocks({beam}, {kRightColumnWidth}, Qt::Horizontal);
  if (QDockWidget* timeline = findChild<QDockWidget*>(QStringLiteral("timelineDock")))
    resizeDocks({timeline}, {1}, Qt::Vertical);  // clamped to the tallest tab's minimum
}

void MainWindow::showCurrentScan() {
  const Dataset* run = document_->dataset().get();
  if (!run) return;
  const PoseSource pose = document_->mapperSettings().pose;
  scanShownPose_ = pose;
  const std::size_t scan = timeline_->currentScan();
  view_->setFollowRobot(false);  // a loaded log's robot is where the timeline puts it
  view_->setRobotAt(run, pose, scan);
  const std::optional<std::size_t> sonar =
      beamDock_->showReadings(run->scans[scan].readings, run->ring.maxRange);
  view_->setHighlightedSonar(sonar);
  showForwardPrediction();
}

void MainWindow::showForwardPrediction() {
  const Dataset* run = document_->dataset().get();
  const auto map = view_->map();
  const std::optional<std::size_t> sonar = beamDock_->sonar();
  if (!run || !map || !sonar || !forward::isForwardModelMap(*map)) {
    beamDock_->showForward({}, nullptr);
    return;
  }
  const Scan& scan = run->scans[timeline_->currentScan()];
  const PoseSource pose = document_->mapperSettings().pose;
  if (!hasPose(scan, pose)) {
    beamDock_->showForward({}, nullptr);
    return;
  }
  for (const Reading& r : scan.readings) {
    if (r.sonar != *sonar || r.sonar >= run->ring.size()) continue;
    forward::ForwardBeam beam;
    beam.sensor = run->pose(scan, pose).compose(run->ring.sonars[r.sonar].pose);
    beam.maxRange = run->ring.maxRange;
    beam.range = r.range < run->ring.maxRange ? r.range : Reading::kNoEcho;
    beamDock_->showForward(beam, map);
    return;
  }
}

bool MainWindow::chooseBeamSonar(std::size_t sonar) {
  if (!document_->dataset()) return false;
  if (!beamDock_->choose(document_->dataset()->scans[timeline_->currentScan()].readings, sonar))
    return false;
  showCurrentScan();
  return true;
}

}  // namespace sg::app
