// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// How the grid view hands the cell inspector a cell: Shift+left click picks the cell under the
// pointer (plain clicks and drags still pan, and the reference editor's tool never sees a
// Shift+click, which it does not use), and the inspected cell is outlined over the view. It
// watches the view from outside (an event filter and a transparent child widget), so neither the
// view nor its GridTool hook changes; the outline is not part of the view's exports.

#include <QObject>
#include <optional>

#include "sonargrid/engine/grid_spec.h"

class QWidget;

namespace sg::ui {

class GridView;

class CellPicker : public QObject {
  Q_OBJECT

 public:
  explicit CellPicker(GridView* view);

  // The cell outlined over the view (none: no outline).
  void setMarkedCell(std::optional<GridSpec> grid, std::optional<CellIndex> cell);
  // The outline in widget pixels, when a cell is marked.
  std::optional<QRectF> markedRect() const;

 signals:
  // Shift+click at world point `world`.
  void picked(const sg::Position& world);

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  friend class CellOutline;
  GridView* view_;
  QWidget* outline_;
  std::optional<GridSpec> grid_;
  std::optional<CellIndex> cell_;
};

}  // namespace sg::ui
