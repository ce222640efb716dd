// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The comparison table (a dock): pinned configurations (model, rule, parameters, pose, cell size)
// as rows, every metric side by side in the style of the papers' tables. Against a reference the
// metrics are computed on the cells that ALL pinned maps observed (sg::ScoreOptions::cellMask of
// sg::commonObservedCells() on each map's grid), so that every row is judged on the same ground;
// a second view scores each map on its own cells. Without a reference each row shows paper 002's
// goodness of its own map.
//
// Each row's map is built from its configuration (the log mapped again on a worker thread, maps
// kept while their configuration stays pinned); a newer set of rows cancels the stale computation,
// and the destructor waits for the running one. Clicking a row asks for its configuration back
// (rowActivated); the window makes that an undoable edit.

#include <QWidget>
#include <atomic>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "job_queue.h"
#include "metrics_compute.h"

class QComboBox;
class QLabel;
class QPushButton;
class QTableWidget;

namespace sg::ui {

struct ComparisonRow {
  QString label;
  MapperSettings settings;
  double cellSize = 0.05;
};

// Which cells the table's metrics are computed over.
enum class CellSet { Common, EachMap };

class ComparisonTable : public QWidget {
  Q_OBJECT

 public:
  explicit ComparisonTable(QWidget* parent = nullptr);
  ~ComparisonTable() override;

  void setRows(std::vector<ComparisonRow> rows);
  void setRuns(std::shared_ptr<const Dataset> run, std::shared_ptr<const Dataset> secondRun);
  void setReference(std::shared_ptr<const ReferenceMap> reference);
  void setCellSet(CellSet set);
  CellSet cellSet() const { return cellSet_; }

  const std::vector<ComparisonRow>& rows() const { return rows_; }
  // The numbers of row `row` in the chosen cell set (null until computed).
  const MetricsResult* result(std::size_t row) const;
  const MetricsResult* result(std::size_t row, CellSet set) const;
  bool busy() const { return pending_ || jobs_.busy(); }
  bool waitForResult(int timeoutMs);

  // The table as CSV (one row per pinned configuration; the JSON keys of score --json as columns,
  // values in full precision) and as a Markdown table (the panel's names, units and decimals).
  QString csv() const;
  QString markdown() const;
  // Writes csv() (or markdown() for a .md file) atomically; the error message, or empty.
  QString exportTo(const QString& path) const;

 signals:
  void pinRequested();
  void removeRequested(std::size_t row);
  void rowActivated(std::size_t row);
  void updated();

 private:
  struct RowResult {
    MetricsResult common, each;
  };
  struct Outcome;
  void schedule();
  void start();
  void fill();
  std::vector<const MetricInfo*> columns() const;
  void exportDialog();

  QLabel* status_;
  QComboBox* cellSetChooser_;
  QPushButton* removeButton_;
  QTableWidget* table_;
  std::vector<ComparisonRow> rows_;
  std::shared_ptr<const Dataset> run_, secondRun_;
  std::shared_ptr<const ReferenceMap> reference_;
  CellSet cellSet_ = CellSet::Common;
  std::vector<std::optional<RowResult>> results_;
  // Maps of pinned configurations, by configuration (kept across recomputations).
  std::shared_ptr<const std::map<std::string, std::shared_ptr<const OccupancyMap>>> maps_;
  bool pending_ = false;
  JobQueue jobs_;  // last: destroyed (cancelled and waited for) first
};

}  // namespace sg::ui
