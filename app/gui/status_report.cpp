// SPDX-License-Identifier: GPL-3.0-or-later
#include "status_report.h"

#include <QFontMetrics>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QStatusBar>

namespace sg::app {

StatusReport::StatusReport(QStatusBar* bar)
    : QObject(bar),
      hint_(new QLabel(bar)),
      remap_(new QLabel(bar)),
      loadBar_(new QProgressBar(bar)),
      cancel_(new QPushButton(tr("Cancel"), bar)) {
  remap_->setObjectName(QStringLiteral("remapStatus"));
  // Wide enough for its longest text, so a new time does not lay the status bar out again.
  remap_->setMinimumWidth(
      remap_->fontMetrics().horizontalAdvance(tr("preview at 99.9 cm (9999 ms)…")) + 8);
  bar->addWidget(hint_, 1);
  bar->addPermanentWidget(remap_);
  loadBar_->setRange(0, 100);
  loadBar_->setFixedWidth(loadBar_->fontMetrics().horizontalAdvance(QLatin1Char('x')) * 40);
  loadBar_->setVisible(false);
  cancel_->setObjectName(QStringLiteral("cancelLoading"));
  cancel_->setToolTip(tr("Stop loading (Esc); the open log stays"));
  cancel_->setVisible(false);
  connect(cancel_, &QPushButton::clicked, this, &StatusReport::cancelLoadClicked);
  bar->addPermanentWidget(loadBar_);
  bar->addPermanentWidget(cancel_);
}

void StatusReport::setHint(const QString& text) {
  hint_->setText(text);
}

void StatusReport::mapping() {
  remap_->setText(tr("mapping…"));
}

void StatusReport::mapped(double ms) {
  lastMapMs_ = ms;
  remap_->setText(tr("re-mapped in %1 ms").arg(ms, 0, 'f', 1));
}

void StatusReport::previewed(double cellCm, double ms) {
  remap_->setText(tr("preview at %1 cm (%2 ms)…").arg(cellCm, 0, 'g', 3).arg(ms, 0, 'f', 0));
}

void StatusReport::mappingFailed() {
  remap_->setText(tr("mapping failed"));
}

void StatusReport::loadStarted(const QString& fileName) {
  loadBar_->setValue(0);
  const QString name =
      loadBar_->fontMetrics().elidedText(fileName, Qt::ElideMiddle, loadBar_->width() / 2);
  loadBar_->setFormat(tr("Loading %1: %p%").arg(name));
  loadBar_->setVisible(true);
  cancel_->setVisible(true);
}

void StatusReport::loadProgress(int percent) {
  loadBar_->setValue(percent);
}

void StatusReport::loadEnded() {
  loadBar_->setVisible(false);
  cancel_->setVisible(false);
}

}  // namespace sg::app
