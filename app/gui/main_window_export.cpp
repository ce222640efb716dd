// SPDX-License-Identifier: GPL-3.0-or-later
// File ▸ Export: the view as PNG or SVG, the map as PNG, the map for ROS map_server.
#include <QApplication>
#include <QBuffer>
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QPainter>
#include <QSettings>
#include <QSvgGenerator>
#include <cmath>

#include "document.h"
#include "export_file.h"
#include "main_window.h"
#include "remap_controller.h"
#include "sonargrid/export/map_export.h"

namespace sg::app {

QString MainWindow::saveFileName(const QString& title, const QString& filter,
                                 const QString& suffix) {
  QSettings s;
  const QString base = document_->dataset()
                           ? QFileInfo(document_->logPath()).completeBaseName() +
                                 QStringLiteral("-") +
                                 QString::fromStdString(document_->mapperSettings().model)
                           : QStringLiteral("sonargrid");
  const QString dir = s.value("files/exportDirectory", QDir::homePath()).toString();
  QString path =
      QFileDialog::getSaveFileName(this, title, dir + QDir::separator() + base + suffix, filter);
  if (path.isEmpty()) return path;
  if (!path.endsWith(suffix, Qt::CaseInsensitive)) path += suffix;
  s.setValue("files/exportDirectory", QFileInfo(path).absolutePath());
  return path;
}

bool MainWindow::mapComplete() {
  // A preview (coarser cells) or a run still going must not end up in a file: wait for the map of
  // the current settings.
  if (remap_->busy()) {
    QApplication::setOverrideCursor(Qt::WaitCursor);
    waitForMap(10 * 60 * 1000);
    QApplication::restoreOverrideCursor();
  }
  if (view_->map() && view_->map() == remap_->lastMap()) return true;
  reportError(tr("Export"),
              tr("The map of the current settings is not complete (only its preview is shown, or "
                 "mapping failed). Export again once the status bar says \"re-mapped\"."),
              false);
  return false;
}

void MainWindow::exportViewPng() {
  if (document_->dataset() && !mapComplete()) return;
  const QString path = saveFileName(tr("Export View as PNG"), tr("PNG images (*.png)"), ".png");
  if (path.isEmpty()) return;
  const QByteArray png = app::encodedImage(view_->renderImage(), "PNG");
  const QString error = png.isEmpty() ? path + tr(": the image cannot be encoded as PNG")
                                      : app::writeFileBytes(path, png);
  if (!error.isEmpty()) reportError(tr("Export failed"), error, false);
}

void MainWindow::exportViewSvg() {
  if (document_->dataset() && !mapComplete()) return;
  const QString path = saveFileName(tr("Export View as SVG"), tr("SVG drawings (*.svg)"), ".svg");
  if (path.isEmpty()) return;
  QByteArray bytes;
  QBuffer buffer(&bytes);
  buffer.open(QIODevice::WriteOnly);
  QSvgGenerator svg;
  svg.setOutputDevice(&buffer);
  svg.setSize(view_->size());
  svg.setViewBox(QRect(QPoint(0, 0), view_->size()));
  svg.setTitle(windowTitle());
  svg.setDescription(tr("Occupancy grid exported by SonarGrid"));
  QPainter painter;
  if (!painter.begin(&svg)) {
    reportError(tr("Export failed"), path + tr(": the drawing cannot be made"), false);
    return;
  }
  view_->paintVector(painter);
  painter.end();
  if (const QString error = app::writeFileBytes(path, bytes); !error.isEmpty())
    reportError(tr("Export failed"), error, false);
}

void MainWindow::exportMapPng() {
  if (!view_->map() || !mapComplete()) return;
  const QString path = saveFileName(tr("Export Map as PNG"), tr("PNG images (*.png)"), ".png");
  if (!path.isEmpty()) exportMapPngTo(path);
}

bool MainWindow::exportMapPngTo(const QString& path) {
  if (!view_->map() || !mapComplete()) return false;
  try {
    PngOptions o;
    o.legend = true;
    o.unknown = kUnknownColour;  // never-observed cells as the view draws them
    o.scale = std::max(1, static_cast<int>(std::lround(0.2 / remap_->lastMap()->spec.cellSize)));
    writeMapPng(*remap_->lastMap(), QDir::toNativeSeparators(path).toStdString(), o);
    return true;
  } catch (const std::exception& e) {
    return reportError(tr("Export failed"), QString::fromStdString(e.what()), false);
  }
}

void MainWindow::exportRosMap() {
  if (!view_->map() || !mapComplete()) return;
  QString path =
      saveFileName(tr("Export Map for ROS map_server"), tr("map_server YAML (*.yaml)"), ".yaml");
  if (path.isEmpty()) return;
  path.chop(5);  // writeRosMap adds .yaml and .pgm
  try {
    writeRosMap(*view_->map(), QDir::toNativeSeparators(path).toStdString());
  } catch (const std::exception& e) {
    reportError(tr("Export failed"), QString::fromStdString(e.what()), false);
  }
}

}  // namespace sg::app
