// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The grid view: pan, zoom (wheel, pinch, keys), fit, a hover read-out and toggled overlays over a
// map snapshot. It draws through one of two surfaces chosen at construction: an OpenGL surface (the
// levels as an 8-bit texture recoloured by a 16-entry palette texture, RViz-style) or a raster
// surface painting renderGridImage(). Under QT_QPA_PLATFORM=offscreen Qt 6.4 gives QOpenGLWidget no
// context and showing one may crash (DESIGN.md), so Automatic picks the raster surface there.

#include <QImage>
#include <QPointF>
#include <QWidget>
#include <memory>

#include "grid_image.h"
#include "grid_tool.h"

class QPainter;

namespace sg::ui {

class GridView : public QWidget {
  Q_OBJECT

 public:
  enum class Backend { Automatic, OpenGL, Raster };

  explicit GridView(Backend backend = Backend::Automatic, QWidget* parent = nullptr);
  ~GridView() override;

  // What Automatic resolves to on the running platform: Raster under "offscreen" and "minimal".
  static Backend automaticBackend();
  Backend backend() const { return backend_; }

  // A new snapshot. The view keeps its pan and zoom while the grid's geometry stays the same, or
  // when a live map's grid grew and the user has moved the view, and fits the new grid otherwise.
  void setMap(std::shared_ptr<const OccupancyMap> map);
  std::shared_ptr<const OccupancyMap> map() const { return scene_.map; }
  void setReferenceLines(std::vector<std::vector<Position>> lines);
  // The robot, ring, beams and path at scan `scan` of `dataset` (nothing when it is null). While
  // the view follows the robot (setFollowRobot) and is not fitted to the whole map, a robot that
  // nears the view's edge (within a sixth of it) is brought back to its centre, at the same zoom.
  void setRobotAt(const Dataset* dataset, PoseSource pose, std::size_t scan);
  // Follow the robot (a live map at its live edge) until the user pans away; turning it on again
  // after it was off, or fitting the map, forgets a pan away.
  void setFollowRobot(bool on);
  bool followsRobot() const { return followRobot_ && !pannedAway_; }
  // Draws this sonar's beam of the current scan highlighted (nullopt: none).
  void setHighlightedSonar(std::optional<std::size_t> sonar);
  // The D_min tint of the map on `spec` (dmin_overlay.h), drawn while Overlay::Dmin is on and the
  // shown map is on the same grid; null: none.
  void setDminTint(std::shared_ptr<const QImage> tint, const GridSpec& spec);
  const GridScene& scene() const { return scene_; }

  void setLevelPalette(const LevelPalette& palette);
  const LevelPalette& levelPalette() const { return palette_; }
  void setOverlays(Overlays overlays);
  void setOverlay(Overlay overlay, bool on);
  Overlays overlays() const { return overlays_; }
  // Name of the rule's native value for the read-out, e.g. "log-odds".
  void setNativeName(const QString& name) { nativeName_ = name; }

  const ViewTransform& view() const { return view_; }
  void setView(const ViewTransform& view);
  // Fits the view to the focus area (where the robot went and the reference) within the grid, or
  // to the whole grid when there is none.
  void fitToMap();
  // The area the fitted view shows (focusArea() in grid_image.h); an empty one fits the grid.
  // Refits a view that still follows the fit.
  void setFocusArea(const FocusArea& area);
  ViewTransform fittedView() const;
  // Zooms by `factor` keeping the world point under `pixel` where it is.
  void zoomAt(double factor, const QPointF& pixel);
  void panBy(const QPointF& pixels);

  // The read-out at a widget pixel (what hovering there shows).
  CellReadout readoutAt(const QPointF& pixel) const;

  // The picture as the raster path draws it at the view's size (the PNG export).
  QImage renderImage() const;
  // The picture drawn as vectors (the SVG export).
  void paintVector(QPainter& painter) const;
  // What the surface actually shows (GL: its framebuffer).
  QImage grabSurface();

  // The tool that takes the mouse and keys first and draws over the overlays (not owned; nullptr:
  // none). It is not part of renderImage() or paintVector(): exports show the map, not the tool.
  void setTool(GridTool* tool);
  GridTool* tool() const { return tool_; }
  // Repaints the tool's drawing (the cells and overlays are not drawn again).
  void toolChanged();

  QSize sizeHint() const override { return {800, 600}; }

 signals:
  void hovered(const sg::ui::CellReadout& readout);
  void hoverText(const QString& text);
  void viewChanged();
  // After every repaint of the surface (what the latency benchmark waits for).
  void repainted();

 protected:
  void resizeEvent(QResizeEvent* event) override;
  void wheelEvent(QWheelEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;
  void mouseDoubleClickEvent(QMouseEvent* event) override;
  void keyPressEvent(QKeyEvent* event) override;
  bool event(QEvent* event) override;

 private:
  friend class GridRasterSurface;
  friend class GridGlSurface;
  void refresh(bool levelsChanged);
  void surfacePainted() { emit repainted(); }

  Backend backend_;
  QWidget* surface_ = nullptr;
  GridScene scene_;
  LevelPalette palette_;
  Overlays overlays_ = kAllOverlays;
  ViewTransform view_;
  bool followFit_ = true;  // refit on resize until the user pans or zooms
  bool followRobot_ = false;
  bool pannedAway_ = false;  // panned while following the robot: it is no longer followed
  FocusArea focus_;
  QString nativeName_;
  QPointF dragFrom_;
  bool dragging_ = false;
  GridTool* tool_ = nullptr;
};

}  // namespace sg::ui
