// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The grid view's reference-editing tool (as Tiled's CreatePolygonObjectTool and EditPolygonTool in
// one): click corners to draw an object, Enter or a double click finishes it open, C (or a click on
// its first corner) finishes it closed, Esc abandons it; drag a corner to move it, Ctrl+click or
// double-click an edge to insert a corner there, Del deletes the selected corner (or the selected
// object), C opens or closes the selected object, S toggles snapping (to an existing corner within
// a few pixels, else to the grid's cell lines). Every change goes through the ReferenceEditModel,
// so each is one undo step and a drag is one step.

#include <QObject>
#include <optional>
#include <vector>

#include "grid_tool.h"
#include "reference_edit_model.h"

namespace sg::ui {

// A corner of an object by index (object -1: none).
struct CornerRef {
  int object = -1;
  int corner = -1;
};

class ReferenceEditTool : public QObject, public GridTool {
  Q_OBJECT

 public:
  explicit ReferenceEditTool(ReferenceEditModel* model, QObject* parent = nullptr);

  bool snapping() const { return snapping_; }
  void setSnapping(bool on);
  bool drawing() const { return !pending_.empty(); }
  // The corners of the object being drawn (map unit).
  const std::vector<Eigen::Vector2d>& pendingCorners() const { return pending_; }
  // Ends the object being drawn: added when it has enough corners (2, or 3 closed).
  void finishDrawing(bool closed);
  void cancelDrawing();
  // The datum corner the dock measures from, drawn marked (object -1: none).
  void setDatum(int object, int corner);

  // Hand-offs from the view.
  bool mousePress(GridView& view, QMouseEvent* event) override;
  bool mouseMove(GridView& view, QMouseEvent* event) override;
  bool mouseRelease(GridView& view, QMouseEvent* event) override;
  bool mouseDoubleClick(GridView& view, QMouseEvent* event) override;
  bool keyPress(GridView& view, QKeyEvent* event) override;
  void paint(QPainter& painter, const ViewTransform& view, const QSize& size) const override;

  // Pixels within which a click picks a corner, an edge, and snaps to a corner.
  static constexpr double kCornerPickPx = 7.0;
  static constexpr double kEdgePickPx = 5.0;
  static constexpr double kSnapPx = 8.0;

 signals:
  void snappingChanged(bool on);
  // Something the tool draws changed (the view repaints it).
  void repaintNeeded();
  // A hint for the status bar.
  void message(const QString& text);

 private:
  struct EdgeHit {
    int object = -1;
    int after = -1;  // the new corner goes at index after + 1
    Position world;  // the nearest point of the edge
  };
  CornerRef cornerAt(const GridView& view, const QPointF& pixel) const;
  std::optional<EdgeHit> edgeAt(const GridView& view, const QPointF& pixel) const;
  // Where a pointer at `pixel` puts a corner (map unit), snapped when snapping is on; `skip` is
  // the corner being dragged, which never snaps to itself.
  Eigen::Vector2d placed(const GridView& view, const QPointF& pixel, CornerRef skip = {}) const;
  void insertOnEdge(const GridView& view, const EdgeHit& hit);

  ReferenceEditModel* model_;
  bool snapping_ = false;
  std::vector<Eigen::Vector2d> pending_;
  std::optional<Eigen::Vector2d> hoverPlaced_;  // where a click would put a corner now
  CornerRef hover_;
  CornerRef drag_;
  CornerRef datum_;
  int dragId_ = 0;
  bool pressed_ = false;
};

}  // namespace sg::ui
