// SPDX-License-Identifier: GPL-3.0-or-later
#include "map_dock.h"

#include <QApplication>
#include <QDoubleSpinBox>
#include <QEvent>
#include <QHBoxLayout>
#include <QLabel>
#include <QTimer>
#include <QVBoxLayout>

#include "project.h"

namespace sg::app {

MapDock::MapDock(double cellSize, QWidget* parent)
    : QWidget(parent),
      cell_(new QDoubleSpinBox(this)),
      summary_(new QLabel(this)),
      timer_(new QTimer(this)) {
  summary_->setTextFormat(Qt::RichText);
  summary_->setAlignment(Qt::AlignTop | Qt::AlignLeft);
  summary_->setMargin(8);
  summary_->setMinimumWidth(220);
  summary_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  cell_->setObjectName(QStringLiteral("cellSize"));
  cell_->setRange(kMinCellSize, kMaxCellSize);
  cell_->setDecimals(3);
  cell_->setSingleStep(0.005);
  cell_->setSuffix(tr(" m"));
  cell_->setValue(cellSize);
  cell_->setKeyboardTracking(false);  // a typed value is one edit, on Enter or leaving the box
  cell_->setToolTip(tr("Side of a grid cell in metres (View ▸ Cell Size…); undoable"));
  cell_->installEventFilter(this);
  connect(cell_, &QDoubleSpinBox::valueChanged, this, [this](double metres) {
    // Held arrow buttons repeat: one edit until the button is released (eventFilter).
    emit cellSizeEdited(metres, QApplication::mouseButtons() != Qt::NoButton);
  });
  auto* label = new QLabel(tr("&Cell size:"), this);
  label->setBuddy(cell_);
  auto* row = new QHBoxLayout;
  row->setContentsMargins(8, 8, 8, 0);
  row->addWidget(label);
  row->addWidget(cell_);
  row->addStretch(1);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addLayout(row);
  layout->addWidget(summary_, 1);

  timer_->setSingleShot(true);
  timer_->setInterval(kSummaryIntervalMs);
  connect(timer_, &QTimer::timeout, this, &MapDock::summaryDue);
}

void MapDock::setCellSize(double metres) {
  if (cell_->value() == metres) return;
  const QSignalBlocker block(cell_);
  cell_->setValue(metres);
}

void MapDock::scheduleSummary() {
  if (!timer_->isActive()) timer_->start();
}

void MapDock::setSummary(const QString& html) {
  summary_->setText(html);
}

bool MapDock::eventFilter(QObject* watched, QEvent* event) {
  if (watched == cell_ && event->type() == QEvent::MouseButtonRelease) emit cellSizeReleased();
  return QWidget::eventFilter(watched, event);
}

}  // namespace sg::app
