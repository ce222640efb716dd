// SPDX-License-Identifier: GPL-3.0-or-later
// The metrics panel and the comparison table (issue 12 items 3 and 4): docks, View menu entries and
// the links with the Document and the re-mapper. The numbers are computed by the widgets on their
// own worker threads (metrics_panel.h, comparison_table.h); this file only wires.
#include <QDockWidget>
#include <QMenu>
#include <QMenuBar>
#include <QUndoStack>

#include "comparison_table.h"
#include "document.h"
#include "grid_view.h"
#include "main_window.h"
#include "main_window_metrics.h"
#include "metrics_panel.h"
#include "parameter_panel.h"
#include "remap_controller.h"

namespace sg::app {
namespace {

std::shared_ptr<const ReferenceMap> referenceOf(const Document* document) {
  const auto& reference = document->reference();
  return reference ? std::make_shared<const ReferenceMap>(*reference) : nullptr;
}

std::vector<ui::ComparisonRow> rowsOf(const Document* document) {
  std::vector<ui::ComparisonRow> rows;
  for (const PinnedRow& p : document->pinnedRows())
    rows.push_back({p.label, p.settings, p.cellSize});
  return rows;
}

QString rowLabel(const Document* document) {
  const MapperSettings& s = document->mapperSettings();
  return QStringLiteral("%1: %2 × %3 @ %4 cm")
      .arg(QStringLiteral("R%1").arg(document->pinnedRows().size() + 1),
           QString::fromStdString(s.model), QString::fromStdString(s.rule))
      .arg(document->cellSize() * 100.0, 0, 'g', 4);
}

}  // namespace

MetricsDocks installMetrics(MainWindow* window) {
  Document* document = window->document();
  ui::RemapController* remap = window->remapController();
  MetricsDocks out;

  out.panel = new ui::MetricsPanel(window);
  auto* panelDock = new QDockWidget(QObject::tr("Metrics"), window);
  panelDock->setObjectName(QStringLiteral("metricsDock"));
  panelDock->setWidget(out.panel);
  panelDock->toggleViewAction()->setShortcut(QKeySequence(QObject::tr("Ctrl+Shift+M")));
  window->addDockWidget(Qt::RightDockWidgetArea, panelDock);
  if (auto* map = window->findChild<QDockWidget*>(QStringLiteral("mapDock")))
    window->tabifyDockWidget(map, panelDock);

  out.table = new ui::ComparisonTable(window);
  auto* tableDock = new QDockWidget(QObject::tr("Comparison"), window);
  tableDock->setObjectName(QStringLiteral("comparisonDock"));
  tableDock->setWidget(out.table);
  tableDock->toggleViewAction()->setShortcut(QKeySequence(QObject::tr("Ctrl+Shift+T")));
  window->addDockWidget(Qt::BottomDockWidgetArea, tableDock);
  if (auto* timeline = window->findChild<QDockWidget*>(QStringLiteral("timelineDock"))) {
    window->tabifyDockWidget(timeline, tableDock);
    timeline->raise();
  }
  if (auto* view = window->menuBar()->findChild<QMenu*>(QStringLiteral("viewMenu"))) {
    view->addAction(panelDock->toggleViewAction());
    view->addAction(tableDock->toggleViewAction());
  }

  ui::MetricsPanel* panel = out.panel;
  ui::ComparisonTable* table = out.table;
  // Every full map (never a preview) is scored, with what it was built with.
  QObject::connect(
      remap, &ui::RemapController::mapped, panel,
      [panel, remap, document](std::shared_ptr<const OccupancyMap> map, double, quint64, bool) {
        panel->setRuns(document->dataset(), document->secondDataset(), remap->settings(),
                       remap->cellSize());
        panel->setMap(std::move(map));
      });
  // While a re-map runs (a dragged slider), the panel scores nothing: on two cores its worker
  // would take a CPU from the re-map (the slider's latency, docs/performance.md).
  QObject::connect(remap, &ui::RemapController::started, panel, &ui::MetricsPanel::awaitMap);
  // A parameter changed once (not by a held slider) is scored as soon as its map arrives; a held
  // slider's map, once the slider rests or is let go. Connected after the window's own connection
  // (createDocks()), which re-maps, so that scoreAtOnce() follows that re-map's awaitMap().
  ui::ParameterPanel* parameters = window->parameterPanel();
  Q_ASSERT(parameters);
  QObject::connect(parameters, &ui::ParameterPanel::settingsChanged, panel, [panel, parameters] {
    if (!parameters->dragging()) panel->scoreAtOnce();
  });
  QObject::connect(parameters, &ui::ParameterPanel::dragFinished, panel,
                   &ui::MetricsPanel::endSettle);
  // No map of that re-map is coming (it failed, or was stopped with nothing newer after it): the
  // panel scores the map it has.
  auto resumeIfNewest = [panel, remap](quint64 generation) {
    if (generation == remap->latestGeneration()) panel->resume();
  };
  QObject::connect(remap, &ui::RemapController::failed, panel,
                   [resumeIfNewest](const QString&, quint64 g) { resumeIfNewest(g); });
  QObject::connect(remap, &ui::RemapController::cancelled, panel,
                   [resumeIfNewest](quint64 g, bool) { resumeIfNewest(g); });
  QObject::connect(panel, &ui::MetricsPanel::dminTintChanged, window->gridView(),
                   &ui::GridView::setDminTint);
  // Each reference edit (the editor's steps reach the Document) scores the shown map again.
  QObject::connect(document, &Document::referenceChanged, panel, [panel, table, document] {
    const auto reference = referenceOf(document);
    panel->setReference(reference);
    table->setReference(reference);
  });
  QObject::connect(document, &Document::secondLogChanged, panel, [panel, remap, document] {
    if (remap->dataset())
      panel->setRuns(document->dataset(), document->secondDataset(), remap->settings(),
                     remap->cellSize());
  });
  auto runs = [table, document] { table->setRuns(document->dataset(), document->secondDataset()); };
  QObject::connect(document, &Document::logChanged, table, runs);
  QObject::connect(document, &Document::secondLogChanged, table, runs);
  QObject::connect(document, &Document::pinnedRowsChanged, table,
                   [table, document] { table->setRows(rowsOf(document)); });

  // The table's gestures are Document edits, each one undo step.
  QObject::connect(table, &ui::ComparisonTable::pinRequested, document, [document] {
    document->pinRow({rowLabel(document), document->mapperSettings(), document->cellSize()});
  });
  QObject::connect(table, &ui::ComparisonTable::removeRequested, document,
                   [document](std::size_t row) { document->removePinnedRow(row); });
  QObject::connect(table, &ui::ComparisonTable::rowActivated, document,
                   [document](std::size_t row) {
                     if (row >= document->pinnedRows().size()) return;
                     const PinnedRow pinned = document->pinnedRows()[row];
                     if (pinned.settings == document->mapperSettings() &&
                         pinned.cellSize == document->cellSize())
                       return;
                     document->undoStack()->beginMacro(QObject::tr("Restore %1").arg(pinned.label));
                     document->setMapperSettings(pinned.settings);
                     document->setCellSize(pinned.cellSize);
                     document->undoStack()->endMacro();
                   });

  panel->setReference(referenceOf(document));
  table->setReference(referenceOf(document));
  runs();
  table->setRows(rowsOf(document));
  return out;
}

}  // namespace sg::app
