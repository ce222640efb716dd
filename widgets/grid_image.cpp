// SPDX-License-Identifier: GPL-3.0-or-later
#include "grid_image.h"

#include <QPainter>
#include <QPainterPath>
#include <algorithm>
#include <cmath>
#include <limits>

#include "dmin_overlay.h"
#include "sonargrid/data/scan_poses.h"

namespace sg::ui {

QPointF ViewTransform::toPixel(const Position& world, const QSize& size) const {
  return {size.width() / 2.0 + (world.x() - centre.x()) * pixelsPerMetre,
          size.height() / 2.0 - (world.y() - centre.y()) * pixelsPerMetre};
}

Position ViewTransform::toWorld(const QPointF& pixel, const QSize& size) const {
  return {centre.x() + (pixel.x() - size.width() / 2.0) / pixelsPerMetre,
          centre.y() - (pixel.y() - size.height() / 2.0) / pixelsPerMetre};
}

ViewTransform ViewTransform::fitting(const GridSpec& grid, const QSize& size, int marginPx) {
  ViewTransform t;
  t.centre = grid.origin + Position(grid.widthMetres(), grid.heightMetres()) / 2.0;
  const double w = std::max(1, size.width() - 2 * marginPx);
  const double h = std::max(1, size.height() - 2 * marginPx);
  if (grid.width > 0 && grid.height > 0)
    t.pixelsPerMetre = std::min(w / grid.widthMetres(), h / grid.heightMetres());
  return t;
}

ViewTransform ViewTransform::fittingBox(const Position& low, const Position& high,
                                        const QSize& size, int marginPx) {
  ViewTransform t;
  t.centre = (low + high) / 2.0;
  const double w = std::max(1, size.width() - 2 * marginPx);
  const double h = std::max(1, size.height() - 2 * marginPx);
  const double bw = high.x() - low.x(), bh = high.y() - low.y();
  if (bw > 0.0 && bh > 0.0) t.pixelsPerMetre = std::min(w / bw, h / bh);
  return t;
}

FocusArea focusArea(const Dataset* data, PoseSource pose, const ReferenceMap* reference,
                    double marginMetres) {
  FocusArea a;
  a.low =
      Position(std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity());
  a.high = -a.low;
  auto take = [&a](const Position& p, double margin) {
    a.low = a.low.cwiseMin(p - Position(margin, margin));
    a.high = a.high.cwiseMax(p + Position(margin, margin));
  };
  if (data) {
    const PoseSource source =
        pose == PoseSource::Truth && !anyScanHasPose(*data, pose) ? PoseSource::Odometry : pose;
    for (const Scan& scan : data->scans)
      if (hasPose(scan, source)) take(data->pose(scan, source).position, marginMetres);
  }
  if (reference)
    for (const auto& line : referencePolylines(*reference))
      for (const Position& p : line) take(p, 0.0);
  if (a.empty()) return FocusArea{};
  return a;
}

std::vector<std::vector<Position>> referencePolylines(const ReferenceMap& reference) {
  std::vector<std::vector<Position>> lines;
  for (const ReferenceObject& object : reference.objects) {
    std::vector<Position> line;
    for (std::size_t i = 0; i < object.corners.size(); ++i)
      line.push_back(reference.cornerMetres(object, i));
    if (object.closed && !line.empty()) line.push_back(line.front());
    lines.push_back(std::move(line));
  }
  return lines;
}

void placeRobot(GridScene& scene, const Dataset& data, PoseSource asked, std::size_t scan) {
  // A log without any true pose is drawn by its odometry, as its map is.
  const PoseSource source = anyScanHasPose(data, asked) ? asked : PoseSource::Odometry;
  scene.path.clear();
  scene.sonars.clear();
  scene.beams.clear();
  scene.robot.reset();
  if (scan >= data.scans.size()) return;
  scene.path.reserve(scan + 1);
  // A scan without the pose of `source` is not on the map's path (data/scan_poses.h).
  for (std::size_t i = 0; i <= scan; ++i)
    if (hasPose(data.scans[i], source))
      scene.path.push_back(data.pose(data.scans[i], source).position);
  if (!hasPose(data.scans[scan], source)) return;
  const Pose2D robot = data.pose(data.scans[scan], source);
  scene.robot = robot;
  for (const SonarMount& mount : data.ring.sonars)
    scene.sonars.push_back(robot.compose(mount.pose));
  for (const Reading& r : data.scans[scan].readings) {
    if (r.sonar >= scene.sonars.size()) continue;
    BeamCone cone;
    cone.sonar = scene.sonars[r.sonar];
    cone.halfAngle = data.ring.apertureRad / 2.0;
    cone.echo = r.echo();
    cone.range = cone.echo ? r.range : data.ring.maxRange;
    cone.sonarIndex = r.sonar;
    scene.beams.push_back(cone);
  }
}

QColor backgroundColour() {
  return QColor(58, 62, 66);
}

QColor unknownColour() {
  return QColor(kUnknownColour.r, kUnknownColour.g, kUnknownColour.b);
}

namespace {

// The colour index of cell `i`: its level, or kLevels (unknown) when no reading wrote it. A map
// without an observed layer of the right size counts every cell as observed.
inline int colourIndex(const OccupancyMap& map, std::size_t i) {
  if (map.observed.size() == map.level.size() && map.observed[i] == 0) return kLevels;
  return std::min<int>(map.level[i], kLevels - 1);
}

}  // namespace

QImage renderGridCells(const OccupancyMap* map, const LevelPalette& palette,
                       const ViewTransform& view, const QSize& size) {
  QImage image(size, QImage::Format_RGB32);
  const QRgb background = backgroundColour().rgb();
  image.fill(background);
  if (!map || map->spec.width <= 0 || map->spec.height <= 0 || size.isEmpty()) return image;
  if (map->level.size() != map->spec.cellCount()) return image;
  const GridSpec& g = map->spec;
  QRgb colours[kLevels + 1];
  for (int k = 0; k < kLevels; ++k) {
    const Rgb& c = palette[static_cast<std::size_t>(k)];
    colours[k] = qRgb(c.r, c.g, c.b);
  }
  colours[kLevels] = unknownColour().rgb();
  // The cell column of every pixel column, computed once (-1 outside the grid).
  std::vector<int> columnCell(static_cast<std::size_t>(size.width()));
  for (int px = 0; px < size.width(); ++px) {
    const double x = view.toWorld(QPointF(px + 0.5, 0.0), size).x();
    const int ix = GridSpec::cellCoordinate((x - g.origin.x()) / g.cellSize);
    columnCell[static_cast<std::size_t>(px)] = ix >= 0 && ix < g.width ? ix : -1;
  }
  for (int py = 0; py < size.height(); ++py) {
    const double y = view.toWorld(QPointF(0.0, py + 0.5), size).y();
    const int iy = GridSpec::cellCoordinate((y - g.origin.y()) / g.cellSize);
    if (iy < 0 || iy >= g.height) continue;
    auto* line = reinterpret_cast<QRgb*>(image.scanLine(py));
    const std::size_t row = static_cast<std::size_t>(iy) * static_cast<std::size_t>(g.width);
    for (int px = 0; px < size.width(); ++px) {
      const int ix = columnCell[static_cast<std::size_t>(px)];
      if (ix >= 0) line[px] = colours[colourIndex(*map, row + static_cast<std::size_t>(ix))];
    }
  }
  return image;
}

namespace {

constexpr int kLegendMargin = 10;
constexpr int kLegendPadding = 6;
constexpr int kSwatch = 16;
constexpr int kLegendLabel = 14;

constexpr int kUnknownGap = 8;              // between level 15 and the unknown swatch
constexpr int kUnknownBlock = 3 * kSwatch;  // room for its label

QRect legendBox(const QSize& size) {
  const int w = 2 * kLegendPadding + kLevels * kSwatch + kUnknownGap + kUnknownBlock;
  const int h = 2 * kLegendPadding + kSwatch + kLegendLabel;
  return {kLegendMargin, size.height() - kLegendMargin - h, w, h};
}

bool legendFits(const QSize& size) {
  const QRect box = legendBox(size);
  return box.top() >= kLegendMargin && box.right() + kLegendMargin < size.width();
}

void paintLegend(QPainter& p, const LevelPalette& palette, const QSize& size) {
  if (!legendFits(size)) return;
  const QRect box = legendBox(size);
  p.setPen(QPen(QColor(40, 40, 40), 1.0));
  p.setBrush(QColor(255, 255, 255, 230));
  p.drawRect(QRectF(box).adjusted(0.5, 0.5, -0.5, -0.5));
  p.setPen(Qt::NoPen);
  for (int k = 0; k < kLevels; ++k) {
    const Rgb& c = palette[static_cast<std::size_t>(k)];
    p.fillRect(legendSwatch(k, size), QColor(c.r, c.g, c.b));
  }
  p.fillRect(legendSwatch(kLevels, size), unknownColour());
  QFont font = p.font();
  font.setPixelSize(10);
  p.setFont(font);
  p.setPen(QColor(30, 30, 30));
  const int labelTop = box.top() + kLegendPadding + kSwatch;
  for (int k : {0, 8, 15}) {
    const QRect s = legendSwatch(k, size);
    p.drawText(QRect(s.left() - 8, labelTop, s.width() + 16, kLegendLabel), Qt::AlignCenter,
               QString::number(k));
  }
  p.drawText(QRect(legendSwatch(2, size).left(), labelTop, 5 * kSwatch, kLegendLabel),
             Qt::AlignCenter, QStringLiteral("free"));
  p.drawText(QRect(legendSwatch(10, size).left(), labelTop, 4 * kSwatch, kLegendLabel),
             Qt::AlignCenter, QStringLiteral("occupied"));
  const QRect unknown = legendSwatch(kLevels, size);
  p.drawText(QRect(unknown.left() - kSwatch / 2, labelTop, kUnknownBlock, kLegendLabel),
             Qt::AlignCenter, QStringLiteral("unknown"));
}

QPolygonF polyline(const std::vector<Position>& points, const ViewTransform& view,
                   const QSize& size) {
  // Points less than a pixel from the last one kept add nothing visible but cost the stroker:
  // a 7,000-scan path drawn whole took 25 ms a frame. The last point is always kept.
  constexpr double kMinStepPx = 1.0;
  QPolygonF out;
  out.reserve(static_cast<qsizetype>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    const QPointF p = view.toPixel(points[i], size);
    if (!out.isEmpty() && i + 1 < points.size()) {
      const QPointF d = p - out.back();
      if (d.x() * d.x() + d.y() * d.y() < kMinStepPx * kMinStepPx) continue;
    }
    out << p;
  }
  return out;
}

QPainterPath conePath(const BeamCone& cone, const ViewTransform& view, const QSize& size) {
  constexpr int kArcSteps = 12;
  QPainterPath path(view.toPixel(cone.sonar.position, size));
  for (int i = 0; i <= kArcSteps; ++i) {
    const double a = cone.sonar.heading - cone.halfAngle + 2.0 * cone.halfAngle * i / kArcSteps;
    const Position tip = cone.sonar.position + cone.range * Position(std::cos(a), std::sin(a));
    path.lineTo(view.toPixel(tip, size));
  }
  path.closeSubpath();
  return path;
}

}  // namespace

QRect legendSwatch(int level, const QSize& size) {
  const QRect box = legendBox(size);
  const int gap = level >= kLevels ? kUnknownGap + kSwatch / 2 : 0;
  return {box.left() + kLegendPadding + level * kSwatch + gap, box.top() + kLegendPadding, kSwatch,
          kSwatch};
}

void paintOverlays(QPainter& p, const GridScene& scene, const LevelPalette& palette,
                   Overlays overlays, const ViewTransform& view, const QSize& size) {
  p.save();
  p.setRenderHint(QPainter::Antialiasing, true);
  p.setBrush(Qt::NoBrush);
  if (overlays.testFlag(Overlay::Dmin)) paintDminTint(p, scene, view, size);
  if (overlays.testFlag(Overlay::Reference)) {
    p.setPen(QPen(QColor(0, 190, 90), 2.0, Qt::SolidLine, Qt::RoundCap, Qt::RoundJoin));
    for (const auto& line : scene.referenceLines) p.drawPolyline(polyline(line, view, size));
  }
  if (overlays.testFlag(Overlay::Path) && scene.path.size() > 1) {
    p.setPen(QPen(QColor(255, 160, 0), 1.5, Qt::SolidLine, Qt::RoundCap, Qt::RoundJoin));
    p.drawPolyline(polyline(scene.path, view, size));
  }
  if (overlays.testFlag(Overlay::Beams)) {
    for (const BeamCone& cone : scene.beams) {
      if (cone.echo) {
        p.setPen(QPen(QColor(255, 214, 0, 200), 1.0));
        p.setBrush(QColor(255, 230, 0, 60));
      } else {
        p.setPen(QPen(QColor(0, 200, 255, 150), 1.0, Qt::DashLine));
        p.setBrush(QColor(0, 200, 255, 25));
      }
      p.drawPath(conePath(cone, view, size));
    }
    // The highlighted beam last, on top of its neighbours.
    for (const BeamCone& cone : scene.beams) {
      if (cone.sonarIndex != scene.highlightedSonar) continue;
      p.setPen(QPen(QColor(255, 60, 160), 2.5, cone.echo ? Qt::SolidLine : Qt::DashLine));
      p.setBrush(QColor(255, 60, 160, 70));
      p.drawPath(conePath(cone, view, size));
    }
    p.setBrush(Qt::NoBrush);
  }
  if (overlays.testFlag(Overlay::Robot) && scene.robot) {
    const QPointF c = view.toPixel(scene.robot->position, size);
    const double r = std::max(4.0, scene.robotRadius * view.pixelsPerMetre);
    p.setPen(QPen(QColor(20, 20, 20), 1.5));
    p.setBrush(QColor(255, 255, 255, 150));
    p.drawEllipse(c, r, r);
    const Position nose =
        scene.robot->position + scene.robotRadius * Position(std::cos(scene.robot->heading),
                                                             std::sin(scene.robot->heading));
    p.drawLine(c, view.toPixel(nose, size));
    p.setBrush(Qt::NoBrush);
  }
  if (overlays.testFlag(Overlay::Ring)) {
    p.setPen(QPen(QColor(0, 120, 255), 1.5));
    p.setBrush(QColor(0, 120, 255));
    for (const Pose2D& s : scene.sonars) {
      const QPointF c = view.toPixel(s.position, size);
      const Position tick = s.position + 0.08 * Position(std::cos(s.heading), std::sin(s.heading));
      p.drawEllipse(c, 2.5, 2.5);
      p.drawLine(c, view.toPixel(tick, size));
    }
    p.setBrush(Qt::NoBrush);
  }
  if (overlays.testFlag(Overlay::Legend)) {
    p.setRenderHint(QPainter::Antialiasing, false);
    paintLegend(p, palette, size);
  }
  p.restore();
}

QImage renderGridImage(const GridScene& scene, const LevelPalette& palette, Overlays overlays,
                       const ViewTransform& view, const QSize& size) {
  QImage image = renderGridCells(scene.map.get(), palette, view, size);
  QPainter painter(&image);
  paintOverlays(painter, scene, palette, overlays, view, size);
  return image;
}

void drawCellImage(QPainter& painter, const QImage& cells, const GridSpec& grid,
                   const ViewTransform& view, const QSize& size) {
  const QPointF topLeft = view.toPixel(grid.origin + Position(0.0, grid.heightMetres()), size);
  const QPointF bottomRight = view.toPixel(grid.origin + Position(grid.widthMetres(), 0.0), size);
  painter.save();
  painter.setClipRect(QRect(QPoint(0, 0), size));
  painter.setRenderHint(QPainter::SmoothPixmapTransform, false);
  painter.drawImage(QRectF(topLeft, bottomRight), cells);
  painter.restore();
}

void paintGridVector(QPainter& painter, const GridScene& scene, const LevelPalette& palette,
                     Overlays overlays, const ViewTransform& view, const QSize& size) {
  painter.fillRect(QRect(QPoint(0, 0), size), backgroundColour());
  const OccupancyMap* map = scene.map.get();
  if (map && map->spec.width > 0 && map->spec.height > 0 &&
      map->level.size() == map->spec.cellCount()) {
    const GridSpec& g = map->spec;
    // One pixel per cell, row 0 of the image at the top (world +y is up).
    QImage cells(g.width, g.height, QImage::Format_RGB32);
    for (int iy = 0; iy < g.height; ++iy) {
      auto* line = reinterpret_cast<QRgb*>(cells.scanLine(g.height - 1 - iy));
      for (int ix = 0; ix < g.width; ++ix) {
        const int k = colourIndex(*map, g.linear({ix, iy}));
        line[ix] = k == kLevels ? unknownColour().rgb()
                                : qRgb(palette[std::size_t(k)].r, palette[std::size_t(k)].g,
                                       palette[std::size_t(k)].b);
      }
    }
    drawCellImage(painter, cells, g, view, size);
  }
  paintOverlays(painter, scene, palette, overlays, view, size);
}

CellReadout readCell(const OccupancyMap& map, const Position& world) {
  CellReadout r;
  r.world = world;
  r.cell = map.spec.worldToCell(world);
  r.inside = map.spec.contains(r.cell);
  if (!r.inside) return r;
  const std::size_t i = map.spec.linear(r.cell);
  if (i < map.level.size()) r.level = map.level[i];
  if (i < map.probability.size()) r.probability = map.probability[i];
  if (i < map.native.size()) r.native = map.native[i];
  if (i < map.observed.size()) r.observed = map.observed[i] != 0;
  return r;
}

namespace {

// A probability with the precision it needs: three decimals in [0.001, 0.999]; beyond, the
// distance from 0 or 1 in two significant digits ("2.3e-86", "1 − 4.1e-07"), never "0.000".
QString probabilityText(double p) {
  if (!std::isfinite(p)) return QStringLiteral("—");
  if (p <= 0.0) return QStringLiteral("0");
  if (p >= 1.0) return QStringLiteral("1");
  if (p < 0.001) return QString::number(p, 'g', 2);
  if (p > 0.999) return QStringLiteral("1 − %1").arg(QString::number(1.0 - p, 'g', 2));
  return QString::number(p, 'f', 3);
}

}  // namespace

QString describeReadout(const CellReadout& r, const QString& nativeName) {
  QString text =
      QStringLiteral("x %1 m, y %2 m").arg(r.world.x(), 0, 'f', 3).arg(r.world.y(), 0, 'f', 3);
  if (!r.inside) return text + QStringLiteral("  (off the grid)");
  text += QStringLiteral("  |  cell (%1, %2)").arg(r.cell.x()).arg(r.cell.y());
  if (!r.observed) return text + QStringLiteral("  |  unknown (never observed)");
  text +=
      QStringLiteral("  |  CV %1  |  p(occ) %2").arg(r.level).arg(probabilityText(r.probability));
  // The rule's own value, unless it is that same probability again (the Bayes rules).
  const bool same = std::abs(r.native - r.probability) <= 1e-12 * std::max(1.0, std::abs(r.native));
  if (!same)
    text += QStringLiteral("  |  %1 %2")
                .arg(nativeName.isEmpty() ? QStringLiteral("native") : nativeName)
                .arg(r.native, 0, 'g', 4);
  return text;
}

}  // namespace sg::ui
