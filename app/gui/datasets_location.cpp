// SPDX-License-Identifier: GPL-3.0-or-later
#include "datasets_location.h"

#include <QCoreApplication>
#include <QDir>
#include <QFileInfo>

namespace sg::app {

QString bundledDatasetsDirectory() {
  const QString installed = QDir(QCoreApplication::applicationDirPath())
                                .filePath(QStringLiteral(SONARGRID_INSTALLED_DATASETS));
  if (QFileInfo(installed).isDir()) return QDir::cleanPath(installed);
  const QString source = QStringLiteral(SONARGRID_SOURCE_DATASETS);
  if (QFileInfo(source).isDir()) return source;
  return {};
}

}  // namespace sg::app
