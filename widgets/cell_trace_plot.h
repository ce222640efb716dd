// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A cell's value over the log (a CellTrace) as a step plot drawn with QPainter: time on x, the
// rule's value, p(occ) or the CV level on y, with axes, ticks and labels; one dot per reading that
// wrote the cell, the selected one ringed, and a vertical line at the timeline's time. Clicking
// near a dot selects that reading.

#include <QWidget>
#include <memory>
#include <optional>

#include "sonargrid/engine/cell_trace.h"

namespace sg::ui {

class CellTracePlot : public QWidget {
  Q_OBJECT

 public:
  enum class Quantity { Native, Probability, Level };

  explicit CellTracePlot(QWidget* parent = nullptr);

  void setTrace(std::shared_ptr<const CellTrace> trace);
  const std::shared_ptr<const CellTrace>& trace() const { return trace_; }
  void setQuantity(Quantity quantity);
  Quantity quantity() const { return quantity_; }
  // The reading ringed (an index into trace()->steps), or none.
  void setSelectedStep(std::optional<std::size_t> step);
  void setMarkerTime(std::optional<double> time);

  // The plotted value of `v` for the current quantity, and its axis title.
  double valueOf(const CellValue& v) const;
  QString quantityTitle() const;
  // The step whose dot is nearest `pixel` (within a few pixels in x), if any.
  std::optional<std::size_t> stepAt(const QPointF& pixel) const;

  QSize sizeHint() const override { return {360, 200}; }
  QSize minimumSizeHint() const override { return {200, 120}; }

 signals:
  void stepClicked(std::size_t step);

 protected:
  void paintEvent(QPaintEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;

 private:
  struct Frame;
  Frame frame() const;

  std::shared_ptr<const CellTrace> trace_;
  Quantity quantity_ = Quantity::Native;
  std::optional<std::size_t> selected_;
  std::optional<double> marker_;
};

}  // namespace sg::ui
