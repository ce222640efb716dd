// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The metrics panel and the comparison table in the window: their docks, their View menu entries
// and their links with the Document (reference, runs, pinned rows) and the re-mapper (each map).

namespace sg::ui {
class ComparisonTable;
class MetricsPanel;
}  // namespace sg::ui

namespace sg::app {

class MainWindow;

struct MetricsDocks {
  ui::MetricsPanel* panel = nullptr;
  ui::ComparisonTable* table = nullptr;
};

// Creates both as children of `window`, wired to its Document, RemapController and GridView.
MetricsDocks installMetrics(MainWindow* window);

}  // namespace sg::app
