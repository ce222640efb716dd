// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A bundled dataset's manifest, `dataset.json` in its folder (docs/formats.md, "Dataset
// manifest"): a title, a one-line description, the reference map of every log in the folder, the
// log File ▸ Open Example opens, and an optional thumbnail. Opening any log of the folder loads its
// reference; the Open Example chooser lists the folders that have one.

#include <QString>
#include <QStringList>
#include <optional>
#include <stdexcept>
#include <vector>

namespace sg::app {

inline constexpr const char* kManifestName = "dataset.json";

struct DatasetManifest {
  QString folder;       // absolute path of the dataset's folder
  QString name;         // the folder's name, e.g. "raschke-multi"
  QString title;        // e.g. "Raschke & Borenstein 1990: multiple obstacles"
  QString description;  // one line
  QString reference;    // absolute path of the reference map, or "" (none declared)
  QString example;      // absolute path of the log Open Example opens
  QString thumbnail;    // absolute path of a picture, or "" (the chooser draws the reference)
};

// A manifest that cannot be used: the message names the file and the field.
class ManifestError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Reads `folder`/dataset.json: nullopt when the folder has none; throws ManifestError when it is
// not valid JSON, lacks a required field ("title", "description", "example") or names a file that
// does not exist.
std::optional<DatasetManifest> readDatasetManifest(const QString& folder);

// The manifest of the folder that holds `logPath`, when it has one (a broken manifest: nullopt,
// with the reason in `error`).
std::optional<DatasetManifest> manifestForLog(const QString& logPath, QString* error = nullptr);

// Every folder of `datasetsDir` with a manifest, sorted by folder name; broken ones are skipped and
// named in `errors`.
std::vector<DatasetManifest> datasetManifests(const QString& datasetsDir,
                                              QStringList* errors = nullptr);

}  // namespace sg::app
