// SPDX-License-Identifier: GPL-3.0-or-later
#include "export_file.h"

#include <QBuffer>
#include <QDir>
#include <string_view>

#include "sonargrid/base/atomic_file.h"

namespace sg::app {

QByteArray encodedImage(const QImage& image, const char* format) {
  QByteArray bytes;
  QBuffer buffer(&bytes);
  if (!buffer.open(QIODevice::WriteOnly) || !image.save(&buffer, format)) return {};
  return bytes;
}

QString writeFileBytes(const QString& path, const QByteArray& bytes) {
  try {
    writeFileAtomically(
        QDir::toNativeSeparators(path).toStdString(),
        std::string_view(bytes.constData(), static_cast<std::size_t>(bytes.size())));
  } catch (const std::exception& e) {
    return QString::fromStdString(e.what());
  }
  return {};
}

}  // namespace sg::app
