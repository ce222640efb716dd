// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A tool of the grid view (as Tiled's AbstractTool): while one is set, the view hands it the mouse
// and keys first, and it draws over the overlays in both the raster and the OpenGL surface. An
// event the tool does not take keeps the view's own behaviour (pan, zoom, fit).

#include <QSize>

#include "grid_image.h"

class QKeyEvent;
class QMouseEvent;
class QPainter;

namespace sg::ui {

class GridView;

class GridTool {
 public:
  virtual ~GridTool() = default;

  // Each returns true when the tool took the event: the view then does not pan, fit or zoom.
  virtual bool mousePress(GridView& view, QMouseEvent* event) = 0;
  virtual bool mouseMove(GridView& view, QMouseEvent* event) = 0;
  virtual bool mouseRelease(GridView& view, QMouseEvent* event) = 0;
  virtual bool mouseDoubleClick(GridView& view, QMouseEvent* event) = 0;
  virtual bool keyPress(GridView& view, QKeyEvent* event) = 0;
  // Draws the tool's state (handles, hover, what is being drawn) in widget pixels.
  virtual void paint(QPainter& painter, const ViewTransform& view, const QSize& size) const = 0;
};

}  // namespace sg::ui
