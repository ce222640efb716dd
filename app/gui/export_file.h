// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The GUI's files (view PNG and SVG, screenshots) are encoded in memory and written by the core's
// one atomic writer, sg::writeFileAtomically, as every other SonarGrid file is: a unique temporary
// file, synced, renamed over the target, the folder synced. Qt's own QImage::save and
// QSvgGenerator::setFileName would write the target in place.

#include <QByteArray>
#include <QImage>
#include <QString>

namespace sg::app {

// The image encoded as `format` (e.g. "PNG"); empty when Qt has no writer for it.
QByteArray encodedImage(const QImage& image, const char* format);

// Writes `bytes` to `path` atomically. Returns an empty string, or the error naming the path and
// the system's reason.
QString writeFileBytes(const QString& path, const QByteArray& bytes);

}  // namespace sg::app
