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

#include "sonargrid/params/presets.h"

namespace sg::ui {

namespace {
constexpr double kMinRange = 0.05;   // m: the shortest reading the view offers
constexpr double kRangeStep = 0.01;  // m per slider position
}  // namespace

// Paints the cached picture; re-renders only when the scenes or the size changed.
class BeamModelView::Canvas : public QWidget {
 public:
  explicit Canvas(BeamModelView* view) : QWidget(view), view_(view) {
    // Narrow and low enough that the grid keeps 60 % of a 1280 × 800 window, with the beam
    // view stacked above the parameter panel.
    setMinimumSize(230, 180);
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
  rebuildCompareChooser();
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
  connect(compare_, &QComboBox::activated, this,
          [this](int index) { compareWith(compare_->itemData(index).toString()); });
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
  comparisonKey_.clear();
  // The chooser names the entry these settings are, if any (else the model at its defaults).
  int index = 0;
  if (settings) {
    for (int i = 1; i < compare_->count() && index == 0; ++i) {
      const QString key = compare_->itemData(i).toString();
      if (key == QLatin1String("current")) continue;
      const std::optional<MapperSettings> s = settingsFor(key);
      if (s && s->model == settings->model && s->parameters == settings->parameters) index = i;
    }
    if (index == 0)
      index = std::max(0, compare_->findData(QStringLiteral("model:") +
                                             QString::fromStdString(settings->model)));
  }
  const QSignalBlocker block(compare_);
  compare_->setCurrentIndex(index);
  invalidate();
}

void BeamModelView::setPinnedConfigurations(std::vector<NamedSettings> pinned) {
  pinned_ = std::move(pinned);
  rebuildCompareChooser();
  // A comparison with a pinned row follows the rows (an unpinned one ends it).
  if (comparisonKey_.startsWith(QLatin1String("pinned:"))) {
    comparison_ = settingsFor(comparisonKey_);
    if (!comparison_) comparisonKey_.clear();
    invalidate();
  }
}

void BeamModelView::rebuildCompareChooser() {
  const QSignalBlocker block(compare_);
  const QString current = compare_->currentData().toString();
  compare_->clear();
  compare_->addItem(tr("nothing (one model)"), QString());
  for (const std::string& name : sensorModelNames()) {
    compare_->addItem(QString::fromStdString(sensorModelInfo(name).title),
                      QStringLiteral("model:") + QString::fromStdString(name));
    compare_->setItemData(compare_->count() - 1, tr("This model at its default parameters"),
                          Qt::ToolTipRole);
  }
  compare_->insertSeparator(compare_->count());
  compare_->addItem(tr("These settings, frozen"), QStringLiteral("current"));
  compare_->setItemData(compare_->count() - 1,
                        tr("Keeps the settings shown now beside the ones you change next "
                           "(move a slider to see both)"),
                        Qt::ToolTipRole);
  compare_->insertSeparator(compare_->count());
  for (const Preset& p : paperPresets())
    compare_->addItem(tr("Preset: %1").arg(QString::fromStdString(p.title)),
                      QStringLiteral("preset:") + QString::fromStdString(p.name));
  if (!pinned_.empty()) compare_->insertSeparator(compare_->count());
  for (std::size_t i = 0; i < pinned_.size(); ++i)
    compare_->addItem(tr("Pinned: %1").arg(pinned_[i].label), QStringLiteral("pinned:%1").arg(i));
  const int keep = compare_->findData(comparisonKey_.isEmpty() ? current : comparisonKey_);
  compare_->setCurrentIndex(std::max(0, keep));
}

std::optional<MapperSettings> BeamModelView::settingsFor(const QString& key) const {
  if (key.startsWith(QLatin1String("model:"))) {
    // The picture depends on the model alone; its paper's rule (or any that fits) will do.
    MapperSettings other;
    other.model = key.mid(6).toStdString();
    try {
      other.rule = sensorModelInfo(other.model).preferredRule;
    } catch (const std::exception&) {
      return std::nullopt;
    }
    if (other.rule.empty() || !compatibility(other.model, other.rule).allowed)
      for (const std::string& rule : updateRuleNames())
        if (compatibility(other.model, rule).allowed) {
          other.rule = rule;
          break;
        }
    other.parameters = defaultParameters(other.model, other.rule);
    return other;
  }
  if (key.startsWith(QLatin1String("preset:"))) {
    const Preset* p = findPreset(key.mid(7).toStdString());
    if (!p) return std::nullopt;
    return applyPreset(*p);
  }
  if (key.startsWith(QLatin1String("pinned:"))) {
    bool ok = false;
    const std::size_t i = key.mid(7).toULongLong(&ok);
    if (!ok || i >= pinned_.size()) return std::nullopt;
    return pinned_[i].settings;
  }
  if (key == QLatin1String("current")) return settings_;
  return std::nullopt;
}

bool BeamModelView::compareWith(const QString& key) {
  const int index = compare_->findData(key);
  if (index < 0) return false;
  {
    const QSignalBlocker block(compare_);
    compare_->setCurrentIndex(index);
  }
  if (key.isEmpty()) {
    comparison_.reset();
    comparisonKey_.clear();
  } else {
    comparison_ = settingsFor(key);
    comparisonKey_ = key == QLatin1String("current") ? QString() : key;
  }
  invalidate();
  return true;
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
