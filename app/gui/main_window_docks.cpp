// SPDX-License-Identifier: GPL-3.0-or-later
// The window's docks: timeline, map summary with the cell size, parameter panel, beam model (and
// the reading of the current scan it shows).
#include <QApplication>
#include <QComboBox>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QSettings>
#include <QVBoxLayout>

#include "beam_model_view.h"
#include "document.h"
#include "grid_view.h"
#include "main_window.h"
#include "parameter_panel.h"
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
  connect(playAction_, &QAction::toggled, timeline_, &ui::Timeline::setPlaying);
  connect(stepForwardAction_, &QAction::triggered, timeline_, &ui::Timeline::stepForward);
  connect(stepBackAction_, &QAction::triggered, timeline_, &ui::Timeline::stepBackward);

  summary_ = new QLabel(this);
  summary_->setTextFormat(Qt::RichText);
  summary_->setAlignment(Qt::AlignTop | Qt::AlignLeft);
  summary_->setMargin(8);
  summary_->setMinimumWidth(220);
  summary_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  // The cell size heads the Map dock: it decides the grid the summary describes.
  cellSpin_ = new QDoubleSpinBox(this);
  cellSpin_->setObjectName(QStringLiteral("cellSize"));
  cellSpin_->setRange(kMinCellSize, kMaxCellSize);
  cellSpin_->setDecimals(3);
  cellSpin_->setSingleStep(0.005);
  cellSpin_->setSuffix(tr(" m"));
  cellSpin_->setValue(document_->cellSize());
  cellSpin_->setKeyboardTracking(false);  // a typed value is one edit, on Enter or leaving the box
  cellSpin_->setToolTip(tr("Side of a grid cell in metres (View ▸ Cell Size…); undoable"));
  cellSpin_->installEventFilter(this);
  connect(cellSpin_, &QDoubleSpinBox::valueChanged, this, [this](double metres) {
    // Held arrow buttons repeat: one undo step until the button is released (eventFilter).
    document_->setCellSize(metres, QApplication::mouseButtons() != Qt::NoButton);
  });
  auto* cellLabel = new QLabel(tr("&Cell size:"), this);
  cellLabel->setBuddy(cellSpin_);
  auto* mapHost = new QWidget(this);
  auto* cellRow = new QHBoxLayout;
  cellRow->setContentsMargins(8, 8, 8, 0);
  cellRow->addWidget(cellLabel);
  cellRow->addWidget(cellSpin_);
  cellRow->addStretch(1);
  auto* mapLayout = new QVBoxLayout(mapHost);
  mapLayout->setContentsMargins(0, 0, 0, 0);
  mapLayout->addLayout(cellRow);
  mapLayout->addWidget(summary_, 1);
  auto* summaryDock = new QDockWidget(tr("Map"), this);
  summaryDock->setObjectName(QStringLiteral("mapDock"));
  summaryDock->setWidget(mapHost);

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
  auto* beamHost = new QWidget(this);
  beamView_ = new ui::BeamModelView(beamHost);
  beamView_->setSettings(document_->mapperSettings());
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
  view_->setRobotAt(run, pose, scan);
  const std::vector<Reading>& readings = run->scans[scan].readings;
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
  if (shown) beamView_->setRange(shown->echo() ? shown->range : run->ring.maxRange);
}

bool MainWindow::chooseBeamSonar(std::size_t sonar) {
  if (!document_->dataset()) return false;
  for (const Reading& r : document_->dataset()->scans[timeline_->currentScan()].readings)
    if (r.sonar == sonar) {
      chosenSonar_ = sonar;
      showCurrentScan();
      return true;
    }
  return false;
}

}  // namespace sg::app
