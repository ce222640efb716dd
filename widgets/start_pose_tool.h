// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The grid view's start-pose tool: press where the robot stood at the log's first scan, drag
// towards where it faced and release; a click without a drag keeps the heading it was given. The
// odometry is then placed there (sonargrid/io/start_pose.h), so an odometry map lands in the
// reference's frame. Esc abandons the pick.

#include <QObject>
#include <QPointF>
#include <optional>

#include "grid_tool.h"
#include "sonargrid/data/pose.h"

namespace sg::ui {

class StartPoseTool : public QObject, public GridTool {
  Q_OBJECT

 public:
  explicit StartPoseTool(QObject* parent = nullptr);

  // The heading a click without a drag keeps (radians).
  void setHeading(double radians) { heading_ = radians; }
  // The pose being dragged out, if a press started one.
  std::optional<Pose2D> pending() const;

  bool mousePress(GridView& view, QMouseEvent* event) override;
  bool mouseMove(GridView& view, QMouseEvent* event) override;
  bool mouseRelease(GridView& view, QMouseEvent* event) override;
  bool mouseDoubleClick(GridView& view, QMouseEvent* event) override;
  bool keyPress(GridView& view, QKeyEvent* event) override;
  void paint(QPainter& painter, const ViewTransform& view, const QSize& size) const override;

  // A drag shorter than this (pixels) is a click: the heading stays.
  static constexpr double kDragPx = 6.0;

 signals:
  void picked(const sg::Pose2D& pose);
  void cancelled();

 private:
  double headingAt(const QPointF& pixel) const;

  double heading_ = 0.0;
  bool pressed_ = false;
  Position anchor_{0.0, 0.0};  // world metres
  QPointF anchorPixel_;
  QPointF currentPixel_;
};

}  // namespace sg::ui
