// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The dialog that opens a ROS bag (docs/user-guide.md, "Opening ROS bags"; docs/formats.md, "ROS
// bags"): every topic of the bag with its type, message count and rate; the sonar topics, the
// odometry and the true pose that auto-detection picked, pre-selected and open to change; the
// ring for point clouds that carry no sonar geometry; and a preview of the first scans that the
// choice gives, read by the core (sg::bag::previewBag) from the bag's first seconds only.

#include <QDialog>
#include <optional>

#include "sonargrid/io/bag/bag_log.h"
#include "sonargrid/io/log_options.h"

class QComboBox;
class QDialogButtonBox;
class QLabel;
class QTableWidget;

namespace sg::ui {

class BagImportDialog : public QDialog {
  Q_OBJECT

 public:
  // `overview`: the bag's topics and picks (sg::bag::inspectBag of `path`). `initial`: topics and
  // ring chosen before (a project's); empty fields take the picks.
  BagImportDialog(const QString& path, sg::bag::Overview overview,
                  const sg::LogOptions& initial = {}, QWidget* parent = nullptr);

  static constexpr double kPreviewSeconds = 10.0;
  static constexpr int kPreviewScans = 20;

  // Topic table columns.
  enum Column { Sonar, Name, Type, Count, Rate, ColumnCount };

  // Ticks or clears a topic in the Sonar column (only topics that can hold sonar have a box).
  void setSonar(const QString& topic, bool on);
  // "/tf" for tf's odom -> robot transforms.
  void setOdometry(const QString& topic);
  // Empty for none.
  void setTruth(const QString& topic);
  // A ring preset name (p3dx, amigobot, k2a), or empty for the bag's own geometry.
  void setRobotPreset(const QString& name);

  // The options the bag loads with (format, topics, ring); empty while the preview fails.
  std::optional<sg::LogOptions> options() const;
  // "N scans, M readings in the first 10 s ..." or the core's error.
  QString result() const;
  bool previewParses() const { return preview_.has_value(); }
  QTableWidget* topicTable() const { return topics_; }
  QTableWidget* previewTable() const { return previewTable_; }

 private:
  sg::LogOptions chosen() const;
  void update();
  void fillPreview();

  QString path_;
  sg::bag::Overview overview_;
  bool building_ = false;
  std::optional<sg::Dataset> preview_;
  QString error_;

  QTableWidget* topics_;
  QComboBox* odometry_;
  QComboBox* truth_;
  QComboBox* robot_;
  QLabel* notes_;
  QTableWidget* previewTable_;
  QLabel* result_;
  QDialogButtonBox* buttons_;
};

}  // namespace sg::ui
