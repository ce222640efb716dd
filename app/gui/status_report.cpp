// SPDX-License-Identifier: GPL-3.0-or-later
#include "status_report.h"

#include <QFontMetrics>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QStatusBar>
#include <algorithm>

namespace sg::app {

StatusReport::StatusReport(QStatusBar* bar)
    : QObject(bar),
      hint_(new QLabel(bar)),
      remap_(new QLabel(bar)),
      loadBar_(new QProgressBar(bar)),
      cancel_(new QPushButton(tr("Cancel"), bar)),
      emBar_(new QProgressBar(bar)),
      stopEm_(new QPushButton(tr("Stop EM"), bar)) {
  remap_->setObjectName(QStringLiteral("remapStatus"));
  // Wide enough for its longest text, so a new time does not lay the status bar out again.
  remap_->setMinimumWidth(remap_->fontMetrics().horizontalAdvance(
                              tr("preview: 99.9 cm cells, 1 scan in 64 (9999 ms)…")) +
                          8);
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
  emBar_->setObjectName(QStringLiteral("emProgress"));
  emBar_->setFixedWidth(emBar_->fontMetrics().horizontalAdvance(QLatin1Char('x')) * 32);
  emBar_->setVisible(false);
  stopEm_->setObjectName(QStringLiteral("stopEm"));
  stopEm_->setToolTip(tr("Stop the forward model's EM; the map shown stays"));
  stopEm_->setVisible(false);
  connect(stopEm_, &QPushButton::clicked, this, &StatusReport::stopEmClicked);
  bar->addPermanentWidget(emBar_);
  bar->addPermanentWidget(stopEm_);
}

void StatusReport::emProgress(int iteration, int cap, double logLikelihood) {
  emBar_->setRange(0, std::max(1, cap));
  emBar_->setValue(std::min(iteration, cap));
  emBar_->setFormat(tr("EM %v of at most %m"));
  emBar_->setToolTip(
      tr("Log-likelihood of the readings under the map so far: %1").arg(logLikelihood, 0, 'f', 1));
  emBar_->setVisible(true);
  stopEm_->setVisible(true);
  remap_->setText(tr("EM: log-likelihood %1").arg(logLikelihood, 0, 'g', 8));
}

void StatusReport::emStopped() {
  emEnded();
  remap_->setText(tr("EM stopped; the map shown stays"));
}

void StatusReport::emEnded() {
  emBar_->setVisible(false);
  stopEm_->setVisible(false);
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

void StatusReport::previewed(double cellCm, int scanStride, double ms) {
  const QString cells = tr("%1 cm cells").arg(cellCm, 0, 'g', 3);
  const QString scans = scanStride > 1 ? tr(", 1 scan in %1").arg(scanStride) : QString();
  remap_->setText(tr("preview: %1%2 (%3 ms)…").arg(cells, scans).arg(ms, 0, 'f', 0));
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
