// SPDX-License-Identifier: GPL-3.0-or-later
#include "cell_inspector_picker.h"

#include <QMouseEvent>
#include <QPainter>
#include <QWidget>
#include <algorithm>

#include "grid_view.h"

namespace sg::ui {

// Draws the inspected cell's outline over the view; the mouse goes through it to the view.
class CellOutline : public QWidget {
 public:
  CellOutline(CellPicker* picker, QWidget* parent) : QWidget(parent), picker_(picker) {
    setAttribute(Qt::WA_TransparentForMouseEvents);
    setAttribute(Qt::WA_NoSystemBackground);
    setAttribute(Qt::WA_TranslucentBackground);
    setFocusPolicy(Qt::NoFocus);
  }

 protected:
  void paintEvent(QPaintEvent*) override {
    const auto r = picker_->markedRect();
    if (!r) return;
    QPainter p(this);
    p.setRenderHint(QPainter::Antialiasing);
    // At least a few pixels across, whatever the zoom, in a colour that no level uses.
    const QPointF c = r->center();
    const double half = std::max(r->width() / 2.0, 4.0);
    const QRectF box(c.x() - half, c.y() - half, 2 * half, 2 * half);
    p.setPen(QPen(QColor(255, 255, 255, 220), 3.0));
    p.drawRect(box);
    p.setPen(QPen(QColor(0, 170, 255), 1.5));
    p.drawRect(box);
  }

 private:
  CellPicker* picker_;
};

CellPicker::CellPicker(GridView* view) : QObject(view), view_(view) {
  outline_ = new CellOutline(this, view);
  outline_->setGeometry(view->rect());
  outline_->hide();
  view->installEventFilter(this);
  connect(view, &GridView::viewChanged, outline_, qOverload<>(&QWidget::update));
}

void CellPicker::setMarkedCell(std::optional<GridSpec> grid, std::optional<CellIndex> cell) {
  grid_ = std::move(grid);
  cell_ = cell;
  outline_->setVisible(grid_ && cell_);
  outline_->raise();
  outline_->update();
}

std::optional<QRectF> CellPicker::markedRect() const {
  if (!grid_ || !cell_) return std::nullopt;
  const ViewTransform& t = view_->view();
  const QSize size = view_->size();
  const Position lo(grid_->origin.x() + cell_->x() * grid_->cellSize,
                    grid_->origin.y() + cell_->y() * grid_->cellSize);
  const Position hi(lo.x() + grid_->cellSize, lo.y() + grid_->cellSize);
  return QRectF(t.toPixel(lo, size), t.toPixel(hi, size)).normalized();
}

bool CellPicker::eventFilter(QObject* watched, QEvent* event) {
  if (watched == view_) {
    if (event->type() == QEvent::Resize) {
      outline_->setGeometry(view_->rect());
    } else if (event->type() == QEvent::MouseButtonPress) {
      auto* e = static_cast<QMouseEvent*>(event);
      if (e->button() == Qt::LeftButton && e->modifiers() == Qt::ShiftModifier) {
        emit picked(view_->view().toWorld(e->position(), view_->size()));
        return true;
      }
    }
  }
  return QObject::eventFilter(watched, event);
}

}  // namespace sg::ui
