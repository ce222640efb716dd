// SPDX-License-Identifier: GPL-3.0-or-later
#include "grid_view.h"

#include <QGestureEvent>
#include <QGuiApplication>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QNativeGestureEvent>
#include <QPainter>
#include <QPinchGesture>
#include <QVBoxLayout>
#include <QWheelEvent>
#include <algorithm>
#include <cmath>

#include "grid_gl_surface.h"

namespace sg::ui {

// The surface for platforms without OpenGL: paints renderGridImage(), caching the cells while only
// the overlays change and the overlays while only the map changes (a re-map repaints the cells
// alone; stroking the path and the cones again cost it several ms). Like the GL surface.
class GridRasterSurface : public QWidget {
 public:
  explicit GridRasterSurface(GridView* view) : QWidget(view), view_(view) {
    setAttribute(Qt::WA_OpaquePaintEvent);
  }
  void invalidateCells() { cellsValid_ = false; }
  void invalidateOverlays() { overlaysValid_ = false; }

 protected:
  void paintEvent(QPaintEvent*) override {
    const QSize size = view_->size();
    if (!cellsValid_ || cells_.size() != size || cachedView_ != view_->view_) {
      cells_ = renderGridCells(view_->scene_.map.get(), view_->palette_, view_->view_, size);
      cachedView_ = view_->view_;
      cellsValid_ = true;
    }
    if (!overlaysValid_ || overlays_.size() != size || overlaysView_ != view_->view_) {
      overlays_ = QImage(size, QImage::Format_ARGB32_Premultiplied);
      overlays_.fill(Qt::transparent);
      QPainter overlayPainter(&overlays_);
      paintOverlays(overlayPainter, view_->scene_, view_->palette_, view_->overlays_, view_->view_,
                    size);
      overlaysView_ = view_->view_;
      overlaysValid_ = true;
    }
    QPainter painter(this);
    painter.drawImage(0, 0, cells_);
    painter.drawImage(0, 0, overlays_);
    if (view_->tool_) view_->tool_->paint(painter, view_->view_, size);
    painter.end();
    view_->surfacePainted();
  }

 private:
  GridView* view_;
  QImage cells_, overlays_;
  ViewTransform cachedView_, overlaysView_;
  bool cellsValid_ = false, overlaysValid_ = false;
};

namespace {
constexpr double kWheelZoomPerDegree = 1.0025;  // one notch (15 degrees) zooms by about 4 %
constexpr double kKeyZoom = 1.25;
constexpr double kKeyPanPixels = 40.0;
constexpr double kMinPixelsPerMetre = 0.5;
constexpr double kMaxPixelsPerMetre = 20000.0;
}  // namespace

GridView::Backend GridView::automaticBackend() {
  const QString platform = QGuiApplication::platformName();
  if (platform == QLatin1String("offscreen") || platform == QLatin1String("minimal"))
    return Backend::Raster;
  return Backend::OpenGL;
}

GridView::GridView(Backend backend, QWidget* parent)
    : QWidget(parent),
      backend_(backend == Backend::Automatic ? automaticBackend() : backend),
      palette_(defaultLevelPalette()) {
  if (backend_ == Backend::OpenGL)
    surface_ = new GridGlSurface(this);
  else
    surface_ = new GridRasterSurface(this);
  // Events reach the view itself; the surface only draws.
  surface_->setAttribute(Qt::WA_TransparentForMouseEvents);
  surface_->setFocusPolicy(Qt::NoFocus);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(surface_);
  setFocusPolicy(Qt::StrongFocus);
  setMouseTracking(true);
  setAcceptDrops(false);
  grabGesture(Qt::PinchGesture);
  setMinimumSize(120, 90);
}

GridView::~GridView() = default;

void GridView::refresh(bool levelsChanged) {
  if (!levelsChanged) {
    if (backend_ == Backend::OpenGL)
      static_cast<GridGlSurface*>(surface_)->overlaysChanged();
    else
      static_cast<GridRasterSurface*>(surface_)->invalidateOverlays();
  }
  if (levelsChanged) {
    if (backend_ == Backend::OpenGL)
      static_cast<GridGlSurface*>(surface_)->levelsChanged();
    else
      static_cast<GridRasterSurface*>(surface_)->invalidateCells();
  }
  surface_->update();
}

namespace {
// Whether two grids cover the same ground to within two of the larger cells: a preview on coarser
// cells and the full map of the same log (RemapController::previewed) keep the user's view.
bool sameGround(const GridSpec& a, const GridSpec& b) {
  const double slack = 2.0 * std::max(a.cellSize, b.cellSize);
  return std::abs(a.origin.x() - b.origin.x()) <= slack &&
         std::abs(a.origin.y() - b.origin.y()) <= slack &&
         std::abs(a.width * a.cellSize - b.width * b.cellSize) <= slack &&
         std::abs(a.height * a.cellSize - b.height * b.cellSize) <= slack;
}
// Whether `b` is `a` grown, as a live map grows (Mapper::append): the same cells, more of them.
bool grownFrom(const GridSpec& a, const GridSpec& b) {
  const double tiny = 1e-6 * a.cellSize;  // origins moved by whole cells, printed as decimals
  return a.cellSize == b.cellSize && b.origin.x() <= a.origin.x() + tiny &&
         b.origin.y() <= a.origin.y() + tiny &&
         b.origin.x() + b.widthMetres() >= a.origin.x() + a.widthMetres() - tiny &&
         b.origin.y() + b.heightMetres() >= a.origin.y() + a.heightMetres() - tiny;
}
}  // namespace

void GridView::setMap(std::shared_ptr<const OccupancyMap> map) {
  // A grown live map keeps a view the user has moved; one still fitted is fitted again.
  const bool sameGrid = scene_.map && map &&
                        (sameGround(scene_.map->spec, map->spec) ||
                         (!followFit_ && grownFrom(scene_.map->spec, map->spec)));
  const bool tintShown = scene_.dminTint && overlays_.testFlag(Overlay::Dmin);
  scene_.map = std::move(map);
  if (tintShown) refresh(false);  // the tint is drawn over a map on its own grid only
  if (!sameGrid && scene_.map) {
    followFit_ = true;
    view_ = fittedView();
    refresh(false);  // the overlays move with the view
    emit viewChanged();
  }
  refresh(true);
}

void GridView::setReferenceLines(std::vector<std::vector<Position>> lines) {
  scene_.referenceLines = std::move(lines);
  refresh(false);
}

void GridView::setRobotAt(const Dataset* dataset, PoseSource pose, std::size_t scan) {
  if (dataset)
    placeRobot(scene_, *dataset, pose, scan);
  else
    placeRobot(scene_, Dataset{}, pose, 0);
  if (followsRobot() && !followFit_ && scene_.robot && width() > 0 && height() > 0) {
    const QPointF at = view_.toPixel(scene_.robot->position, size());
    const double mx = width() / 6.0, my = height() / 6.0;
    if (at.x() < mx || at.x() > width() - mx || at.y() < my || at.y() > height() - my) {
      view_.centre = scene_.robot->position;
      emit viewChanged();
    }
  }
  refresh(false);
}

void GridView::setFollowRobot(bool on) {
  if (on && !followRobot_) pannedAway_ = false;
  followRobot_ = on;
}

void GridView::setHighlightedSonar(std::optional<std::size_t> sonar) {
  if (scene_.highlightedSonar == sonar) return;
  scene_.highlightedSonar = sonar;
  refresh(false);
}

void GridView::setDminTint(std::shared_ptr<const QImage> tint, const GridSpec& spec) {
  scene_.dminTint = std::move(tint);
  scene_.dminSpec = spec;
  if (overlays_.testFlag(Overlay::Dmin)) refresh(false);
}

void GridView::setLevelPalette(const LevelPalette& palette) {
  palette_ = palette;
  if (backend_ == Backend::OpenGL) static_cast<GridGlSurface*>(surface_)->paletteChanged();
  refresh(false);  // the legend
  refresh(true);
}

void GridView::setOverlays(Overlays overlays) {
  overlays_ = overlays;
  refresh(false);
}

void GridView::setOverlay(Overlay overlay, bool on) {
  setOverlays(overlays_.setFlag(overlay, on));
}

void GridView::setView(const ViewTransform& view) {
  view_ = view;
  view_.pixelsPerMetre = std::clamp(view_.pixelsPerMetre, kMinPixelsPerMetre, kMaxPixelsPerMetre);
  followFit_ = false;
  refresh(false);
  emit viewChanged();
}

ViewTransform GridView::fittedView() const {
  if (!scene_.map) return view_;
  const GridSpec& g = scene_.map->spec;
  if (focus_.empty()) return ViewTransform::fitting(g, size());
  // The focus within the grid: a phantom echo may stretch the grid, never the first view.
  const Position gridHigh = g.origin + Position(g.widthMetres(), g.heightMetres());
  const Position low = focus_.low.cwiseMax(g.origin);
  const Position high = focus_.high.cwiseMin(gridHigh);
  if (!(low.x() < high.x() && low.y() < high.y())) return ViewTransform::fitting(g, size());
  return ViewTransform::fittingBox(low, high, size());
}

void GridView::setFocusArea(const FocusArea& area) {
  focus_ = area;
  if (followFit_ && scene_.map) {
    view_ = fittedView();
    refresh(false);
    emit viewChanged();
  }
}

void GridView::fitToMap() {
  if (!scene_.map) return;
  view_ = fittedView();
  followFit_ = true;
  pannedAway_ = false;
  refresh(false);
  emit viewChanged();
}

void GridView::zoomAt(double factor, const QPointF& pixel) {
  const Position anchor = view_.toWorld(pixel, size());
  ViewTransform t = view_;
  t.pixelsPerMetre =
      std::clamp(view_.pixelsPerMetre * factor, kMinPixelsPerMetre, kMaxPixelsPerMetre);
  // Keep `anchor` under `pixel`: solve toPixel(anchor) == pixel for the centre.
  t.centre = anchor - Position((pixel.x() - width() / 2.0) / t.pixelsPerMetre,
                               -(pixel.y() - height() / 2.0) / t.pixelsPerMetre);
  setView(t);
}

void GridView::panBy(const QPointF& pixels) {
  if (followRobot_) pannedAway_ = true;
  ViewTransform t = view_;
  t.centre -= Position(pixels.x() / t.pixelsPerMetre, -pixels.y() / t.pixelsPerMetre);
  setView(t);
}

CellReadout GridView::readoutAt(const QPointF& pixel) const {
  const Position world = view_.toWorld(pixel, size());
  if (!scene_.map) {
    CellReadout r;
    r.world = world;
    return r;
  }
  return readCell(*scene_.map, world);
}

void GridView::setTool(GridTool* tool) {
  if (tool_ == tool) return;
  tool_ = tool;
  dragging_ = false;
  unsetCursor();
  toolChanged();
}

void GridView::toolChanged() {
  // Both surfaces draw the tool afresh on every paint, over their cached cells and overlays.
  surface_->update();
}

QImage GridView::renderImage() const {
  return renderGridImage(scene_, palette_, overlays_, view_, size());
}

void GridView::paintVector(QPainter& painter) const {
  paintGridVector(painter, scene_, palette_, overlays_, view_, size());
}

QImage GridView::grabSurface() {
  if (backend_ == Backend::OpenGL) return static_cast<GridGlSurface*>(surface_)->grabFramebuffer();
  return surface_->grab().toImage();
}

void GridView::resizeEvent(QResizeEvent* event) {
  QWidget::resizeEvent(event);
  if (followFit_ && scene_.map) {
    view_ = fittedView();
    emit viewChanged();
  }
  refresh(false);
}

void GridView::wheelEvent(QWheelEvent* event) {
  const double degrees = event->angleDelta().y() / 8.0;
  if (degrees != 0.0) zoomAt(std::pow(kWheelZoomPerDegree, degrees), event->position());
  event->accept();
}

void GridView::mousePressEvent(QMouseEvent* event) {
  if (tool_ && tool_->mousePress(*this, event)) return event->accept();
  if (event->button() == Qt::LeftButton || event->button() == Qt::MiddleButton) {
    dragging_ = true;
    dragFrom_ = event->position();
    setCursor(Qt::ClosedHandCursor);
  }
  event->accept();
}

void GridView::mouseMoveEvent(QMouseEvent* event) {
  if (tool_ && tool_->mouseMove(*this, event)) dragging_ = false;
  if (dragging_) {
    panBy(event->position() - dragFrom_);
    dragFrom_ = event->position();
  }
  const CellReadout r = readoutAt(event->position());
  emit hovered(r);
  emit hoverText(describeReadout(r, nativeName_));
  event->accept();
}

void GridView::mouseReleaseEvent(QMouseEvent* event) {
  if (tool_ && tool_->mouseRelease(*this, event)) return event->accept();
  dragging_ = false;
  unsetCursor();
  event->accept();
}

void GridView::mouseDoubleClickEvent(QMouseEvent* event) {
  if (tool_ && tool_->mouseDoubleClick(*this, event)) return event->accept();
  fitToMap();
  event->accept();
}

void GridView::keyPressEvent(QKeyEvent* event) {
  if (tool_ && tool_->keyPress(*this, event)) return event->accept();
  const QPointF centre(width() / 2.0, height() / 2.0);
  switch (event->key()) {
    case Qt::Key_Plus:
    case Qt::Key_Equal:
      zoomAt(kKeyZoom, centre);
      break;
    case Qt::Key_Minus:
      zoomAt(1.0 / kKeyZoom, centre);
      break;
    case Qt::Key_F:
    case Qt::Key_Home:
    case Qt::Key_0:
      fitToMap();
      break;
    case Qt::Key_Left:
      panBy({kKeyPanPixels, 0.0});
      break;
    case Qt::Key_Right:
      panBy({-kKeyPanPixels, 0.0});
      break;
    case Qt::Key_Up:
      panBy({0.0, kKeyPanPixels});
      break;
    case Qt::Key_Down:
      panBy({0.0, -kKeyPanPixels});
      break;
    default:
      QWidget::keyPressEvent(event);
      return;
  }
  event->accept();
}

bool GridView::event(QEvent* event) {
  if (event->type() == QEvent::NativeGesture) {
    // Trackpad pinch (macOS, libinput under Wayland): value is the relative scale change.
    auto* g = static_cast<QNativeGestureEvent*>(event);
    if (g->gestureType() == Qt::ZoomNativeGesture) {
      zoomAt(1.0 + g->value(), g->position());
      return true;
    }
  }
  if (event->type() == QEvent::Gesture) {
    auto* g = static_cast<QGestureEvent*>(event);
    if (auto* pinch = static_cast<QPinchGesture*>(g->gesture(Qt::PinchGesture))) {
      if (pinch->changeFlags() & QPinchGesture::ScaleFactorChanged)
        zoomAt(pinch->scaleFactor(), mapFromGlobal(pinch->centerPoint()));
      g->accept(pinch);
      return true;
    }
  }
  return QWidget::event(event);
}

}  // namespace sg::ui
