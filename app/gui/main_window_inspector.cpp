// SPDX-License-Identifier: GPL-3.0-or-later
// The cell inspector's place in the window (docs/user-guide.md, "Inspecting a cell"): its dock
// under the grid, Shift+click in the grid view to pick a cell (CellPicker), a re-map of the loaded
// log with other settings or cells traces the cell again, and a reading chosen in its list moves
// the timeline to that reading's scan and shows it in the beam-model view.
#include <QAction>
#include <QDockWidget>
#include <QStatusBar>

#include "beam_model_view.h"
#include "cell_inspector.h"
#include "cell_inspector_picker.h"
#include "document.h"
#include "grid_view.h"
#include "main_window.h"
#include "remap_controller.h"
#include "sonargrid/forward/catalog.h"
#include "timeline.h"

namespace sg::app {

void MainWindow::createInspector() {
  inspector_ = new ui::CellInspector(this);
  auto* dock = new QDockWidget(tr("Cell Inspector"), this);
  dock->setObjectName(QStringLiteral("cellInspectorDock"));
  dock->setWidget(inspector_);
  dock->toggleViewAction()->setShortcut(QKeySequence(tr("Ctrl+Shift+I")));
  addDockWidget(Qt::BottomDockWidgetArea, dock);
  // Right of the timeline, with most of the width: the plot and the list side by side.
  if (auto* timeline = findChild<QDockWidget*>(QStringLiteral("timelineDock"))) {
    splitDockWidget(timeline, dock, Qt::Horizontal);
    resizeDocks({timeline, dock}, {380, 900}, Qt::Horizontal);
  }
  resizeDocks({dock}, {kInspectorHeight}, Qt::Vertical);
  dock->hide();  // shown by the first Shift+click, or from the View menu
  // The row it shares with the timeline is one row of controls high at first launch: shown, the
  // inspector gets the height its plot and list need (once laid out, hence queued).
  connect(dock, &QDockWidget::visibilityChanged, this, [this, dock](bool visible) {
    if (!visible || dock->isFloating()) return;
    QMetaObject::invokeMethod(
        this,
        [this, dock] {
          if (dock->isVisible() && !dock->isFloating() && dock->height() < kInspectorHeight)
            resizeDocks({dock}, {kInspectorHeight}, Qt::Vertical);
        },
        Qt::QueuedConnection);
  });

  picker_ = new ui::CellPicker(view_);
  connect(picker_, &ui::CellPicker::picked, this, [this, dock](const Position& world) {
    if (!remap_->dataset() || !view_->map()) {
      statusBar()->showMessage(tr("Open a log to inspect its cells"), 5000);
      return;
    }
    dock->show();
    dock->raise();
    if (!inspector_->inspectAt(world))
      statusBar()->showMessage(tr("That point is outside the grid"), 5000);
  });
  connect(inspector_, &ui::CellInspector::cellChanged, this, [this] {
    const std::shared_ptr<const OccupancyMap> map = view_->map();
    picker_->setMarkedCell(inspector_->cell() && map ? std::optional(map->spec) : std::nullopt,
                           inspector_->cell());
  });
  connect(inspector_, &ui::CellInspector::traceFailed, this,
          [this](const QString& message) { statusBar()->showMessage(message, 8000); });
  // A full map (never a preview) names the grid and settings to trace with; the trace covers the
  // whole log whatever the timeline's time, which the plot marks.
  connect(remap_, &ui::RemapController::mapped, this,
          [this](std::shared_ptr<const OccupancyMap> map, double, quint64 generation, bool) {
            if (generation != remap_->latestGeneration()) return;
            if (!remap_->dataset()) {
              inspector_->clearContext(
                  tr("The inspector replays a loaded log; a live robot's map cannot be traced."));
              return;
            }
            if (forward::isForwardModel(remap_->settings().model)) {
              inspector_->clearContext(
                  tr("The forward model learns every cell from all readings at once by EM: no "
                     "reading updates a cell on its own, so there is no trace to replay. The "
                     "beam view shows a reading's predicted range under the map."));
              return;
            }
            inspector_->setContext(remap_->dataset(), map->spec, remap_->settings());
            if (inspector_->cell()) picker_->setMarkedCell(map->spec, inspector_->cell());
          });
  connect(timeline_, &ui::Timeline::timeChanged, inspector_,
          [this](double t, std::size_t) { inspector_->setCurrentTime(t); });
  connect(inspector_, &ui::CellInspector::readingChosen, this,
          [this](std::size_t scan, std::size_t sonar) { showReading(scan, sonar); });
}

bool MainWindow::showReading(std::size_t scan, std::size_t sonar) {
  const Dataset* run = document_->dataset().get();
  if (!run || scan >= run->scans.size()) return false;
  // The timeline at the reading's scan maps up to it; then its sonar is the beam view's reading.
  timeline_->setTime(run->scans[scan].time);
  if (timeline_->currentScan() != scan) return false;
  return chooseBeamSonar(sonar);
}

}  // namespace sg::app
