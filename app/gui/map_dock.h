// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The Map dock's content: the cell size (it decides the grid the summary describes) above the
// summary of the log, the settings, the grid and the reference. The summary's rich text is laid
// out again on every change (a few ms), so a change only schedules it: a few times a second is all
// a reader needs while a slider is dragged.

#include <QString>
#include <QWidget>

class QDoubleSpinBox;
class QLabel;
class QTimer;

namespace sg::app {

class MapDock : public QWidget {
  Q_OBJECT

 public:
  explicit MapDock(double cellSize, QWidget* parent = nullptr);

  // Shows `metres` without announcing it as an edit.
  void setCellSize(double metres);
  // summaryDue() follows within kSummaryIntervalMs, once for any number of calls.
  void scheduleSummary();
  void setSummary(const QString& html);

 signals:
  // The user set the cell size; `held`: by an arrow button held down, which repeats until
  // cellSizeReleased().
  void cellSizeEdited(double metres, bool held);
  void cellSizeReleased();
  void summaryDue();

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  static constexpr int kSummaryIntervalMs = 250;
  QDoubleSpinBox* cell_;
  QLabel* summary_;
  QTimer* timer_;
};

}  // namespace sg::app
