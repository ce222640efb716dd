// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// File ▸ Open Example: the bundled datasets (their manifests, dataset_manifest.h) as a list with
// a thumbnail, the title and the one-line description each. Open takes the dataset's example log;
// "Other run…" picks another log of the same folder. Either loads with the dataset's reference.

#include <QDialog>
#include <QImage>
#include <vector>

#include "dataset_manifest.h"

class QListWidget;

namespace sg::app {

class ExampleChooser : public QDialog {
  Q_OBJECT

 public:
  explicit ExampleChooser(std::vector<DatasetManifest> datasets, QWidget* parent = nullptr);

  // The log to open once the dialog is accepted ("" before).
  const QString& chosenLog() const { return chosen_; }
  // The list (one row per dataset, in folder order), for tests.
  QListWidget* list() const { return list_; }
  // Selects the dataset called `name` (its folder's name) and accepts with its example log; false
  // when there is none.
  bool choose(const QString& name);

  // The dataset's thumbnail: its picture when the manifest names one, else its reference map's
  // walls and obstacles drawn to fit `size` (an empty picture when there is neither).
  static QImage thumbnail(const DatasetManifest& dataset, QSize size);

 private:
  void openOther();

  std::vector<DatasetManifest> datasets_;
  QListWidget* list_;
  QString chosen_;
};

}  // namespace sg::app
