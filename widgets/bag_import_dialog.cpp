// SPDX-License-Identifier: GPL-3.0-or-later
#include "bag_import_dialog.h"

#include <QComboBox>
#include <QDialogButtonBox>
#include <QFileInfo>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QPushButton>
#include <QTableWidget>
#include <QVBoxLayout>
#include <cmath>

#include "sonargrid/io/bag/ros_messages.h"

namespace sg::ui {
namespace {

using bag::MessageType;

bool sonarLike(MessageType m) {
  return m == MessageType::Range || m == MessageType::PointCloud || m == MessageType::PointCloud2;
}

QString shortType(const std::string& type) {
  QString t = QString::fromStdString(type);
  return t.replace(QStringLiteral("/msg/"), QStringLiteral("/"));
}

QTableWidgetItem* cell(const QString& text, Qt::Alignment align = Qt::AlignLeft) {
  auto* item = new QTableWidgetItem(text);
  item->setFlags(Qt::ItemIsEnabled);
  item->setTextAlignment(align | Qt::AlignVCenter);
  return item;
}

void select(QComboBox* c, const QString& value) {
  const int i = c->findData(value);
  if (i >= 0) c->setCurrentIndex(i);
}

QString number(double v, int decimals) {
  return QString::number(v, 'f', decimals);
}

}  // namespace

BagImportDialog::BagImportDialog(const QString& path, bag::Overview overview,
                                 const LogOptions& initial, QWidget* parent)
    : QDialog(parent), path_(path), overview_(std::move(overview)) {
  setWindowTitle(tr("Open ROS bag — %1").arg(QFileInfo(path).fileName()));
  building_ = true;

  // Every topic: a box in the Sonar column for those that can hold sonar readings.
  topics_ = new QTableWidget(static_cast<int>(overview_.topics.size()), ColumnCount, this);
  topics_->setHorizontalHeaderLabels(
      {tr("Sonar"), tr("Topic"), tr("Type"), tr("Messages"), tr("Rate (Hz)")});
  topics_->verticalHeader()->hide();
  topics_->setSelectionMode(QAbstractItemView::NoSelection);
  topics_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  topics_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  topics_->horizontalHeader()->setSectionResizeMode(Name, QHeaderView::Stretch);
  odometry_ = new QComboBox(this);
  truth_ = new QComboBox(this);
  truth_->addItem(tr("none"), QStringLiteral("-"));
  bool tf = false;
  for (std::size_t i = 0; i < overview_.topics.size(); ++i) {
    const bag::Topic& t = overview_.topics[i];
    const int row = static_cast<int>(i);
    const QString name = QString::fromStdString(t.name);
    const MessageType m = bag::messageType(t.type);
    auto* box = cell(QString());
    if (sonarLike(m)) {
      box->setFlags(Qt::ItemIsEnabled | Qt::ItemIsUserCheckable);
      box->setCheckState(Qt::Unchecked);
    }
    topics_->setItem(row, Sonar, box);
    topics_->setItem(row, Name, cell(name));
    topics_->setItem(row, Type, cell(shortType(t.type)));
    topics_->setItem(row, Count,
                     cell(t.count ? QString::number(t.count) : tr("—"), Qt::AlignRight));
    // Messages per second over the span of their log times.
    const double span = static_cast<double>(t.lastNs - t.firstNs) * 1e-9;
    topics_->setItem(
        row, Rate,
        cell(t.count > 1 && span > 0.0 ? number(static_cast<double>(t.count - 1) / span, 1)
                                       : tr("—"),
             Qt::AlignRight));
    if (m == MessageType::Odometry) odometry_->addItem(name, name);
    if (m == MessageType::Odometry || m == MessageType::PoseStamped) truth_->addItem(name, name);
    if (m == MessageType::Tf && t.name == "/tf") tf = true;
  }
  if (tf) odometry_->addItem(tr("/tf (odom → robot transforms)"), QStringLiteral("/tf"));

  robot_ = new QComboBox(this);
  robot_->addItem(tr("from the bag (/tf_static, Range fields)"), QString());
  for (const std::string& name : SonarRing::presetNames())
    robot_->addItem(QString::fromStdString(name), QString::fromStdString(name));
  robot_->setToolTip(
      tr("Point clouds (RosAria) carry no sonar geometry: choose the robot's ring. Range topics "
         "take their sonar poses from /tf_static or /tf; the ring only where the bag has none."));

  // The picks (or the choice given), pre-selected.
  const BagTopics& picks = overview_.picks;
  const std::vector<std::string>& sonar =
      initial.topics.sonar.empty() ? picks.sonar : initial.topics.sonar;
  for (const std::string& s : sonar) setSonar(QString::fromStdString(s), true);
  setOdometry(QString::fromStdString(initial.topics.odometry.empty() ? picks.odometry
                                                                     : initial.topics.odometry));
  const std::string truth = initial.topics.truth.empty() ? picks.truth : initial.topics.truth;
  setTruth(truth == "-" ? QString() : QString::fromStdString(truth));
  if (initial.ring) setRobotPreset(QString::fromStdString(initial.ring->robot));

  QStringList notes;
  for (const std::string& n : overview_.notes) notes << QString::fromStdString(n).toHtmlEscaped();
  notes_ = new QLabel(tr("<b>Picked:</b> %1").arg(notes.join(QStringLiteral("<br>"))), this);
  notes_->setWordWrap(true);
  notes_->setTextInteractionFlags(Qt::TextSelectableByMouse);

  auto* choice = new QGroupBox(tr("Read"), this);
  auto* form = new QFormLayout(choice);
  form->addRow(tr("Odometry:"), odometry_);
  form->addRow(tr("True pose:"), truth_);
  form->addRow(tr("Sonar ring:"), robot_);

  previewTable_ = new QTableWidget(0, 7, this);
  previewTable_->setHorizontalHeaderLabels({tr("t (s)"), tr("x (m)"), tr("y (m)"), tr("θ (°)"),
                                            tr("Readings"), tr("Echoes"), tr("Nearest (m)")});
  previewTable_->verticalHeader()->hide();
  previewTable_->setSelectionMode(QAbstractItemView::NoSelection);
  previewTable_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  previewTable_->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  result_ = new QLabel(this);
  result_->setWordWrap(true);
  result_->setTextInteractionFlags(Qt::TextSelectableByMouse);

  buttons_ = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, this);
  buttons_->button(QDialogButtonBox::Ok)->setText(tr("Load"));
  connect(buttons_, &QDialogButtonBox::accepted, this, &QDialog::accept);
  connect(buttons_, &QDialogButtonBox::rejected, this, &QDialog::reject);

  auto* top = new QHBoxLayout;
  auto* left = new QVBoxLayout;
  left->addWidget(new QLabel(tr("Topics (tick the sonar ones):"), this));
  left->addWidget(topics_, 1);
  top->addLayout(left, 3);
  auto* right = new QVBoxLayout;
  right->addWidget(choice);
  right->addWidget(notes_);
  right->addStretch(1);
  top->addLayout(right, 2);

  auto* layout = new QVBoxLayout(this);
  layout->addLayout(top, 1);
  layout->addWidget(new QLabel(
      tr("Preview of the first scans (the first %1 s of the bag):").arg(kPreviewSeconds), this));
  layout->addWidget(previewTable_, 1);
  layout->addWidget(result_);
  layout->addWidget(buttons_);
  resize(960, 680);

  building_ = false;
  connect(topics_, &QTableWidget::itemChanged, this, [this] { update(); });
  connect(odometry_, &QComboBox::currentIndexChanged, this, [this] { update(); });
  connect(truth_, &QComboBox::currentIndexChanged, this, [this] { update(); });
  connect(robot_, &QComboBox::currentIndexChanged, this, [this] { update(); });
  update();
}

void BagImportDialog::setSonar(const QString& topic, bool on) {
  for (int row = 0; row < topics_->rowCount(); ++row) {
    QTableWidgetItem* box = topics_->item(row, Sonar);
    if (topics_->item(row, Name)->text() == topic && (box->flags() & Qt::ItemIsUserCheckable))
      box->setCheckState(on ? Qt::Checked : Qt::Unchecked);
  }
}

void BagImportDialog::setOdometry(const QString& topic) {
  select(odometry_, topic);
}

void BagImportDialog::setTruth(const QString& topic) {
  select(truth_, topic.isEmpty() ? QStringLiteral("-") : topic);
}

void BagImportDialog::setRobotPreset(const QString& name) {
  select(robot_, name);
}

LogOptions BagImportDialog::chosen() const {
  LogOptions o;
  o.format = LogFormat::Bag;
  for (int row = 0; row < topics_->rowCount(); ++row)
    if (topics_->item(row, Sonar)->checkState() == Qt::Checked)
      o.topics.sonar.push_back(topics_->item(row, Name)->text().toStdString());
  o.topics.odometry = odometry_->currentData().toString().toStdString();
  o.topics.truth = truth_->currentData().toString().toStdString();
  const QString preset = robot_->currentData().toString();
  SonarRing ring;
  if (!preset.isEmpty() && SonarRing::preset(preset.toStdString(), ring)) o.ring = ring;
  return o;
}

std::optional<LogOptions> BagImportDialog::options() const {
  if (!preview_) return std::nullopt;
  return chosen();
}

QString BagImportDialog::result() const {
  return result_->text();
}

void BagImportDialog::update() {
  if (building_) return;
  preview_.reset();
  error_.clear();
  const LogOptions o = chosen();
  if (o.topics.sonar.empty()) {
    error_ = tr("Tick at least one sonar topic.");
  } else if (o.topics.odometry.empty()) {
    error_ = tr("The bag has no odometry (nav_msgs/Odometry or /tf): it cannot be mapped.");
  } else {
    try {
      LoadReport report;
      preview_ = bag::previewBag(path_.toStdString(), o, kPreviewSeconds, report);
    } catch (const std::exception& e) {
      error_ = QString::fromUtf8(e.what());
      // The core speaks the CLI's flags; here the ring is chosen above.
      bool cloud = false;
      for (const bag::Topic& t : overview_.topics)
        for (const std::string& s : o.topics.sonar)
          cloud = cloud || (t.name == s && bag::messageType(t.type) != MessageType::Range);
      if (cloud && !o.ring)
        error_ = tr("Choose the robot under Sonar ring: point clouds carry no sonar geometry "
                    "(p3dx for a Pioneer 3-DX under RosAria).\n") +
                 error_;
    }
  }
  fillPreview();
  buttons_->button(QDialogButtonBox::Ok)->setEnabled(preview_.has_value());
}

void BagImportDialog::fillPreview() {
  previewTable_->setRowCount(0);
  if (!preview_) {
    result_->setText(error_);
    result_->setStyleSheet(QStringLiteral("color: #b00020"));
    return;
  }
  const Dataset& d = *preview_;
  const int rows = static_cast<int>(std::min<std::size_t>(d.scans.size(), kPreviewScans));
  previewTable_->setRowCount(rows);
  for (int i = 0; i < rows; ++i) {
    const Scan& s = d.scans[static_cast<std::size_t>(i)];
    int echoes = 0;
    double nearest = INFINITY;
    for (const Reading& r : s.readings) {
      if (!r.echo()) continue;
      ++echoes;
      nearest = std::min(nearest, r.range);
    }
    previewTable_->setItem(i, 0, cell(number(s.time, 3), Qt::AlignRight));
    previewTable_->setItem(i, 1, cell(number(s.odometry.x(), 3), Qt::AlignRight));
    previewTable_->setItem(i, 2, cell(number(s.odometry.y(), 3), Qt::AlignRight));
    previewTable_->setItem(i, 3, cell(number(radToDeg(s.odometry.heading), 1), Qt::AlignRight));
    previewTable_->setItem(i, 4, cell(QString::number(s.readings.size()), Qt::AlignRight));
    previewTable_->setItem(i, 5, cell(QString::number(echoes), Qt::AlignRight));
    previewTable_->setItem(i, 6, cell(echoes ? number(nearest, 3) : tr("—"), Qt::AlignRight));
  }
  result_->setStyleSheet(QString());
  result_->setText((d.scans.size() == 1 ? tr("1 scan") : tr("%1 scans").arg(d.scans.size())) +
                   tr(", %1 readings in the first %2 s; %3 sonars (%4)%5")
                       .arg(d.readingCount())
                       .arg(kPreviewSeconds)
                       .arg(d.ring.size())
                       .arg(QString::fromStdString(d.ring.robot))
                       .arg(d.hasTruth() ? tr(", with true poses") : QString()));
}

}  // namespace sg::ui
