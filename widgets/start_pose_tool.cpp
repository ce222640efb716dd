// SPDX-License-Identifier: GPL-3.0-or-later
#include "start_pose_tool.h"

#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>
#include <QPainterPath>
#include <cmath>

#include "grid_view.h"

namespace sg::ui {

StartPoseTool::StartPoseTool(QObject* parent) : QObject(parent) {}

double StartPoseTool::headingAt(const QPointF& pixel) const {
  const QPointF d = pixel - anchorPixel_;
  if (std::hypot(d.x(), d.y()) < kDragPx) return heading_;
  return std::atan2(-d.y(), d.x());  // pixels grow downwards, y in the world upwards
}

std::optional<Pose2D> StartPoseTool::pending() const {
  if (!pressed_) return std::nullopt;
  Pose2D p;
  p.position = anchor_;
  p.heading = headingAt(currentPixel_);
  return p;
}

bool StartPoseTool::mousePress(GridView& view, QMouseEvent* event) {
  if (event->button() != Qt::LeftButton) return false;
  pressed_ = true;
  anchorPixel_ = currentPixel_ = event->position();
  anchor_ = view.view().toWorld(anchorPixel_, view.size());
  view.toolChanged();
  return true;
}

bool StartPoseTool::mouseMove(GridView& view, QMouseEvent* event) {
  if (!pressed_) return false;  // hovering reads cells out as usual
  currentPixel_ = event->position();
  view.toolChanged();
  return true;
}

bool StartPoseTool::mouseRelease(GridView& view, QMouseEvent* event) {
  if (!pressed_ || event->button() != Qt::LeftButton) return false;
  currentPixel_ = event->position();
  const Pose2D pose = *pending();
  pressed_ = false;
  view.toolChanged();
  emit picked(pose);
  return true;
}

bool StartPoseTool::mouseDoubleClick(GridView&, QMouseEvent*) {
  return true;  // not the view's fit: the first click already placed the robot
}

bool StartPoseTool::keyPress(GridView& view, QKeyEvent* event) {
  if (event->key() != Qt::Key_Escape) return false;
  pressed_ = false;
  view.toolChanged();
  emit cancelled();
  return true;
}

void StartPoseTool::paint(QPainter& painter, const ViewTransform& view, const QSize& size) const {
  const std::optional<Pose2D> p = pending();
  if (!p) return;
  // The robot as the path overlay draws it: a disc with a line to where it faces, 0.25 m radius.
  const QPointF c = view.toPixel(p->position, size);
  const double r = std::max(6.0, 0.25 * view.pixelsPerMetre);
  const QPointF tip = c + QPointF(std::cos(p->heading), -std::sin(p->heading)) * (2.0 * r);
  painter.save();
  painter.setRenderHint(QPainter::Antialiasing);
  painter.setPen(QPen(QColor(0, 140, 255), 2.0));
  painter.setBrush(QColor(0, 140, 255, 60));
  painter.drawEllipse(c, r, r);
  painter.drawLine(c, tip);
  painter.restore();
}

}  // namespace sg::ui
