// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The cell inspector (docs/user-guide.md, "Inspecting a cell"): one cell's value over the log as a
// plot (CellTracePlot) and the readings that wrote it, each with its time, sonar, range, the
// model's pE and pO at the cell and the cell's value after it. The trace (sg::traceCell) replays
// the log with the map's model, rule and grid on a worker thread; a newer cell or a re-map with
// other settings cancels a stale one. Selecting a reading emits readingChosen (the window shows it
// in the beam-model view).

#include <QWidget>
#include <atomic>
#include <memory>
#include <optional>

#include "cell_trace_plot.h"
#include "job_queue.h"
#include "sonargrid/data/dataset.h"
#include "sonargrid/engine/cell_trace.h"
#include "sonargrid/engine/mapper.h"

class QComboBox;
class QLabel;
class QTreeWidget;

namespace sg::ui {

class CellInspector : public QWidget {
  Q_OBJECT

 public:
  explicit CellInspector(QWidget* parent = nullptr);
  ~CellInspector() override;  // cancels the running trace and waits for it

  // What the map was made of: the log, its grid and the mapper's settings. Traces the inspected
  // cell again when any of them changed (a re-map with new settings or cells).
  void setContext(std::shared_ptr<const Dataset> log, const GridSpec& grid,
                  const MapperSettings& settings);
  // Nothing can be traced (no log, or a live robot's map): says why, and forgets the trace.
  void clearContext(const QString& why);
  // Inspects the cell holding world point `world`; false when it is outside the grid (or there is
  // no context).
  bool inspectAt(const Position& world);
  bool inspect(const CellIndex& cell);
  std::optional<CellIndex> cell() const { return cell_; }
  // The cell's centre in the world, when one is inspected.
  std::optional<Position> cellCentre() const;

  // The last complete trace of the inspected cell (null while none has arrived).
  const std::shared_ptr<const CellTrace>& trace() const { return trace_; }
  bool busy() const { return jobs_.busy(); }
  // The timeline's time: a line on the plot.
  void setCurrentTime(double t);
  // Selects reading `step` of the trace in the list and the plot, and emits readingChosen.
  void selectStep(std::size_t step);

  QTreeWidget* readingList() const { return list_; }
  CellTracePlot* plot() const { return plot_; }

 signals:
  void traced(std::shared_ptr<const sg::CellTrace> trace);
  void traceFailed(const QString& message);
  // The user chose a reading of the trace: scan `scan`'s reading of sonar `sonar`.
  void readingChosen(std::size_t scan, std::size_t sonar);
  // A new cell is inspected (or none).
  void cellChanged();

 private:
  void start();
  void deliver(quint64 generation, std::shared_ptr<const CellTrace> trace, const QString& error);
  void fillList();
  void updateHeader();

  std::shared_ptr<const Dataset> data_;
  std::optional<GridSpec> grid_;
  MapperSettings settings_;
  std::optional<CellIndex> cell_;
  std::shared_ptr<const CellTrace> trace_;
  QString status_;

  QLabel* header_;
  QComboBox* quantity_;
  CellTracePlot* plot_;
  QTreeWidget* list_;
  // One job at a time: a new trace waits for the cancelled one to stop. Last: destroyed (cancelled
  // and waited for) first.
  JobQueue jobs_;
};

}  // namespace sg::ui
