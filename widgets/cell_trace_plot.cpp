// SPDX-License-Identifier: GPL-3.0-or-later
#include "cell_trace_plot.h"

#include <QMouseEvent>
#include <QPainter>
#include <QPainterPath>
#include <algorithm>
#include <cmath>

namespace sg::ui {

namespace {

constexpr int kPickPx = 6;  // how near a click must fall to a reading's dot, in x

// A tick step of 1, 2 or 5 × 10^k giving about `ticks` ticks over `span`.
double niceStep(double span, int ticks) {
  if (!(span > 0.0)) return 1.0;
  const double raw = span / ticks;
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double m : {1.0, 2.0, 5.0})
    if (raw <= m * decade) return m * decade;
  return 10.0 * decade;
}

QString tickLabel(double v, double step) {
  const int decimals = step >= 1.0 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
  return QString::number(v, 'f', std::clamp(decimals, 0, 6));
}

}  // namespace

// Where the data go in the widget, and the data ranges they show.
struct CellTracePlot::Frame {
  QRectF area;
  double t0 = 0.0, t1 = 1.0, y0 = 0.0, y1 = 1.0;
  double x(double t) const { return area.left() + (t - t0) / (t1 - t0) * area.width(); }
  double y(double v) const { return area.bottom() - (v - y0) / (y1 - y0) * area.height(); }
};

CellTracePlot::CellTracePlot(QWidget* parent) : QWidget(parent) {
  setAttribute(Qt::WA_OpaquePaintEvent);
  setToolTip(tr("The cell's value after each reading that wrote it; click a dot to select it"));
}

void CellTracePlot::setTrace(std::shared_ptr<const CellTrace> trace) {
  trace_ = std::move(trace);
  selected_.reset();
  update();
}

void CellTracePlot::setQuantity(Quantity quantity) {
  quantity_ = quantity;
  update();
}

void CellTracePlot::setSelectedStep(std::optional<std::size_t> step) {
  selected_ = step;
  update();
}

void CellTracePlot::setMarkerTime(std::optional<double> time) {
  if (marker_ == time) return;
  marker_ = time;
  update();
}

double CellTracePlot::valueOf(const CellValue& v) const {
  switch (quantity_) {
    case Quantity::Probability:
      return v.probability;
    case Quantity::Level:
      return v.level;
    case Quantity::Native:
      break;
  }
  return v.native;
}

QString CellTracePlot::quantityTitle() const {
  switch (quantity_) {
    case Quantity::Probability:
      return tr("p(occ)");
    case Quantity::Level:
      return tr("level (0–15)");
    case Quantity::Native:
      break;
  }
  return trace_ ? QString::fromStdString(trace_->nativeName) : tr("value");
}

CellTracePlot::Frame CellTracePlot::frame() const {
  Frame f;
  const QFontMetricsF fm(font());
  const double left = fm.horizontalAdvance(QStringLiteral("−0.000")) + 14.0;
  f.area =
      QRectF(left, fm.height() + 6.0, width() - left - 12.0, height() - 2.0 * fm.height() - 18.0);
  if (!trace_) return f;
  f.t0 = trace_->firstTime;
  f.t1 = trace_->lastTime;
  if (!(f.t1 > f.t0)) f.t1 = f.t0 + 1.0;
  switch (quantity_) {
    case Quantity::Probability:
      f.y0 = 0.0;
      f.y1 = 1.0;
      break;
    case Quantity::Level:
      f.y0 = 0.0;
      f.y1 = 15.0;
      break;
    case Quantity::Native: {
      double lo = valueOf(trace_->initial), hi = lo;
      for (const CellTraceStep& s : trace_->steps) {
        lo = std::min(lo, valueOf(s.after));
        hi = std::max(hi, valueOf(s.after));
      }
      if (!(hi > lo)) {
        lo -= 0.5;
        hi += 0.5;
      }
      const double pad = 0.05 * (hi - lo);
      f.y0 = lo - pad;
      f.y1 = hi + pad;
      break;
    }
  }
  return f;
}

std::optional<std::size_t> CellTracePlot::stepAt(const QPointF& pixel) const {
  if (!trace_ || trace_->steps.empty()) return std::nullopt;
  const Frame f = frame();
  std::optional<std::size_t> best;
  double bestDistance = kPickPx;
  for (std::size_t k = 0; k < trace_->steps.size(); ++k) {
    const double d = std::abs(f.x(trace_->steps[k].time) - pixel.x());
    if (d <= bestDistance) {
      bestDistance = d;
      best = k;
    }
  }
  return best;
}

void CellTracePlot::mousePressEvent(QMouseEvent* event) {
  if (event->button() == Qt::LeftButton) {
    if (const auto step = stepAt(event->position())) {
      setSelectedStep(step);
      emit stepClicked(*step);
    }
  }
  event->accept();
}

void CellTracePlot::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.fillRect(rect(), palette().base());
  p.setRenderHint(QPainter::Antialiasing);
  const QColor ink = palette().color(QPalette::Text);
  QColor faint = ink;
  faint.setAlpha(50);
  const Frame f = frame();
  const QFontMetricsF fm(font());

  if (!trace_) {
    p.setPen(ink);
    p.drawText(rect(), Qt::AlignCenter | Qt::TextWordWrap,
               tr("Shift+click a cell of the grid to inspect it"));
    return;
  }

  // Grid lines and tick labels on both axes.
  const double yStep = niceStep(f.y1 - f.y0, 5);
  for (double v = std::ceil(f.y0 / yStep) * yStep; v <= f.y1 + 1e-9 * yStep; v += yStep) {
    const double y = f.y(v);
    p.setPen(faint);
    p.drawLine(QPointF(f.area.left(), y), QPointF(f.area.right(), y));
    p.setPen(ink);
    p.drawText(QRectF(0, y - fm.height() / 2, f.area.left() - 6, fm.height()),
               Qt::AlignRight | Qt::AlignVCenter, tickLabel(std::abs(v) < 1e-12 ? 0.0 : v, yStep));
  }
  const double tStep = niceStep(f.t1 - f.t0, 6);
  for (double t = std::ceil(f.t0 / tStep) * tStep; t <= f.t1 + 1e-9 * tStep; t += tStep) {
    const double x = f.x(t);
    p.setPen(faint);
    p.drawLine(QPointF(x, f.area.top()), QPointF(x, f.area.bottom()));
    p.setPen(ink);
    p.drawText(QRectF(x - 40, f.area.bottom() + 3, 80, fm.height()), Qt::AlignHCenter,
               tickLabel(t, tStep));
  }
  p.setPen(ink);
  p.drawRect(f.area);
  // Axis titles: y above its axis, x under the ticks.
  p.drawText(QRectF(4, 2, width() - 8, fm.height()), Qt::AlignLeft, quantityTitle());
  p.drawText(QRectF(f.area.left(), height() - fm.height() - 2, f.area.width(), fm.height()),
             Qt::AlignHCenter, tr("time (s)"));

  p.save();
  p.setClipRect(f.area.adjusted(-4, -4, 4, 4));
  // The timeline's time.
  if (marker_ && *marker_ >= f.t0 && *marker_ <= f.t1) {
    p.setPen(QPen(QColor(200, 60, 60), 1.0, Qt::DashLine));
    p.drawLine(QPointF(f.x(*marker_), f.area.top()), QPointF(f.x(*marker_), f.area.bottom()));
  }
  // The value holds between readings: a step line from the log's start, dots where it changed.
  const QColor line = palette().color(QPalette::Highlight);
  QPainterPath path;
  double value = valueOf(trace_->initial);
  path.moveTo(f.x(f.t0), f.y(value));
  for (const CellTraceStep& s : trace_->steps) {
    path.lineTo(f.x(s.time), f.y(value));
    value = valueOf(s.after);
    path.lineTo(f.x(s.time), f.y(value));
  }
  path.lineTo(f.x(f.t1), f.y(value));
  p.setPen(QPen(line, 1.5));
  p.setBrush(Qt::NoBrush);
  p.drawPath(path);
  p.setPen(Qt::NoPen);
  p.setBrush(line);
  const double dot = trace_->steps.size() > 400 ? 1.5 : 2.5;
  for (const CellTraceStep& s : trace_->steps)
    p.drawEllipse(QPointF(f.x(s.time), f.y(valueOf(s.after))), dot, dot);
  if (selected_ && *selected_ < trace_->steps.size()) {
    const CellTraceStep& s = trace_->steps[*selected_];
    p.setPen(QPen(QColor(230, 120, 0), 2.0));
    p.setBrush(Qt::NoBrush);
    p.drawEllipse(QPointF(f.x(s.time), f.y(valueOf(s.after))), 5.5, 5.5);
  }
  p.restore();
}

}  // namespace sg::ui
