// SPDX-License-Identifier: GPL-3.0-or-later
#include "beam_model_render.h"

#include <QFont>
#include <QFontMetrics>
#include <QLinearGradient>
#include <QPainter>
#include <QPainterPath>
#include <QPolygonF>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "sonargrid/export/palette.h"

namespace sg::ui {

namespace {

constexpr double kPi = std::numbers::pi;

// One configured model, asked for values at (r, α) for one reading.
class BeamProbe {
 public:
  explicit BeamProbe(const BeamScene& scene)
      : model_(makeSensorModel(scene.settings.model)),
        range_(scene.range),
        maxRange_(scene.maxRange) {
    if (model_) model_->configure(scene.settings.parameters);
  }
  bool valid() const { return model_ != nullptr; }
  ModelValue at(double r, double alpha) const {
    if (!model_ || r < 0.0) return {};
    return model_->evaluate(r, alpha, range_, maxRange_);
  }
  // The value at plane point (x, y). A model may write a line of zero width (HIMM writes only the
  // acoustic axis): within `axisBand` of the axis, a point the model leaves alone takes the axis
  // value at its x (at exactly s within `axisBand` of it), so the line is drawn visibly wide.
  ModelValue atPoint(double x, double y, double axisBand) const {
    const ModelValue v = at(std::hypot(x, y), std::atan2(y, x));
    if (v.region != BeamRegion::Outside || std::abs(y) > axisBand || x <= 0.0) return v;
    const double onAxis = std::isfinite(range_) && std::abs(x - range_) <= axisBand ? range_ : x;
    return at(onAxis, 0.0);
  }
  const SensorModel* model() const { return model_.get(); }

 private:
  std::unique_ptr<SensorModel> model_;
  double range_, maxRange_;
};

int fontPixels(const QRect& area) {
  return std::clamp(area.height() / 16, 12, 18);
}

QFont fontOf(int pixels, bool bold = false) {
  QFont f;
  f.setPixelSize(pixels);
  f.setBold(bold);
  return f;
}

// About `count` round tick values covering [lo, hi].
std::vector<double> ticks(double lo, double hi, int count) {
  const double raw = (hi - lo) / std::max(1, count);
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10.0 * decade;
  for (const double m : {1.0, 2.0, 5.0}) {
    if (m * decade >= raw) {
      step = m * decade;
      break;
    }
  }
  std::vector<double> out;
  for (double t = std::ceil(lo / step - 1e-9) * step; t <= hi + 1e-9 * step; t += step) {
    out.push_back(std::abs(t) < 1e-12 ? 0.0 : t);
  }
  return out;
}

QString number(double v) {
  return QString::number(v, 'g', 4);
}

// `full` when it fits `width` pixels in `fm`, else `brief` (a narrow column in compare mode).
QString fitting(const QFontMetrics& fm, const QString& full, const QString& brief, double width) {
  return fm.horizontalAdvance(full) <= width ? full : brief;
}

// The titles of a plot's axes in `area`: `xFull` (`xBrief` where it does not fit) centred under
// `plot`, its top `below` font heights under the plot, and `y` turned up the left edge.
void drawAxisTitles(QPainter& painter, const QFontMetrics& fm, const QRect& area, const QRect& plot,
                    int fp, double below, const QString& xFull, const QString& xBrief,
                    const QString& y) {
  painter.drawText(QRectF(plot.left(), plot.bottom() + fp * below, plot.width(), fp * 1.4),
                   Qt::AlignHCenter | Qt::TextDontClip, fitting(fm, xFull, xBrief, plot.width()));
  painter.save();
  painter.translate(area.left() + fp * 0.9, plot.center().y());
  painter.rotate(-90);
  painter.drawText(QRectF(-plot.height() / 2.0, -fp, plot.height(), fp * 1.4), Qt::AlignHCenter, y);
  painter.restore();
}

// The model's own words for its regions, as its ModelInfo declares them (paper 002 §3.1 names
// Murphy's I, II and III; the others are named after what the region writes).
QString regionLabel(const ModelInfo& info, BeamRegion region, bool beyondReading) {
  const ModelInfo::Regions& r = info.regions;
  if (region == BeamRegion::Occupied && !r.occupied.empty())
    return QString::fromStdString(r.occupied);
  if (region == BeamRegion::Empty && !r.empty.empty()) return QString::fromStdString(r.empty);
  if (region == BeamRegion::Outside && beyondReading && !r.beyond.empty())
    return QString::fromStdString(r.beyond);
  if (region == BeamRegion::Occupied) return QStringLiteral("occupied");
  if (region == BeamRegion::Empty) return QStringLiteral("free");
  return QStringLiteral("no update");
}

QColor regionShade(BeamRegion region) {
  switch (region) {
    case BeamRegion::Occupied:
      return QColor(214, 72, 52, 50);
    case BeamRegion::Empty:
      return QColor(70, 130, 220, 45);
    case BeamRegion::Outside:
      break;
  }
  return QColor(150, 150, 150, 40);
}

QString modelSummary(const BeamScene& scene) {
  QStringList parts;
  parts << (std::isfinite(scene.range) ? QStringLiteral("s = %1 m").arg(number(scene.range))
                                       : QStringLiteral("no echo"));
  try {
    for (const ParameterSpec& spec : sensorModelInfo(scene.settings.model).parameters) {
      if (spec.name == "no_echo" || !scene.settings.parameters.has(spec.name)) continue;
      const QString unit = spec.unit == "deg" ? QStringLiteral("°")
                           : spec.unit.empty()
                               ? QString()
                               : QStringLiteral(" ") + QString::fromStdString(spec.unit);
      parts << QStringLiteral("%1 = %2%3")
                   .arg(QString::fromStdString(spec.symbol),
                        number(scene.settings.parameters.get(spec.name)), unit);
    }
  } catch (const std::exception&) {
  }
  return parts.join(QStringLiteral(" · "));
}

// Inner plot rectangle of a panel with axes: room on the left for tick labels and on the bottom
// for tick labels and the axis title.
QRect plotArea(const QRect& area) {
  const int fp = fontPixels(area);
  return area.adjusted(4 * fp, fp / 2, -fp, -3 * fp);
}

}  // namespace

QColor occupancyColour(double p) {
  const LevelPalette& palette = defaultLevelPalette();
  const double t = std::clamp(std::isfinite(p) ? p : 0.5, 0.0, 1.0) * 15.0;
  const int k = std::min(14, static_cast<int>(t));
  const double f = t - k;
  const Rgb& a = palette[static_cast<std::size_t>(k)];
  const Rgb& b = palette[static_cast<std::size_t>(k + 1)];
  auto mix = [f](int u, int v) { return static_cast<int>(std::lround(u + f * (v - u))); };
  return QColor(mix(a.r, b.r), mix(a.g, b.g), mix(a.b, b.b));
}

QColor noUpdateColour() {
  return QColor(226, 222, 210);
}

BeamExtent beamExtent(const std::vector<BeamScene>& scenes) {
  BeamExtent e{0.5, 0.0};
  for (const BeamScene& s : scenes) {
    e.xMax = std::max(e.xMax, std::isfinite(s.range) ? 1.3 * s.range + 0.2 : 1.1 * s.maxRange);
  }
  // Far enough to show where each model stops writing on the axis (Region III beyond it).
  const double searched = 2.0 * e.xMax;
  for (const BeamScene& s : scenes) {
    const BeamProbe probe(s);
    double far = 0.0;
    for (int i = 0; i <= 400; ++i) {
      const double r = searched * i / 400.0;
      if (probe.at(r, 0.0).region != BeamRegion::Outside) far = r;
    }
    e.xMax = std::max(e.xMax, 1.3 * far);
  }
  // How wide the models write: the largest angle at which any of them gives a value.
  double alpha = 0.0;
  for (const BeamScene& s : scenes) {
    const BeamProbe probe(s);
    for (int i = 1; i <= 40; ++i) {
      const double r = e.xMax * i / 40.0;
      for (double a = kPi / 2.0; a > alpha; a -= kPi / 360.0) {
        if (probe.at(r, a).region != BeamRegion::Outside) {
          alpha = a;
          break;
        }
      }
    }
  }
  e.yMax = std::max(0.25 * e.xMax, 1.08 * e.xMax * std::sin(std::min(alpha, kPi / 2.0)));
  return e;
}

ConeMapFrame coneMapFrame(const BeamExtent& extent, const QRect& area) {
  const QRect inner = plotArea(area);
  const double x0 = -0.05 * extent.xMax;
  const double w = extent.xMax - x0, h = 2.0 * extent.yMax;
  const double scale = std::min(inner.width() / w, inner.height() / h);
  const double pw = std::floor(w * scale), ph = std::floor(h * scale);
  const double left = std::floor(inner.left() + (inner.width() - pw) / 2.0);
  const double top = std::floor(inner.top() + (inner.height() - ph) / 2.0);
  return ConeMapFrame{QRectF(left, top, pw, ph), extent};
}

QPointF ConeMapFrame::toPixel(double x, double y) const {
  const double x0 = -0.05 * extent.xMax;
  const double scale = plot.width() / (extent.xMax - x0);
  return {plot.left() + (x - x0) * scale, plot.top() + (extent.yMax - y) * scale};
}

QPointF ConeMapFrame::toPlane(const QPointF& pixel) const {
  const double x0 = -0.05 * extent.xMax;
  const double scale = plot.width() / (extent.xMax - x0);
  return {x0 + (pixel.x() - plot.left()) / scale, extent.yMax - (pixel.y() - plot.top()) / scale};
}

AxialProfileFrame axialProfileFrame(const BeamExtent& extent, const QRect& area) {
  return AxialProfileFrame{plotArea(area), extent};
}

QPointF AxialProfileFrame::toPixel(double r, double p) const {
  const double x0 = -0.05 * extent.xMax;
  return {plot.left() + (r - x0) / (extent.xMax - x0) * plot.width(),
          plot.bottom() + 1 - p * plot.height()};
}

std::vector<AxialSpan> axialSpans(const BeamScene& scene, double xMax) {
  const BeamProbe probe(scene);
  std::vector<double> r;
  constexpr int kSamples = 1200;
  for (int i = 0; i <= kSamples; ++i) r.push_back(xMax * i / kSamples);
  if (std::isfinite(scene.range) && scene.range < xMax) r.push_back(scene.range);
  std::sort(r.begin(), r.end());
  r.erase(std::unique(r.begin(), r.end()), r.end());

  std::vector<AxialSpan> spans;
  for (const double x : r) {
    const BeamRegion region = probe.at(x, 0.0).region;
    if (!spans.empty() && spans.back().region == region) {
      spans.back().to = x;
    } else {
      spans.push_back({x, x, region, {}});
    }
  }
  // Boundaries lie halfway between the samples either side, except that a one-sample span (the
  // HIMM echo cell at exactly s) keeps its exact position.
  for (std::size_t i = 1; i < spans.size(); ++i) {
    const double mid = 0.5 * (spans[i - 1].to + spans[i].from);
    if (spans[i - 1].from != spans[i - 1].to) spans[i - 1].to = mid;
    if (spans[i].from != spans[i].to) spans[i].from = mid;
  }
  bool beyond = false;  // past a span that reaches the reading
  static const ModelInfo unnamed{};
  const ModelInfo* info = &unnamed;
  try {
    info = &sensorModelInfo(scene.settings.model);
  } catch (const std::exception&) {
  }
  for (AxialSpan& s : spans) {
    s.label = regionLabel(*info, s.region, beyond);
    if (s.region != BeamRegion::Outside && std::isfinite(scene.range) && s.to >= scene.range) {
      beyond = true;
    }
  }
  return spans;
}

BeamLayout beamLayout(QSize size, int columns) {
  columns = std::max(1, columns);
  BeamLayout l;
  const int fp = std::clamp(size.height() / 50, 12, 20);
  const int barWidth = std::max(7 * fp, size.width() / 11);
  const int columnWidth = (size.width() - barWidth) / columns;
  const int titleHeight = 4 * fp;  // a title and its settings, each on up to two lines
  // Two scenes side by side while each column is wide enough to read; in a narrower view (the
  // Beam Model dock at its default width) they stack one above the other, each the full width
  // (issue 49: compare mode could not be read at the dock's width).
  l.stacked = columns > 1 && columnWidth < kMinBeamColumnWidth;
  const int width = l.stacked ? size.width() - barWidth : columnWidth;
  const int band = l.stacked ? size.height() / columns : size.height();
  const int title = l.stacked ? std::min(titleHeight, band / 4) : titleHeight;
  const int rest = band - title;
  // The panels a band has room for, in this order: the cone map, the axial profile, the
  // surface. A low band (compare mode stacked in the dock above the parameter panel) drops the
  // surface, then the profile, rather than squeezing three unreadable panels.
  // Each panel keeps kMinBeamPanelHeight: three where the smallest share (the profile's 26 % side
  // by side, the surface's 27 % stacked) has it, two where the profile's 40 % of two has it.
  const int smallestOfThree = l.stacked ? 27 : 26;
  const int panels = rest * smallestOfThree / 100 >= kMinBeamPanelHeight ? 3
                     : rest * 40 / 100 >= kMinBeamPanelHeight            ? 2
                                                                         : 1;
  const int mapHeight = panels == 3   ? rest * (l.stacked ? 45 : 40) / 100
                        : panels == 2 ? rest * 60 / 100
                                      : rest;
  const int profileHeight = panels == 3   ? rest * (l.stacked ? 28 : 26) / 100
                            : panels == 2 ? rest - mapHeight
                                          : 0;
  const int surfaceHeight = rest - mapHeight - profileHeight;
  for (int c = 0; c < columns; ++c) {
    const int x = l.stacked ? 0 : c * columnWidth;
    const int y = l.stacked ? c * band : 0;
    l.title.emplace_back(x, y, width, title);
    l.map.emplace_back(x, y + title, width, mapHeight);
    l.profile.emplace_back(x, y + title + mapHeight, width, profileHeight);
    l.surface.emplace_back(x, y + title + mapHeight + profileHeight, width, surfaceHeight);
  }
  l.colourBar = l.stacked
                    ? QRect(width, title, barWidth, size.height() - 2 * title)
                    // A low view gives the bar its whole height: room for its labels.
                    : (panels == 3 ? QRect(columns * columnWidth, titleHeight, barWidth,
                                           mapHeight + profileHeight)
                                   : QRect(columns * columnWidth, 0, barWidth, size.height()));
  return l;
}

void drawConeMap(QPainter& painter, const BeamScene& scene, const BeamExtent& extent,
                 const QRect& area) {
  const ConeMapFrame frame = coneMapFrame(extent, area);
  const QRect plot = frame.plot.toRect();
  const BeamProbe probe(scene);
  const double metresPerPixel = (extent.xMax * 1.05) / std::max(1.0, frame.plot.width());
  const double axisBand = 1.5 * metresPerPixel;

  QImage image(plot.size(), QImage::Format_RGB32);
  const QRgb background = noUpdateColour().rgb();
  for (int j = 0; j < image.height(); ++j) {
    auto* line = reinterpret_cast<QRgb*>(image.scanLine(j));
    for (int i = 0; i < image.width(); ++i) {
      const QPointF p = frame.toPlane(QPointF(plot.left() + i + 0.5, plot.top() + j + 0.5));
      const ModelValue v = probe.atPoint(p.x(), p.y(), axisBand);
      line[i] = v.region == BeamRegion::Outside ? background : occupancyColour(v.probability).rgb();
    }
  }
  painter.drawImage(plot.topLeft(), image);

  const int fp = fontPixels(area);
  painter.save();
  painter.setRenderHint(QPainter::Antialiasing);
  painter.setFont(fontOf(fp));
  painter.setPen(QPen(QColor(60, 60, 60), 1));
  painter.setBrush(Qt::NoBrush);
  painter.drawRect(QRectF(plot).adjusted(-0.5, -0.5, 0.5, 0.5));
  const QFontMetrics fm(painter.font());
  for (const double t : ticks(0.0, extent.xMax, 6)) {
    const QPointF p = frame.toPixel(t, -extent.yMax);
    painter.drawLine(p, p + QPointF(0, fp * 0.4));
    const QString text = number(t);
    painter.drawText(QPointF(p.x() - fm.horizontalAdvance(text) / 2.0, p.y() + fp * 1.4), text);
  }
  for (const double t : ticks(-extent.yMax, extent.yMax, 4)) {
    const QPointF p = frame.toPixel(-0.05 * extent.xMax, t);
    painter.drawLine(p, p - QPointF(fp * 0.4, 0));
    const QString text = number(t);
    painter.drawText(QPointF(p.x() - fp * 0.6 - fm.horizontalAdvance(text), p.y() + fp * 0.35),
                     text);
  }
  drawAxisTitles(painter, fm, area, plot, fp, 1.5, QStringLiteral("x [m] along the acoustic axis"),
                 QStringLiteral("x [m]"), QStringLiteral("y [m]"));

  // The sensor, and where the reading s lies on the axis.
  const QPointF origin = frame.toPixel(0.0, 0.0);
  painter.setPen(Qt::NoPen);
  painter.setBrush(QColor(20, 20, 20));
  painter.drawPolygon(QPolygonF{origin + QPointF(-fp * 0.6, -fp * 0.45),
                                origin + QPointF(-fp * 0.6, fp * 0.45), origin});
  if (std::isfinite(scene.range) && scene.range <= extent.xMax) {
    const QPointF tick = frame.toPixel(scene.range, -extent.yMax);
    painter.setBrush(QColor(20, 20, 20));
    painter.drawPolygon(
        QPolygonF{tick, tick + QPointF(-fp * 0.4, -fp * 0.6), tick + QPointF(fp * 0.4, -fp * 0.6)});
    painter.setPen(QColor(20, 20, 20));
    painter.setFont(fontOf(fp, true));
    painter.drawText(tick + QPointF(fp * 0.5, -fp * 0.3), QStringLiteral("s"));
  }
  painter.restore();
}

void drawAxialProfile(QPainter& painter, const BeamScene& scene, const BeamExtent& extent,
                      const QRect& area) {
  const int fp = fontPixels(area);
  const AxialProfileFrame frame = axialProfileFrame(extent, area);
  const QRect plot = frame.plot;
  auto px = [&](double r) { return frame.toPixel(r, 0.0).x(); };
  auto py = [&](double p) { return frame.toPixel(0.0, p).y(); };

  painter.save();
  painter.setRenderHint(QPainter::Antialiasing);
  painter.fillRect(plot, Qt::white);

  // Regions, shaded and labelled.
  const std::vector<AxialSpan> spans = axialSpans(scene, extent.xMax);
  painter.setFont(fontOf(fp, true));
  const QFontMetrics bold(painter.font());
  // Labels go where the curve is not (low for Region I, whose values are high; high elsewhere),
  // centred over their own region (never beside it, over a neighbour), on the first of three lines
  // where they overlap no label already placed. A label wider than its region gets a tick down
  // to it.
  std::vector<QRectF> placed;
  for (const AxialSpan& s : spans) {
    double a = px(s.from), b = px(s.to);
    if (b - a < 3.0) a = (a + b) / 2.0 - 1.5, b = a + 3.0;
    painter.fillRect(QRectF(a, plot.top(), b - a, plot.height()), regionShade(s.region));
  }
  painter.setPen(QColor(40, 40, 40));
  for (const AxialSpan& s : spans) {
    const double a = std::max<double>(px(s.from), plot.left());
    const double b = std::min<double>(px(s.to), plot.right() + 1);
    if (b <= a && s.from != s.to) continue;  // outside the plot
    const double width = bold.horizontalAdvance(s.label) + 6.0;
    const double centre = (a + b) / 2.0;
    const double left =
        std::clamp(centre - width / 2.0, double(plot.left()), plot.right() + 1.0 - width);
    const bool low = s.region == BeamRegion::Occupied;
    for (int line = 0; line < 3; ++line) {
      const double top =
          low ? plot.bottom() - fp * (1.6 + 1.3 * line) : plot.top() + fp * (0.2 + 1.3 * line);
      const QRectF box(left, top, width, fp * 1.3);
      const bool free = std::none_of(placed.begin(), placed.end(),
                                     [&](const QRectF& r) { return r.intersects(box); });
      if (!free) continue;
      painter.drawText(box, Qt::AlignCenter, s.label);
      if (width > b - a + 2.0) {
        const double y = low ? box.top() : box.bottom();
        painter.drawLine(QPointF(centre, y), QPointF(centre, y + (low ? -fp * 0.5 : fp * 0.5)));
      }
      placed.push_back(box);
      break;
    }
  }

  // P = 0.5: no information.
  painter.setPen(QPen(QColor(120, 120, 120), 1, Qt::DashLine));
  painter.drawLine(QPointF(plot.left(), py(0.5)), QPointF(plot.right(), py(0.5)));

  // The curve P(r, α = 0), broken where the model writes nothing.
  const BeamProbe probe(scene);
  std::vector<double> rs;
  const int n = std::max(200, plot.width() * 2);
  for (int i = 0; i <= n; ++i) rs.push_back(extent.xMax * i / n);
  if (std::isfinite(scene.range) && scene.range <= extent.xMax) rs.push_back(scene.range);
  std::sort(rs.begin(), rs.end());
  painter.setPen(QPen(QColor(25, 25, 25), 2.5, Qt::SolidLine, Qt::RoundCap, Qt::RoundJoin));
  QPolygonF run;
  auto flush = [&]() {
    if (run.size() == 1) {
      // A single point (the HIMM echo cell): a stem from 0.5 to the value and a dot.
      painter.drawLine(QPointF(run[0].x(), py(0.5)), run[0]);
      painter.drawEllipse(run[0], 3.0, 3.0);
    } else if (run.size() > 1) {
      painter.drawPolyline(run);
    }
    run.clear();
  };
  for (const double r : rs) {
    const ModelValue v = probe.at(r, 0.0);
    if (v.region == BeamRegion::Outside) {
      flush();
      continue;
    }
    run << QPointF(px(r), py(v.probability));
  }
  flush();

  // The reading.
  if (std::isfinite(scene.range) && scene.range <= extent.xMax) {
    painter.setPen(QPen(QColor(20, 20, 20), 1, Qt::DotLine));
    painter.drawLine(QPointF(px(scene.range), plot.top()), QPointF(px(scene.range), plot.bottom()));
  }

  // Axes.
  painter.setFont(fontOf(fp));
  const QFontMetrics fm(painter.font());
  painter.setPen(QPen(QColor(60, 60, 60), 1));
  painter.setBrush(Qt::NoBrush);
  painter.drawRect(QRectF(plot).adjusted(-0.5, -0.5, 0.5, 0.5));
  for (const double t : ticks(0.0, extent.xMax, 6)) {
    const double x = px(t);
    painter.drawLine(QPointF(x, plot.bottom()), QPointF(x, plot.bottom() + fp * 0.4));
    const QString text = number(t);
    painter.drawText(QPointF(x - fm.horizontalAdvance(text) / 2.0, plot.bottom() + fp * 1.5), text);
  }
  for (const double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    const double y = py(t);
    painter.drawLine(QPointF(plot.left(), y), QPointF(plot.left() - fp * 0.4, y));
    const QString text = number(t);
    painter.drawText(QPointF(plot.left() - fp * 0.6 - fm.horizontalAdvance(text), y + fp * 0.35),
                     text);
  }
  drawAxisTitles(painter, fm, area, plot, fp, 1.6, QStringLiteral("r [m] on the axis (α = 0)"),
                 QStringLiteral("r [m], α = 0"), QStringLiteral("P(occ)"));
  painter.restore();
}

void drawSurface(QPainter& painter, const BeamScene& scene, const BeamExtent& extent,
                 const QRect& area) {
  // A mesh over the plane, z = P(occ) (0.5 where the model writes nothing: "the flat space
  // represents unknown", paper 002 Fig. 2), drawn back to front (painter's algorithm).
  const BeamProbe probe(scene);
  std::vector<double> xs, ys;
  constexpr int kNx = 48, kNy = 30;
  for (int i = 0; i <= kNx; ++i) xs.push_back(extent.xMax * i / kNx);
  if (std::isfinite(scene.range) && scene.range < extent.xMax) xs.push_back(scene.range);
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  for (int j = 0; j <= kNy; ++j) ys.push_back(-extent.yMax + 2.0 * extent.yMax * j / kNy);

  struct Vertex {
    double x, y, p;
    bool inside;
  };
  std::vector<Vertex> vertices;
  const double band = 0.6 * (ys[1] - ys[0]);
  for (const double y : ys) {
    for (const double x : xs) {
      const ModelValue v = probe.atPoint(x, y, band);
      vertices.push_back({x, y, v.probability, v.region != BeamRegion::Outside});
    }
  }
  const std::size_t nx = xs.size();
  auto vertex = [&](std::size_t i, std::size_t j) -> const Vertex& { return vertices[j * nx + i]; };

  // View: azimuth and elevation chosen so the cone opens to the right and the peaks stand up.
  const double az = -0.35, el = 0.45;
  const double ca = std::cos(az), sa = std::sin(az), ce = std::cos(el), se = std::sin(el);
  const double height = 0.5;  // box height relative to the axis length
  struct Projected {
    QPointF screen;
    double depth;
  };
  auto project = [&](double x, double y, double p) {
    const double u = x / extent.xMax - 0.5, v = y / extent.xMax, w = (p - 0.5) * height;
    const double sx = u * ca - v * sa;
    const double d = u * sa + v * ca;  // into the screen
    return Projected{QPointF(sx, -(w * ce + d * se)), d * ce - w * se};
  };

  // Fit the box into the area.
  const int fp = fontPixels(area);
  std::vector<QPointF> corners;
  for (const double x : {0.0, extent.xMax}) {
    for (const double y : {-extent.yMax, extent.yMax}) {
      for (const double p : {0.0, 1.0}) corners.push_back(project(x, y, p).screen);
    }
  }
  double minX = 1e9, maxX = -1e9, minY = 1e9, maxY = -1e9;
  for (const QPointF& c : corners) {
    minX = std::min(minX, c.x()), maxX = std::max(maxX, c.x());
    minY = std::min(minY, c.y()), maxY = std::max(maxY, c.y());
  }
  const QRectF target = QRectF(area).adjusted(3.0 * fp, 1.2 * fp, -fp, -1.4 * fp);
  const double scale = std::min(target.width() / (maxX - minX), target.height() / (maxY - minY));
  const QPointF offset(target.center().x() - scale * (minX + maxX) / 2.0,
                       target.center().y() - scale * (minY + maxY) / 2.0);
  auto toScreen = [&](double x, double y, double p) {
    return offset + scale * project(x, y, p).screen;
  };

  struct Quad {
    QPolygonF polygon;
    QColor colour;
    double depth;
  };
  std::vector<Quad> quads;
  quads.reserve((nx - 1) * (ys.size() - 1));
  for (std::size_t j = 0; j + 1 < ys.size(); ++j) {
    for (std::size_t i = 0; i + 1 < nx; ++i) {
      const std::array<const Vertex*, 4> c = {&vertex(i, j), &vertex(i + 1, j),
                                              &vertex(i + 1, j + 1), &vertex(i, j + 1)};
      QPolygonF poly;
      double depth = 0.0, sum = 0.0;
      int inside = 0;
      for (const Vertex* v : c) {
        const double p = v->inside ? v->p : 0.5;
        poly << toScreen(v->x, v->y, p);
        depth += project(v->x, v->y, p).depth;
        if (v->inside) sum += v->p, ++inside;
      }
      QColor colour = noUpdateColour();
      if (inside > 0) {
        colour = occupancyColour(sum / inside);
        // Light from the viewer's upper left: steeper faces turned away are darker.
        const double dzdx = (c[1]->p - c[0]->p + c[2]->p - c[3]->p) / 2.0;
        const double shade = std::clamp(0.92 - 0.6 * dzdx * height * 4.0, 0.7, 1.0);
        colour = QColor::fromRgbF(static_cast<float>(colour.redF() * shade),
                                  static_cast<float>(colour.greenF() * shade),
                                  static_cast<float>(colour.blueF() * shade));
      }
      quads.push_back({poly, colour, depth / 4.0});
    }
  }
  std::sort(quads.begin(), quads.end(),
            [](const Quad& a, const Quad& b) { return a.depth > b.depth; });

  painter.save();
  painter.setRenderHint(QPainter::Antialiasing);
  // The box's back walls and floor, then the surface over them.
  painter.setPen(QPen(QColor(170, 170, 170), 1));
  const QPointF o0 = toScreen(0.0, extent.yMax, 0.0), o1 = toScreen(extent.xMax, extent.yMax, 0.0),
                o2 = toScreen(extent.xMax, -extent.yMax, 0.0),
                o3 = toScreen(0.0, -extent.yMax, 0.0);
  painter.drawPolygon(QPolygonF{o0, o1, o2, o3});
  painter.setFont(fontOf(fp));
  const QFontMetrics fm(painter.font());
  for (const double t : {0.0, 0.5, 1.0}) {
    const QPointF a = toScreen(0.0, extent.yMax, t), b = toScreen(extent.xMax, extent.yMax, t);
    painter.setPen(QPen(QColor(170, 170, 170), 1, t == 0.5 ? Qt::DashLine : Qt::SolidLine));
    painter.drawLine(a, b);
    painter.setPen(QColor(60, 60, 60));
    const QString text = number(t);
    painter.drawText(a + QPointF(-fm.horizontalAdvance(text) - fp * 0.4, fp * 0.35), text);
  }
  painter.setPen(QPen(QColor(170, 170, 170), 1));
  painter.drawLine(toScreen(0.0, extent.yMax, 0.0), toScreen(0.0, extent.yMax, 1.0));

  for (const Quad& q : quads) {
    painter.setBrush(q.colour);
    // Wire edges on the surface only; the flat no-update plane stays calm.
    painter.setPen(q.colour == noUpdateColour() ? QPen(q.colour, 0.6)
                                                : QPen(q.colour.darker(135), 0.6));
    painter.drawPolygon(q.polygon);
  }

  painter.setPen(QColor(60, 60, 60));
  const QPointF pLabel = toScreen(0.0, extent.yMax, 1.0);
  painter.drawText(pLabel + QPointF(-fp * 1.5, -fp * 0.6), QStringLiteral("P(occ)"));
  const QPointF rLabel = toScreen(extent.xMax, -extent.yMax, 0.0);
  painter.drawText(rLabel + QPointF(-fp * 5, fp * 1.3),
                   QStringLiteral("x → %1 m").arg(extent.xMax, 0, 'f', 1));
  painter.restore();
}

void drawColourBar(QPainter& painter, const QRect& area) {
  const int fp = std::clamp(area.height() / 28, 12, 18);
  painter.save();
  painter.setRenderHint(QPainter::Antialiasing);
  painter.setFont(fontOf(fp, true));
  painter.setPen(QColor(40, 40, 40));
  painter.drawText(QRect(area.left(), area.top(), area.width(), fp * 2), Qt::AlignCenter,
                   QStringLiteral("P(occ)"));
  const QRect bar(area.left() + fp / 2, area.top() + fp * 4, fp * 2, area.height() - fp * 10);
  for (int y = 0; y < bar.height(); ++y) {
    const double p = 1.0 - (y + 0.5) / bar.height();
    painter.fillRect(QRect(bar.left(), bar.top() + y, bar.width(), 1), occupancyColour(p));
  }
  painter.setBrush(Qt::NoBrush);
  painter.setPen(QPen(QColor(60, 60, 60), 1));
  painter.drawRect(QRectF(bar).adjusted(-0.5, -0.5, 0.5, 0.5));
  painter.setFont(fontOf(fp));
  // Five labelled ticks where a label's height fits between two, else three, else the ends.
  const double labelSpace = bar.height() / static_cast<double>(fp);
  const std::vector<double> ticks = labelSpace >= 6.0
                                        ? std::vector<double>{0.0, 0.25, 0.5, 0.75, 1.0}
                                    : labelSpace >= 3.0 ? std::vector<double>{0.0, 0.5, 1.0}
                                                        : std::vector<double>{0.0, 1.0};
  for (const double t : ticks) {
    const double y = bar.bottom() + 1 - t * bar.height();
    painter.drawLine(QPointF(bar.right() + 1, y), QPointF(bar.right() + fp * 0.5, y));
    painter.drawText(QPointF(bar.right() + fp * 0.7, y + fp * 0.35), number(t));
  }
  painter.setFont(fontOf(std::max(11, fp - 2)));
  painter.drawText(QPointF(bar.left(), bar.top() - fp * 0.9), QStringLiteral("occupied"));
  painter.drawText(QPointF(bar.left(), bar.bottom() + fp * 1.3), QStringLiteral("free"));
  // The no-update swatch.
  const QRect swatch(bar.left(), bar.bottom() + fp * 2, bar.width(), fp * 2);
  painter.fillRect(swatch, noUpdateColour());
  painter.drawRect(QRectF(swatch).adjusted(-0.5, -0.5, 0.5, 0.5));
  painter.drawText(QRect(area.left(), swatch.bottom() + fp / 2, area.width(), fp * 3),
                   Qt::AlignHCenter | Qt::TextWordWrap, QStringLiteral("no update"));
  painter.restore();
}

QImage renderBeamModel(const std::vector<BeamScene>& scenes, QSize size) {
  QImage image(size, QImage::Format_RGB32);
  image.fill(Qt::white);
  if (scenes.empty() || size.isEmpty()) return image;
  const BeamLayout layout = beamLayout(size, static_cast<int>(scenes.size()));
  const BeamExtent extent = beamExtent(scenes);
  QPainter painter(&image);
  for (std::size_t c = 0; c < scenes.size(); ++c) {
    const BeamScene& scene = scenes[c];
    const QRect title = layout.title[c];
    const int fp = std::clamp(title.height() / 3, 12, 20);
    QString heading;
    try {
      heading = QString::fromStdString(sensorModelInfo(scene.settings.model).title);
    } catch (const std::exception&) {
      heading =
          QStringLiteral("unknown model '%1'").arg(QString::fromStdString(scene.settings.model));
    }
    painter.setPen(QColor(20, 20, 20));
    // The title and the settings wrap; both shrink together until they fit the title band.
    const QRect inner = title.adjusted(fp / 2, fp / 4, -fp / 2, 0);
    const int flags = Qt::AlignLeft | Qt::AlignTop | Qt::TextWordWrap;
    const QString summary = modelSummary(scene);
    int pixels = fp;
    QRect headRect, summaryRect;
    for (;; --pixels) {
      headRect = QFontMetrics(fontOf(pixels, true)).boundingRect(inner, flags, heading);
      summaryRect = QFontMetrics(fontOf(std::max(9, pixels - 3)))
                        .boundingRect(inner.adjusted(0, headRect.height(), 0, 0), flags, summary);
      if (pixels <= 9 || headRect.height() + summaryRect.height() <= inner.height()) break;
    }
    painter.setFont(fontOf(pixels, true));
    painter.drawText(inner, flags, heading);
    painter.setFont(fontOf(std::max(9, pixels - 3)));
    painter.drawText(inner.adjusted(0, headRect.height(), 0, 0), flags, summary);
    drawConeMap(painter, scene, extent, layout.map[c]);
    if (!layout.profile[c].isEmpty()) drawAxialProfile(painter, scene, extent, layout.profile[c]);
    if (!layout.surface[c].isEmpty()) drawSurface(painter, scene, extent, layout.surface[c]);
    if (c > 0) {
      painter.setPen(QPen(QColor(200, 200, 200), 1));
      if (layout.stacked)
        painter.drawLine(title.topLeft(), title.topRight());
      else
        painter.drawLine(title.topLeft(), QPoint(title.left(), size.height() - 1));
    }
  }
  drawColourBar(painter, layout.colourBar);
  return image;
}

}  // namespace sg::ui
