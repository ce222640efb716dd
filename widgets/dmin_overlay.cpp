// SPDX-License-Identifier: GPL-3.0-or-later
#include "dmin_overlay.h"

#include <QPainter>
#include <algorithm>

#include "grid_image.h"

namespace sg::ui {
namespace {

constexpr int kTintAlpha = 210;

QColor mix(const QColor& a, const QColor& b, double t) {
  return QColor::fromRgbF(static_cast<float>(a.redF() + (b.redF() - a.redF()) * t),
                          static_cast<float>(a.greenF() + (b.greenF() - a.greenF()) * t),
                          static_cast<float>(a.blueF() + (b.blueF() - a.blueF()) * t));
}

void paintScale(QPainter& p, const QSize& size) {
  constexpr int kWidth = 150, kBar = 10, kMargin = 10, kPad = 6, kLabel = 14;
  const QRect box(size.width() - kMargin - kWidth - 2 * kPad, kMargin, kWidth + 2 * kPad,
                  kBar + kLabel + 2 * kPad + kLabel);
  if (box.left() < kMargin || box.bottom() + kMargin > size.height()) return;
  p.save();
  p.setRenderHint(QPainter::Antialiasing, false);
  p.setPen(QPen(QColor(40, 40, 40), 1.0));
  p.setBrush(QColor(255, 255, 255, 230));
  p.drawRect(QRectF(box).adjusted(0.5, 0.5, -0.5, -0.5));
  QFont font = p.font();
  font.setPixelSize(10);
  p.setFont(font);
  p.setPen(QColor(30, 30, 30));
  p.drawText(QRect(box.left() + kPad, box.top() + kPad, kWidth, kLabel), Qt::AlignCenter,
             QStringLiteral("D_min of filled cells"));
  const int barTop = box.top() + kPad + kLabel;
  for (int x = 0; x < kWidth; ++x) {
    const double mm = kDminRedMm * 1.25 * x / (kWidth - 1);
    p.fillRect(QRect(box.left() + kPad + x, barTop, 1, kBar), dminColour(mm));
  }
  p.setPen(QColor(30, 30, 30));
  const int labelTop = barTop + kBar;
  auto label = [&](double mm, const QString& text) {
    const int x = box.left() + kPad + static_cast<int>(mm / (kDminRedMm * 1.25) * (kWidth - 1));
    p.drawText(QRect(x - 30, labelTop, 60, kLabel), Qt::AlignCenter, text);
  };
  label(0.0, QStringLiteral("0"));
  label(kDminYellowMm, QString::number(kDminYellowMm, 'f', 0));
  label(kDminRedMm, QStringLiteral("%1 mm").arg(kDminRedMm, 0, 'f', 0));
  p.restore();
}

}  // namespace

QColor dminColour(double mm) {
  const QColor green(0, 200, 60), yellow(255, 220, 0), red(230, 20, 20);
  if (!(mm > 0.0)) return green;
  if (mm < kDminYellowMm) return mix(green, yellow, mm / kDminYellowMm);
  if (mm < kDminRedMm) return mix(yellow, red, (mm - kDminYellowMm) / (kDminRedMm - kDminYellowMm));
  return red;
}

QImage dminTintImage(const OccupancyMap& map, const std::vector<float>& distanceCells) {
  const GridSpec& g = map.spec;
  if (g.width <= 0 || g.height <= 0 || distanceCells.size() != g.cellCount() ||
      map.filled.size() != g.cellCount())
    return {};
  QImage image(g.width, g.height, QImage::Format_ARGB32);
  image.fill(Qt::transparent);
  for (int iy = 0; iy < g.height; ++iy) {
    auto* line = reinterpret_cast<QRgb*>(image.scanLine(g.height - 1 - iy));
    for (int ix = 0; ix < g.width; ++ix) {
      const std::size_t i = g.linear({ix, iy});
      if (map.filled[i] == 0) continue;
      const QColor c = dminColour(static_cast<double>(distanceCells[i]) * g.cellSize * 1000.0);
      line[ix] = qRgba(c.red(), c.green(), c.blue(), kTintAlpha);
    }
  }
  return image;
}

void paintDminTint(QPainter& p, const GridScene& scene, const ViewTransform& view,
                   const QSize& size) {
  if (!scene.dminTint || scene.dminTint->isNull() || !scene.map ||
      !(scene.map->spec == scene.dminSpec))
    return;
  drawCellImage(p, *scene.dminTint, scene.dminSpec, view, size);
  paintScale(p, size);
}

}  // namespace sg::ui
