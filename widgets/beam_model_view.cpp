// SPDX-License-Identifier: GPL-3.0-or-later
#include "beam_model_view.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QGridLayout>
#include <QLabel>
#include <QPainter>
#include <QSignalBlocker>
#include <QSlider>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>

namespace sg::ui {

namespace {
constexpr double kMinRange = 0.05;   // m: the shortest reading the view offers
constexpr double kRangeStep = 0.01;  // m per slider position
}  // namespace

// Paints the cached picture; re-renders only when the scenes or the size changed.
class BeamModelView::Canvas : public QWidget {
 public:
  explicit Canvas(BeamModelView* view) : QWidget(view), view_(view) {
    setMinimumSize(260, 280);
    setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Expanding);
  }
  void invalidate() {
    image_ = QImage();
    update();
  }

 protected:
  void paintEvent(QPaintEvent*) override {
    if (image_.size() != size()) image_ = view_->render(size());
    QPainter(this).drawImage(0, 0, image_);
  }

 private:
  BeamModelView* view_;
  QImage image_;
};

BeamModelView::BeamModelView(QWidget* parent) : QWidget(parent) {
  settings_.parameters = defaultParameters(settings_.model, settings_.rule);

  rangeSlider_ = new QSlider(Qt::Horizontal, this);
  rangeSlider_->setObjectName(QStringLiteral("rangeSlider"));
  rangeSlider_->setFocusPolicy(Qt::StrongFocus);
  rangeSlider_->setAccessibleName(tr("Reading s"));
  rangeSpin_ = new QDoubleSpinBox(this);
  rangeSpin_->setObjectName(QStringLiteral("rangeSpin"));
  rangeSpin_->setDecimals(2);
  rangeSpin_->setSingleStep(0.05);
  rangeSpin_->setSuffix(QStringLiteral(" m"));
  rangeSpin_->setKeyboardTracking(false);
  rangeSpin_->setAccessibleName(tr("Reading s"));
  auto* rangeLabel = new QLabel(tr("Reading &s:"), this);
  rangeLabel->setBuddy(rangeSpin_);
  rangeLabel->setToolTip(tr("The sonar reading whose beam model is drawn"));

  compare_ = new QComboBox(this);
  compare_->setObjectName(QStringLiteral("compareChooser"));
  compare_->addItem(tr("nothing (one model)"), QString());
  for (const std::string& name : sensorModelNames()) {
    compare_->addItem(QString::fromStdString(sensorModelInfo(name).title),
                      QString::fromStdString(name));
  }
  compare_->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
  compare_->setMinimumContentsLength(12);
  auto* compareLabel = new QLabel(tr("&Compare with:"), this);
  compareLabel->setBuddy(compare_);

  // Two rows, so that the slider keeps its length in a narrow dock.
  auto* controls = new QGridLayout;
  controls->setContentsMargins(0, 0, 0, 0);
  controls->addWidget(rangeLabel, 0, 0);
  controls->addWidget(rangeSlider_, 0, 1);
  controls->addWidget(rangeSpin_, 0, 2);
  controls->addWidget(compareLabel, 1, 0);
  controls->addWidget(compare_, 1, 1, 1, 2);
  controls->setColumnStretch(1, 1);

  canvas_ = new Canvas(this);
  auto* layout = new QVBoxLayout(this);
  layout->addLayout(controls);
  layout->addWidget(canvas_, 1);

  connect(rangeSlider_, &QSlider::valueChanged, this, [this](int position) {
    setRange(kMinRange + position * kRangeStep);
    emit rangeChanged(range_);
  });
  connect(rangeSpin_, &QDoubleSpinBox::valueChanged, this, [this](double s) {
    setRange(s);
    emit rangeChanged(range_);
  });
  connect(compare_, &QComboBox::activated, this, [this](int index) {
    const std::string model = compare_->itemData(index).toString().toStdString();
    if (model.empty()) {
      setComparisonSettings(std::nullopt);
      return;
    }
    // The picture depends on the model alone; any rule that fits it will do.
    MapperSettings other;
    other.model = model;
    for (const std::string& rule : updateRuleNames()) {
      if (compatibility(model, rule).allowed) {
        other.rule = rule;
        break;
      }
    }
    other.parameters = defaultParameters(other.model, other.rule);
    setComparisonSettings(other);
  });
  setMaxRange(maxRange_);
}

void BeamModelView::setSettings(const MapperSettings& settings) {
  settings_ = settings;
  invalidate();
}

void BeamModelView::setRange(double s) {
  s = std::clamp(s, kMinRange, maxRange_);
  if (s == range_) return;
  range_ = s;
  showRange();
  invalidate();
}

void BeamModelView::setMaxRange(double metres) {
  maxRange_ = std::max(metres, 2.0 * kMinRange);
  range_ = std::clamp(range_, kMinRange, maxRange_);
  {
    const QSignalBlocker a(rangeSlider_), b(rangeSpin_);
    rangeSlider_->setRange(0, static_cast<int>(std::lround((maxRange_ - kMinRange) / kRangeStep)));
    rangeSpin_->setRange(kMinRange, maxRange_);
  }
  showRange();
  invalidate();
}

void BeamModelView::setComparisonSettings(const std::optional<MapperSettings>& settings) {
  comparison_ = settings;
  const QSignalBlocker block(compare_);
  compare_->setCurrentIndex(
      settings ? std::max(0, compare_->findData(QString::fromStdString(settings->model))) : 0);
  invalidate();
}

std::vector<BeamScene> BeamModelView::scenes() const {
  std::vector<BeamScene> out{{settings_, range_, maxRange_}};
  if (comparison_) out.push_back({*comparison_, range_, maxRange_});
  return out;
}

void BeamModelView::showRange() {
  const QSignalBlocker a(rangeSlider_), b(rangeSpin_);
  rangeSlider_->setValue(static_cast<int>(std::lround((range_ - kMinRange) / kRangeStep)));
  rangeSpin_->setValue(range_);
}

void BeamModelView::invalidate() {
  canvas_->invalidate();
}

}  // namespace sg::ui
