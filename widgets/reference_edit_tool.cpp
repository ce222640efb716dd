// SPDX-License-Identifier: GPL-3.0-or-later
#include "reference_edit_tool.h"

#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>
#include <QPainterPath>
#include <cmath>

#include "grid_view.h"
#include "typed_length.h"

namespace sg::ui {
namespace {

double pixelDistance(const QPointF& a, const QPointF& b) {
  return std::hypot(a.x() - b.x(), a.y() - b.y());
}

// Nearest point of segment ab to p, as the fraction along ab.
double projection(const QPointF& a, const QPointF& b, const QPointF& p) {
  const QPointF d = b - a;
  const double len2 = d.x() * d.x() + d.y() * d.y();
  if (len2 == 0.0) return 0.0;
  return std::clamp(((p - a).x() * d.x() + (p - a).y() * d.y()) / len2, 0.0, 1.0);
}

// Colours chosen apart from the 16-level palette (grey to black) and the green reference overlay.
const QColor kObjectColour(0, 170, 255);
const QColor kSelectedColour(255, 120, 0);
const QColor kPendingColour(220, 0, 220);

}  // namespace

ReferenceEditTool::ReferenceEditTool(ReferenceEditModel* model, QObject* parent)
    : QObject(parent), model_(model) {
  connect(model_, &ReferenceEditModel::changed, this, [this] {
    if (datum_.object >= model_->objectCount()) datum_ = {};
    hover_ = {};
    emit repaintNeeded();
  });
  connect(model_, &ReferenceEditModel::selectionChanged, this, &ReferenceEditTool::repaintNeeded);
}

void ReferenceEditTool::setSnapping(bool on) {
  if (snapping_ == on) return;
  snapping_ = on;
  emit snappingChanged(on);
  emit message(
      on ? tr("Snapping on: to corners within %1 px, else to the grid's cell lines").arg(kSnapPx)
         : tr("Snapping off"));
  emit repaintNeeded();
}

void ReferenceEditTool::setDatum(int object, int corner) {
  datum_ = {object, corner};
  emit repaintNeeded();
}

void ReferenceEditTool::finishDrawing(bool closed) {
  if (pending_.empty()) return;
  if (closed && pending_.size() < 3) {
    emit message(tr("A closed object needs at least 3 corners"));
    return;
  }
  if (pending_.size() >= 2) {
    ReferenceObject object;
    object.name = model_->freeName();
    object.closed = closed;
    object.corners = pending_;
    pending_.clear();
    model_->addObject(std::move(object));
  } else {
    pending_.clear();
  }
  emit message({});
  emit repaintNeeded();
}

void ReferenceEditTool::cancelDrawing() {
  if (pending_.empty()) return;
  pending_.clear();
  emit message({});
  emit repaintNeeded();
}

CornerRef ReferenceEditTool::cornerAt(const GridView& view, const QPointF& pixel) const {
  CornerRef best;
  double bestDistance = kCornerPickPx;
  const ReferenceMap& map = model_->map();
  for (int o = 0; o < model_->objectCount(); ++o) {
    const ReferenceObject& object = map.objects[static_cast<std::size_t>(o)];
    for (std::size_t c = 0; c < object.corners.size(); ++c) {
      const double d =
          pixelDistance(view.view().toPixel(map.cornerMetres(object, c), view.size()), pixel);
      // The selected object's corners win ties: they are the ones being worked on.
      if (d < bestDistance || (d == bestDistance && o == model_->selectedObject())) {
        bestDistance = d;
        best = {o, static_cast<int>(c)};
      }
    }
  }
  return best;
}

std::optional<ReferenceEditTool::EdgeHit> ReferenceEditTool::edgeAt(const GridView& view,
                                                                    const QPointF& pixel) const {
  std::optional<EdgeHit> best;
  double bestDistance = kEdgePickPx;
  const ReferenceMap& map = model_->map();
  for (int o = 0; o < model_->objectCount(); ++o) {
    const ReferenceObject& object = map.objects[static_cast<std::size_t>(o)];
    const std::size_t n = object.corners.size();
    const std::size_t edges = object.closed ? n : (n == 0 ? 0 : n - 1);
    for (std::size_t e = 0; e < edges; ++e) {
      const Position a = map.cornerMetres(object, e);
      const Position b = map.cornerMetres(object, (e + 1) % n);
      const QPointF pa = view.view().toPixel(a, view.size());
      const QPointF pb = view.view().toPixel(b, view.size());
      const double t = projection(pa, pb, pixel);
      const double d = pixelDistance(pa + t * (pb - pa), pixel);
      if (d <= bestDistance) {
        bestDistance = d;
        best = EdgeHit{o, static_cast<int>(e), a + t * (b - a)};
      }
    }
  }
  return best;
}

Eigen::Vector2d ReferenceEditTool::placed(const GridView& view, const QPointF& pixel,
                                          CornerRef skip) const {
  const Position world = view.view().toWorld(pixel, view.size());
  if (!snapping_) return model_->worldToUnit(world);
  const ReferenceMap& map = model_->map();
  // An existing corner first: joining walls at a shared corner is what a tape survey describes.
  std::optional<Eigen::Vector2d> nearest;
  double bestDistance = kSnapPx;
  auto consider = [&](const Eigen::Vector2d& corner) {
    const double d =
        pixelDistance(view.view().toPixel(model_->unitToWorld(corner), view.size()), pixel);
    if (d <= bestDistance) {
      bestDistance = d;
      nearest = corner;
    }
  };
  for (int o = 0; o < model_->objectCount(); ++o) {
    const auto& corners = map.objects[static_cast<std::size_t>(o)].corners;
    for (std::size_t c = 0; c < corners.size(); ++c)
      if (!(o == skip.object && static_cast<int>(c) == skip.corner)) consider(corners[c]);
  }
  for (const Eigen::Vector2d& c : pending_) consider(c);
  if (nearest) return *nearest;
  // Then the cell lines: the grid's origin is a multiple of its cell size (GridSpec::covering),
  // so multiples of the cell size from the world origin are the lines the view draws.
  const double cell = view.map() ? view.map()->spec.cellSize : 0.1;
  return {snappedToCells(world.x(), cell, map.unit), snappedToCells(world.y(), cell, map.unit)};
}

void ReferenceEditTool::insertOnEdge(const GridView& view, const EdgeHit& hit) {
  Eigen::Vector2d at = model_->worldToUnit(hit.world);
  if (snapping_) at = placed(view, view.view().toPixel(hit.world, view.size()));
  model_->insertCorner(hit.object, hit.after + 1, at);
}

bool ReferenceEditTool::mousePress(GridView& view, QMouseEvent* event) {
  if (event->button() != Qt::LeftButton) return false;
  const QPointF pixel = event->position();
  pressed_ = true;
  if (drawing()) {
    // A click on the first corner closes the object, as in most drawing programs.
    if (pending_.size() >= 3 &&
        pixelDistance(view.view().toPixel(model_->unitToWorld(pending_.front()), view.size()),
                      pixel) <= kCornerPickPx) {
      finishDrawing(true);
      return true;
    }
    const Eigen::Vector2d p = placed(view, pixel);
    if (pending_.back() != p) pending_.push_back(p);
    emit repaintNeeded();
    return true;
  }
  if (const CornerRef c = cornerAt(view, pixel); c.object >= 0) {
    model_->select(c.object, c.corner);
    drag_ = c;
    dragId_ = model_->beginDrag();
    return true;
  }
  if (const auto edge = edgeAt(view, pixel)) {
    if (event->modifiers() & Qt::ControlModifier)
      insertOnEdge(view, *edge);
    else
      model_->select(edge->object);
    return true;
  }
  model_->select(-1);
  pending_ = {placed(view, pixel)};
  emit message(
      tr("Click the next corners; Enter or a double click ends the object open, C or a "
         "click on the first corner ends it closed, Esc abandons it"));
  emit repaintNeeded();
  return true;
}

bool ReferenceEditTool::mouseMove(GridView& view, QMouseEvent* event) {
  const QPointF pixel = event->position();
  if (drag_.object >= 0) {
    model_->moveCorner(drag_.object, drag_.corner, placed(view, pixel, drag_), dragId_);
    hoverPlaced_.reset();
    return true;
  }
  hover_ = cornerAt(view, pixel);
  hoverPlaced_ = placed(view, pixel);
  emit repaintNeeded();
  return pressed_;
}

bool ReferenceEditTool::mouseRelease(GridView&, QMouseEvent* event) {
  if (event->button() != Qt::LeftButton) return false;
  drag_ = {};
  pressed_ = false;
  return true;
}

bool ReferenceEditTool::mouseDoubleClick(GridView& view, QMouseEvent* event) {
  if (event->button() != Qt::LeftButton) return false;
  pressed_ = true;  // the release follows
  if (drawing()) {
    finishDrawing(false);
  } else if (cornerAt(view, event->position()).object < 0) {
    if (const auto edge = edgeAt(view, event->position())) insertOnEdge(view, *edge);
  }
  return true;
}

bool ReferenceEditTool::keyPress(GridView&, QKeyEvent* event) {
  const int selected = model_->selectedObject();
  switch (event->key()) {
    case Qt::Key_Return:
    case Qt::Key_Enter:
      if (!drawing()) return false;
      finishDrawing(false);
      return true;
    case Qt::Key_Escape:
      if (drawing()) {
        cancelDrawing();
        return true;
      }
      if (selected < 0) return false;
      model_->select(-1);
      return true;
    case Qt::Key_C:
      if (drawing()) {
        finishDrawing(true);
      } else if (const ReferenceObject* o = model_->object(selected)) {
        if (!model_->setClosed(selected, !o->closed))
          emit message(tr("A closed object needs at least 3 corners"));
      }
      return true;
    case Qt::Key_S:
      setSnapping(!snapping_);
      return true;
    case Qt::Key_Backspace:
    case Qt::Key_Delete:
      if (drawing()) {
        pending_.pop_back();
        emit repaintNeeded();
      } else if (model_->selectedCorner() >= 0) {
        model_->removeCorner(selected, model_->selectedCorner());
      } else if (selected >= 0) {
        model_->removeObject(selected);
      } else {
        return false;
      }
      return true;
    default:
      return false;
  }
}

void ReferenceEditTool::paint(QPainter& painter, const ViewTransform& view,
                              const QSize& size) const {
  painter.save();
  painter.setRenderHint(QPainter::Antialiasing, true);
  const ReferenceMap& map = model_->map();
  const auto pixelOf = [&](const Eigen::Vector2d& corner) {
    return view.toPixel(model_->unitToWorld(corner), size);
  };
  for (int o = 0; o < model_->objectCount(); ++o) {
    const ReferenceObject& object = map.objects[static_cast<std::size_t>(o)];
    const bool selected = o == model_->selectedObject();
    QPolygonF line;
    for (const Eigen::Vector2d& c : object.corners) line << pixelOf(c);
    painter.setPen(QPen(selected ? kSelectedColour : kObjectColour, selected ? 3.0 : 2.0));
    painter.setBrush(Qt::NoBrush);
    if (object.closed)
      painter.drawPolygon(line);
    else
      painter.drawPolyline(line);
    for (int c = 0; c < line.size(); ++c) {
      const bool isSelected = selected && c == model_->selectedCorner();
      painter.setPen(QPen(Qt::black, 1.0));
      painter.setBrush(isSelected ? QColor(Qt::red) : QColor(Qt::white));
      const double r = isSelected ? 4.5 : 3.5;
      painter.drawRect(QRectF(line[c] - QPointF(r, r), QSizeF(2 * r, 2 * r)));
      if (o == hover_.object && c == hover_.corner) {
        painter.setPen(QPen(QColor(255, 220, 0), 2.0));
        painter.setBrush(Qt::NoBrush);
        painter.drawEllipse(line[c], 8.0, 8.0);
      }
      if (o == datum_.object && c == datum_.corner) {
        // The datum: a ring and a cross, as a surveyor marks a reference point.
        painter.setPen(QPen(Qt::red, 1.5));
        painter.setBrush(Qt::NoBrush);
        painter.drawEllipse(line[c], 11.0, 11.0);
        painter.drawLine(line[c] - QPointF(14, 0), line[c] + QPointF(14, 0));
        painter.drawLine(line[c] - QPointF(0, 14), line[c] + QPointF(0, 14));
      }
    }
  }
  if (!pending_.empty()) {
    QPolygonF line;
    for (const Eigen::Vector2d& c : pending_) line << pixelOf(c);
    if (hoverPlaced_) line << pixelOf(*hoverPlaced_);
    painter.setPen(QPen(kPendingColour, 2.0, Qt::DashLine));
    painter.setBrush(Qt::NoBrush);
    painter.drawPolyline(line);
    painter.setPen(QPen(Qt::black, 1.0));
    painter.setBrush(kPendingColour);
    for (std::size_t c = 0; c < pending_.size(); ++c)
      painter.drawRect(QRectF(line[static_cast<int>(c)] - QPointF(3.5, 3.5), QSizeF(7, 7)));
  }
  if (snapping_ && hoverPlaced_ && drag_.object < 0) {
    const QPointF p = pixelOf(*hoverPlaced_);
    painter.setPen(QPen(kPendingColour, 1.5));
    painter.drawLine(p - QPointF(6, 6), p + QPointF(6, 6));
    painter.drawLine(p - QPointF(6, -6), p + QPointF(6, -6));
  }
  painter.restore();
}

}  // namespace sg::ui
