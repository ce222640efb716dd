// SPDX-License-Identifier: GPL-3.0-or-later
#include "dataset_manifest.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonDocument>
#include <QJsonObject>
#include <QJsonParseError>

namespace sg::app {
namespace {

[[noreturn]] void fail(const QString& file, const QString& what) {
  throw ManifestError(
      QStringLiteral("%1: %2").arg(QDir::toNativeSeparators(file), what).toStdString());
}

QString text(const QJsonObject& o, const char* field, bool required, const QString& file) {
  const QJsonValue v = o.value(QLatin1String(field));
  if (v.isUndefined() || v.isNull()) {
    if (required) fail(file, QStringLiteral("field \"%1\" is missing").arg(QLatin1String(field)));
    return {};
  }
  if (!v.isString() || v.toString().trimmed().isEmpty())
    fail(file, QStringLiteral("field \"%1\" must be a non-empty string").arg(QLatin1String(field)));
  return v.toString().trimmed();
}

// A file named by the manifest, relative to its folder; it must exist.
QString fileIn(const QDir& dir, const QString& name, const char* field, const QString& file) {
  if (name.isEmpty()) return {};
  if (QDir::isAbsolutePath(name) || name.contains(QLatin1String("..")))
    fail(file, QStringLiteral("field \"%1\": \"%2\" must name a file in the dataset's folder")
                   .arg(QLatin1String(field), name));
  const QString path = dir.filePath(name);
  if (!QFileInfo(path).isFile())
    fail(file, QStringLiteral("field \"%1\": %2 does not exist")
                   .arg(QLatin1String(field), QDir::toNativeSeparators(path)));
  return QDir::cleanPath(path);
}

}  // namespace

std::optional<DatasetManifest> readDatasetManifest(const QString& folder) {
  const QDir dir(QFileInfo(folder).absoluteFilePath());
  const QString file = dir.filePath(QLatin1String(kManifestName));
  QFile f(file);
  if (!f.exists()) return std::nullopt;
  if (!f.open(QIODevice::ReadOnly)) fail(file, f.errorString());
  QJsonParseError error{};
  const QJsonDocument doc = QJsonDocument::fromJson(f.readAll(), &error);
  if (error.error != QJsonParseError::NoError)
    fail(
        file,
        QStringLiteral("not valid JSON at byte %1: %2").arg(error.offset).arg(error.errorString()));
  if (!doc.isObject()) fail(file, QStringLiteral("the manifest must be a JSON object"));
  const QJsonObject o = doc.object();
  if (o.value(QLatin1String("format")).toString() != QLatin1String("sonargrid-dataset"))
    fail(file, QStringLiteral("field \"format\" must be \"sonargrid-dataset\""));
  if (o.value(QLatin1String("version")).toInt(-1) != 1)
    fail(file, QStringLiteral("field \"version\" must be 1"));
  DatasetManifest m;
  m.folder = dir.absolutePath();
  m.name = dir.dirName();
  m.title = text(o, "title", true, file);
  m.description = text(o, "description", true, file);
  if (m.description.contains(QLatin1Char('\n')))
    fail(file, QStringLiteral("field \"description\" must be one line"));
  m.reference = fileIn(dir, text(o, "reference", false, file), "reference", file);
  m.example = fileIn(dir, text(o, "example", true, file), "example", file);
  m.thumbnail = fileIn(dir, text(o, "thumbnail", false, file), "thumbnail", file);
  return m;
}

std::optional<DatasetManifest> manifestForLog(const QString& logPath, QString* error) {
  try {
    return readDatasetManifest(QFileInfo(logPath).absolutePath());
  } catch (const ManifestError& e) {
    if (error) *error = QString::fromUtf8(e.what());
    return std::nullopt;
  }
}

std::vector<DatasetManifest> datasetManifests(const QString& datasetsDir, QStringList* errors) {
  std::vector<DatasetManifest> out;
  const QDir dir(datasetsDir);
  for (const QString& sub : dir.entryList(QDir::Dirs | QDir::NoDotAndDotDot, QDir::Name)) {
    try {
      if (auto m = readDatasetManifest(dir.filePath(sub))) out.push_back(std::move(*m));
    } catch (const ManifestError& e) {
      if (errors) *errors << QString::fromUtf8(e.what());
    }
  }
  return out;
}

}  // namespace sg::app
