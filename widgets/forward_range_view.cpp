// SPDX-License-Identifier: GPL-3.0-or-later
#include "forward_range_view.h"

#include <QPainter>
#include <QPainterPath>
#include <algorithm>
#include <cmath>

namespace sg::ui {

namespace {
constexpr int kSamples = 400;
}

ForwardRangeView::ForwardRangeView(QWidget* parent) : QWidget(parent) {
  setObjectName(QStringLiteral("forwardRangeView"));
  setMinimumSize(240, 160);
  clear();
}

void ForwardRangeView::clear() {
  ranges_.clear();
  prediction_ = {};
  measured_.reset();
  note_ =
      tr("The forward model's prediction for a reading appears here once EM has learned a "
         "map of the log.");
  update();
}

void ForwardRangeView::show(const forward::ForwardBeam& beam,
                            std::shared_ptr<const OccupancyMap> map,
                            const forward::ForwardSettings& settings) {
  if (!map || !forward::isForwardModelMap(*map)) {
    clear();
    return;
  }
  maxRange_ = beam.maxRange;
  ranges_.resize(kSamples);
  for (int i = 0; i < kSamples; ++i) ranges_[i] = (i + 0.5) * beam.maxRange / kSamples;
  try {
    prediction_ = forward::predictRange(beam, map->spec, map->native.values(), settings, ranges_);
  } catch (const forward::ForwardError& e) {
    ranges_.clear();
    prediction_ = {};
    note_ = QString::fromUtf8(e.what());
    update();
    return;
  }
  measured_ = beam.echo() ? std::optional<double>(beam.range) : std::nullopt;
  note_.clear();
  update();
}

void ForwardRangeView::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);
  p.fillRect(rect(), palette().base());
  const QFontMetrics fm = p.fontMetrics();
  if (ranges_.empty()) {
    p.setPen(palette().text().color());
    p.drawText(rect().adjusted(12, 12, -12, -12), Qt::AlignCenter | Qt::TextWordWrap, note_);
    return;
  }
  // The plot: ranges along x, density up; at the right a bar for P(no echo), on its own scale
  // (a probability, not a density), 0 to 1.
  const int left = fm.horizontalAdvance(QStringLiteral("00.0")) + 10;
  const int barWidth = 36;
  const QRect plot(left, fm.height() + 10, width() - left - barWidth - 24,
                   height() - 3 * fm.height() - 20);
  const QRect bar(plot.right() + 14, plot.top(), barWidth - 10, plot.height());
  const double peak =
      std::max(1e-9, *std::max_element(prediction_.density.begin(), prediction_.density.end()));
  const auto x = [&](double z) { return plot.left() + z / maxRange_ * plot.width(); };
  const auto y = [&](double d) { return plot.bottom() - d / peak * plot.height(); };

  p.setPen(palette().text().color());
  const QString title = tr("This reading's range as the EM map predicts it");
  p.drawText(QRect(4, 2, width() - 8, fm.height()), Qt::AlignHCenter,
             fm.elidedText(title, Qt::ElideRight, width() - 8));
  p.drawRect(plot);
  // x ticks every metre (every 2 m past 6 m).
  const double step = maxRange_ > 6.0 ? 2.0 : 1.0;
  for (double z = 0.0; z <= maxRange_ + 1e-9; z += step) {
    p.drawLine(QPointF(x(z), plot.bottom()), QPointF(x(z), plot.bottom() + 4));
    p.drawText(QRectF(x(z) - 20, plot.bottom() + 5, 40, fm.height()), Qt::AlignHCenter,
               QString::number(z, 'g', 3));
  }
  p.drawText(QRect(plot.left(), plot.bottom() + 5 + fm.height(), plot.width(), fm.height()),
             Qt::AlignHCenter, tr("range z (m)"));
  p.drawText(QRect(0, plot.top(), left - 6, fm.height()), Qt::AlignRight,
             QString::number(peak, 'g', 3));
  p.drawText(QRect(0, plot.bottom() - fm.height(), left - 6, fm.height()), Qt::AlignRight,
             QStringLiteral("0"));
  p.save();
  p.translate(12, plot.center().y());
  p.rotate(-90);
  p.drawText(QRect(-plot.height() / 2, -fm.height(), plot.height(), fm.height()), Qt::AlignHCenter,
             tr("p(z | m) per metre"));
  p.restore();

  QPainterPath curve;
  curve.moveTo(x(0.0), plot.bottom());
  for (std::size_t i = 0; i < ranges_.size(); ++i)
    curve.lineTo(x(ranges_[i]), y(prediction_.density[i]));
  curve.lineTo(x(maxRange_), plot.bottom());
  curve.closeSubpath();
  QColor fill(70, 120, 200, 90);
  p.fillPath(curve, fill);
  p.setPen(QPen(QColor(40, 80, 170), 1.5));
  p.drawPath(curve);

  // P(no echo), 0 to 1.
  p.setPen(palette().text().color());
  p.drawRect(bar);
  const double h = std::clamp(prediction_.noEcho, 0.0, 1.0) * bar.height();
  p.fillRect(QRectF(bar.left() + 1, bar.bottom() - h, bar.width() - 1, h), QColor(40, 80, 170));
  p.drawText(QRect(bar.left() - 10, bar.bottom() + 5, bar.width() + 20, fm.height()),
             Qt::AlignHCenter, tr("none"));

  // The measured range (red), or no echo (the bar outlined red).
  QPen red(QColor(200, 30, 30), 2);
  p.setPen(red);
  QString what;
  if (measured_) {
    p.drawLine(QPointF(x(*measured_), plot.top()), QPointF(x(*measured_), plot.bottom()));
    what = tr("measured %1 m").arg(*measured_, 0, 'f', 2);
  } else {
    p.drawRect(bar.adjusted(-2, -2, 2, 2));
    what = tr("measured: no echo");
  }
  p.drawText(QRect(plot.left() + 6, plot.top() + 4, plot.width() - 12, fm.height()), Qt::AlignRight,
             what);
  p.setPen(palette().text().color());
  p.drawText(QRect(plot.left() + 6, plot.top() + 4 + fm.height(), plot.width() - 12, fm.height()),
             Qt::AlignRight, tr("P(no echo) = %1").arg(prediction_.noEcho, 0, 'f', 3));
}

}  // namespace sg::ui
