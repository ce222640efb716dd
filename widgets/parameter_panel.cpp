// SPDX-License-Identifier: GPL-3.0-or-later
#include "parameter_panel.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QRegularExpression>
#include <QScrollArea>
#include <QScrollBar>
#include <QSignalBlocker>
#include <QSlider>
#include <QStandardItemModel>
#include <QVBoxLayout>
#include <QValidator>
#include <algorithm>
#include <cmath>
#include <functional>
#include <initializer_list>

#include "sonargrid/forward/catalog.h"
#include "sonargrid/params/presets.h"

namespace sg::ui {

namespace {

QString qs(const std::string& s) {
  return QString::fromStdString(s);
}

// The smallest 1, 2 or 5 × 10^k that is at least `raw`.
double niceStep(double raw) {
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double m : {1.0, 2.0, 5.0}) {
    if (m * decade >= raw * (1.0 - 1e-9)) return m * decade;
  }
  return 10.0 * decade;
}

// Decimals that print `x` exactly (up to 6).
int decimalsOf(double x) {
  for (int d = 0; d < 6; ++d) {
    const double scale = std::pow(10.0, d);
    if (std::abs(std::round(x * scale) / scale - x) < 1e-9) return d;
  }
  return 6;
}

QString unitSuffix(const std::string& unit) {
  if (unit.empty()) return {};
  if (unit == "deg") return QStringLiteral("°");
  return QStringLiteral(" ") + qs(unit);
}

// The row's label: the symbol and unit ("k [1/m]"), short so that the slider keeps its width; the
// long name is in the tooltip and the accessible name.
QString labelText(const ParameterSpec& spec) {
  QString text = (spec.symbol.empty() || spec.symbol == "—") ? qs(spec.name) : qs(spec.symbol);
  if (!spec.unit.empty()) text += QStringLiteral(" [%1]").arg(qs(spec.unit));
  return text;
}

// The symbol with the long name: "k (attenuation_slope) [1/m]".
QString fullName(const ParameterSpec& spec) {
  QString text = (spec.symbol.empty() || spec.symbol == "—" || spec.symbol == spec.name)
                     ? qs(spec.name)
                     : QStringLiteral("%1  (%2)").arg(qs(spec.symbol), qs(spec.name));
  if (!spec.unit.empty()) text += QStringLiteral(" [%1]").arg(qs(spec.unit));
  return text;
}

// A spin box that says why a typed number is refused ("1e9" for a value of 1 … 15) instead of
// silently keeping part of it.
class ParameterSpinBox : public QDoubleSpinBox {
 public:
  using QDoubleSpinBox::QDoubleSpinBox;
  std::function<void(const QString&)> outOfRange;

  QValidator::State validate(QString& text, int& pos) const override {
    const QValidator::State state = QDoubleSpinBox::validate(text, pos);
    if (state == QValidator::Acceptable) return state;
    QString number = text;
    if (!suffix().isEmpty() && number.endsWith(suffix())) number.chop(suffix().size());
    number = number.trimmed();
    bool ok = false;
    double v = locale().toDouble(number, &ok);
    if (!ok) v = number.toDouble(&ok);  // "1e9" in any locale
    if (ok && std::isfinite(v) && (v < minimum() || v > maximum())) {
      if (outOfRange) outOfRange(number);
      return QValidator::Intermediate;  // kept in the box until corrected; never committed
    }
    // A number being typed in scientific notation ("1e", "1e9"): let it be finished, so that the
    // user sees what was refused rather than a box that swallowed the "e".
    static const QRegularExpression partial(
        QStringLiteral("^[+-]?[0-9]*[.,]?[0-9]*[eE][+-]?[0-9]*$"));
    if (partial.match(number).hasMatch()) return QValidator::Intermediate;
    return state;
  }
};

QString toolTipOf(const ParameterSpec& spec) {
  return QStringLiteral(
             "<p><b>%7</b></p><p>%1</p><p><b>Source:</b> %2</p><p><b>Range:</b> %3 … %4%5, "
             "default %6</p>")
      .arg(qs(spec.description).toHtmlEscaped(), qs(spec.source).toHtmlEscaped())
      .arg(spec.min)
      .arg(spec.max)
      .arg(unitSuffix(spec.unit).toHtmlEscaped())
      .arg(spec.defaultValue)
      .arg(fullName(spec).toHtmlEscaped());
}

QString presetToolTip(const Preset& p) {
  QString text = QStringLiteral("<p><b>%1</b> + <b>%2</b>: %3</p><ul>")
                     .arg(qs(p.model), qs(p.rule), qs(p.source).toHtmlEscaped());
  for (const PresetValue& v : p.values) {
    text += QStringLiteral("<li>%1 = %2 — %3</li>")
                .arg(qs(v.parameter))
                .arg(v.value)
                .arg(qs(v.citation).toHtmlEscaped());
  }
  return text + QStringLiteral("</ul>");
}

// The declared set for `model` and `rule`, taking every value of `from` that it declares and
// accepts (the rest stay at their defaults).
ParameterSet carriedOver(const std::string& model, const std::string& rule,
                         const ParameterSet& from) {
  ParameterSet p = forward::mapDefaultParameters(model, rule);
  for (const auto& [name, value] : from.values()) {
    if (!p.has(name)) continue;
    try {
      p.set(name, value);
    } catch (const ParameterError&) {
    }
  }
  return p;
}

}  // namespace

ParameterPanel::ParameterPanel(QWidget* parent) : QWidget(parent) {
  settings_.parameters = forward::mapDefaultParameters(settings_.model, settings_.rule);

  model_ = new QComboBox(this);
  model_->setObjectName(QStringLiteral("modelChooser"));
  // The inverse models, then the forward model learned by EM (forward/catalog.h).
  for (const std::string& name : forward::mapModelNames()) {
    model_->addItem(qs(forward::mapModelTitle(name)), qs(name));
    model_->setItemData(model_->count() - 1, qs(forward::mapModelSource(name)), Qt::ToolTipRole);
  }
  rule_ = new QComboBox(this);
  rule_->setObjectName(QStringLiteral("ruleChooser"));
  for (const std::string& name : forward::mapRuleNames())
    rule_->addItem(qs(forward::mapRuleTitle(name)), qs(name));
  preset_ = new QComboBox(this);
  preset_->setObjectName(QStringLiteral("presetChooser"));
  preset_->addItem(tr("Custom"), QString());
  for (const Preset& p : paperPresets()) {
    preset_->addItem(qs(p.title), qs(p.name));
    preset_->setItemData(preset_->count() - 1, presetToolTip(p), Qt::ToolTipRole);
  }

  // Long titles are elided rather than widening the dock; the tooltips give them whole.
  for (QComboBox* box : {model_, rule_, preset_}) {
    box->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
    box->setMinimumContentsLength(12);
  }
  auto* choosers = new QFormLayout;
  choosers->addRow(tr("Sensor &model:"), model_);
  choosers->addRow(tr("Update &rule:"), rule_);
  choosers->addRow(tr("Paper &preset:"), preset_);

  // The model's caveat (sensorModelCaveat()): why its maps look as they do, where that is poor.
  caveat_ = new QLabel(this);
  caveat_->setObjectName(QStringLiteral("modelCaveat"));
  caveat_->setWordWrap(true);
  caveat_->setVisible(false);
  QFont small = caveat_->font();
  small.setItalic(true);
  caveat_->setFont(small);

  status_ = new QLabel(this);
  status_->setObjectName(QStringLiteral("status"));
  status_->setWordWrap(true);
  status_->setVisible(false);

  rowsHost_ = new QWidget;
  rowsLayout_ = new QVBoxLayout(rowsHost_);
  rowsLayout_->setContentsMargins(0, 0, 0, 0);
  rowsLayout_->addStretch(1);  // the rows stay at the top; the groups go before this
  scroll_ = new QScrollArea(this);
  scroll_->setWidgetResizable(true);
  scroll_->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  scroll_->setFrameShape(QFrame::NoFrame);
  scroll_->setWidget(rowsHost_);

  reset_ = new QPushButton(tr("Reset to &defaults"), this);
  reset_->setObjectName(QStringLiteral("resetToDefaults"));
  reset_->setToolTip(tr("Every parameter of this model and rule back to its declared default"));
  remapTime_ = new QLabel(tr("Re-map: —"), this);
  remapTime_->setObjectName(QStringLiteral("remapTime"));
  remapTime_->setToolTip(tr("Wall time of the last complete re-map of the whole log"));
  auto* bottom = new QHBoxLayout;
  bottom->addWidget(reset_);
  bottom->addStretch(1);
  bottom->addWidget(remapTime_);

  auto* layout = new QVBoxLayout(this);
  layout->addLayout(choosers);
  layout->addWidget(caveat_);
  layout->addWidget(status_);
  layout->addWidget(scroll_, 1);
  layout->addLayout(bottom);

  connect(model_, &QComboBox::currentIndexChanged, this, &ParameterPanel::chooseModel);
  connect(rule_, &QComboBox::currentIndexChanged, this, &ParameterPanel::chooseRule);
  connect(preset_, &QComboBox::activated, this, [this](int index) {
    const QString name = preset_->itemData(index).toString();
    if (!name.isEmpty()) applyPreset(name);
  });
  connect(reset_, &QPushButton::clicked, this, &ParameterPanel::resetToDefaults);

  updating_ = true;
  model_->setCurrentIndex(model_->findData(qs(settings_.model)));
  rule_->setCurrentIndex(rule_->findData(qs(settings_.rule)));
  updating_ = false;
  refreshRuleAvailability();
  rebuildRows();
}

QSlider* ParameterPanel::sliderFor(const QString& name) const {
  return rowsHost_->findChild<QSlider*>(QStringLiteral("slider_") + name);
}

QDoubleSpinBox* ParameterPanel::spinBoxFor(const QString& name) const {
  return rowsHost_->findChild<QDoubleSpinBox*>(QStringLiteral("spin_") + name);
}

void ParameterPanel::setSettings(const MapperSettings& settings, bool ruleNamed) {
  MapperSettings next = settings;
  try {
    const Compatibility c = forward::mapCompatibility(settings.model, settings.rule);
    if (!c.allowed) throw MapperError(settings.model + " with " + settings.rule + ": " + c.reason);
    next.parameters = carriedOver(settings.model, settings.rule, settings.parameters);
  } catch (const std::exception& e) {
    showStatus(tr("Settings refused: %1").arg(qs(e.what())));
    return;
  }
  const bool rebuild = next.model != settings_.model || next.rule != settings_.rule;
  const bool same = !rebuild && next.parameters == settings_.parameters;
  // A new model with its paper's rule (the Mapping menu, undo, a project): say that the rule
  // changed too. Settings the panel already shows (its own change coming back) keep the note.
  // (Not the first settings the panel is given: its own defaults were never the user's; nor a
  // rule the user named.)
  const bool given = property("settingsGiven").toBool();
  const QString note =
      given && !ruleNamed && next.model != settings_.model && next.rule != settings_.rule
          ? ruleChangeNote(settings_.rule, next.model, next.rule)
          : QString();
  setProperty("settingsGiven", true);
  settings_ = next;
  updating_ = true;
  model_->setCurrentIndex(model_->findData(qs(settings_.model)));
  rule_->setCurrentIndex(rule_->findData(qs(settings_.rule)));
  // Name the preset these settings are, if any.
  int presetIndex = 0;
  for (int i = 1; i < preset_->count(); ++i) {
    const Preset* p = findPreset(preset_->itemData(i).toString().toStdString());
    const MapperSettings ps = sg::applyPreset(*p);
    if (ps.model == settings_.model && ps.rule == settings_.rule &&
        ps.parameters == settings_.parameters) {
      presetIndex = i;
      break;
    }
  }
  preset_->setCurrentIndex(presetIndex);
  updating_ = false;
  refreshRuleAvailability();
  if (rebuild)
    rebuildRows();
  else
    showValues();
  if (!same) showStatus(note);
}

QString ParameterPanel::ruleChangeNote(const std::string& fromRule, const std::string& model,
                                       const std::string& toRule) const {
  const Compatibility c = forward::mapCompatibility(model, fromRule);
  const QString why =
      !c.allowed ? qs(c.reason)
      : toRule == forward::mapModelPreferredRule(model)
          ? tr("%1 is the rule its paper pairs with %2 (%3); choose another "
               "rule below to override it")
                .arg(qs(forward::mapRuleTitle(toRule)), qs(forward::mapModelTitle(model)),
                     qs(forward::mapModelSource(model)))
          : QString();
  return tr("Rule changed from %1 to %2%3")
      .arg(qs(forward::mapRuleTitle(fromRule)), qs(forward::mapRuleTitle(toRule)),
           why.isEmpty() ? QString() : QStringLiteral(": ") + why);
}

QString ParameterPanel::statusText() const {
  return status_->isHidden() ? QString() : status_->text();
}

void ParameterPanel::showRemapTime(double milliseconds) {
  remapTime_->setText(tr("Re-map: %1 ms").arg(milliseconds, 0, 'f', milliseconds < 10.0 ? 1 : 0));
}

void ParameterPanel::resetToDefaults() {
  const ParameterSet defaults = forward::mapDefaultParameters(settings_.model, settings_.rule);
  {
    const QSignalBlocker block(preset_);
    preset_->setCurrentIndex(0);
  }
  if (defaults == settings_.parameters) return;
  settings_.parameters = defaults;
  showValues();
  showStatus({});
  changed();
}

bool ParameterPanel::applyPreset(const QString& name) {
  const Preset* preset = findPreset(name.toStdString());
  if (!preset) return false;
  MapperSettings next = sg::applyPreset(*preset);
  next.pose = settings_.pose;
  const bool same = next == settings_;
  setSettings(next, /*ruleNamed=*/true);  // a preset names its rule: no "rule changed" note
  if (!same) changed();
  return true;
}

void ParameterPanel::chooseModel(int index) {
  if (updating_ || index < 0) return;
  const std::string model = model_->itemData(index).toString().toStdString();
  if (model == settings_.model) return;
  const std::string rule = ruleForModel(model, settings_.rule);
  const QString note =
      rule != settings_.rule ? ruleChangeNote(settings_.rule, model, rule) : QString();
  settings_.parameters = carriedOver(model, rule, settings_.parameters);
  settings_.model = model;
  settings_.rule = rule;
  updating_ = true;
  rule_->setCurrentIndex(rule_->findData(qs(rule)));
  preset_->setCurrentIndex(0);
  updating_ = false;
  refreshRuleAvailability();
  rebuildRows();
  showStatus(note);  // stays until the next change
  changed();
}

std::string ParameterPanel::ruleForModel(const std::string& model, const std::string& current) {
  // The paper's pairing first (ModelInfo::preferredRule), then the current rule, then the first
  // rule that fits.
  const std::string preferred = forward::mapModelPreferredRule(model);
  if (!preferred.empty() && forward::mapCompatibility(model, preferred).allowed) return preferred;
  if (forward::mapCompatibility(model, current).allowed) return current;
  for (const std::string& r : forward::mapRuleNames())
    if (forward::mapCompatibility(model, r).allowed) return r;
  return current;
}

void ParameterPanel::chooseRule(int index) {
  if (updating_ || index < 0) return;
  const std::string rule = rule_->itemData(index).toString().toStdString();
  if (rule == settings_.rule) return;
  const Compatibility c = forward::mapCompatibility(settings_.model, rule);
  if (!c.allowed) {
    // A disabled item cannot be picked by hand; refuse it when set programmatically too.
    const QSignalBlocker block(rule_);
    rule_->setCurrentIndex(rule_->findData(qs(settings_.rule)));
    showStatus(
        tr("%1 cannot be used with %2: %3").arg(qs(rule), qs(settings_.model), qs(c.reason)));
    return;
  }
  settings_.parameters = carriedOver(settings_.model, rule, settings_.parameters);
  settings_.rule = rule;
  {
    const QSignalBlocker block(preset_);
    preset_->setCurrentIndex(0);
  }
  rebuildRows();
  showStatus({});
  changed();
}

void ParameterPanel::refreshRuleAvailability() {
  auto* items = qobject_cast<QStandardItemModel*>(rule_->model());
  for (int i = 0; i < rule_->count(); ++i) {
    const std::string rule = rule_->itemData(i).toString().toStdString();
    const Compatibility c = forward::mapCompatibility(settings_.model, rule);
    QStandardItem* item = items->item(i);
    item->setEnabled(c.allowed);
    item->setToolTip(c.allowed ? qs(forward::mapRuleSource(rule))
                               : tr("Not with %1: %2").arg(qs(settings_.model), qs(c.reason)));
  }
}

void ParameterPanel::rebuildRows() {
  for (QGroupBox* box : rowsHost_->findChildren<QGroupBox*>(Qt::FindDirectChildrenOnly)) delete box;
  rows_.clear();
  if (dragging_) {  // a held slider went with its row: its drag is over
    dragging_ = false;
    emit dragFinished();
  }
  const bool forwardModel = forward::isForwardModel(settings_.model);
  const QString caveat =
      forwardModel
          ? tr("A batch method: every change runs EM over the whole log, with its progress in "
               "the status bar (Stop EM ends it); the map shown stays until the new one is ready.")
          : qs(sensorModelCaveat(settings_.model));
  caveat_->setText(caveat);
  caveat_->setVisible(!caveat.isEmpty());
  // Short headings (the choosers above show the titles): a long one would widen the dock.
  addRows(forward::mapModelParameters(settings_.model), tr("Model (%1)").arg(qs(settings_.model)));
  if (!forwardModel)  // EM has no parameters of its own: the model's carry its cap
    addRows(forward::mapRuleParameters(settings_.rule), tr("Rule (%1)").arg(qs(settings_.rule)));
  // The rows are never squeezed or cut: the panel (and its dock) is at least as wide as they need
  // with the vertical scroll bar beside them.
  scroll_->setMinimumWidth(rowsHost_->minimumSizeHint().width() +
                           scroll_->verticalScrollBar()->sizeHint().width());
  showValues();
}

void ParameterPanel::addRows(const std::vector<ParameterSpec>& specs, const QString& heading) {
  auto* box = new QGroupBox(heading, rowsHost_);
  auto* grid = new QGridLayout(box);
  grid->setColumnStretch(1, 1);
  if (specs.empty()) grid->addWidget(new QLabel(tr("No parameters."), box), 0, 0, 1, 3);
  int line = 0;
  for (const ParameterSpec& spec : specs) {
    ParameterRow row;
    row.spec = spec;
    const double range = spec.max - spec.min;
    row.step = spec.integer ? 1.0 : niceStep(range / kSliderResolution);
    const int positions = static_cast<int>(std::ceil(range / row.step - 1e-9));
    const QString name = qs(spec.name);
    const QString tip = toolTipOf(spec);

    auto* label = new QLabel(labelText(spec), box);
    label->setToolTip(tip);
    row.slider = new QSlider(Qt::Horizontal, box);
    row.slider->setObjectName(QStringLiteral("slider_") + name);
    row.slider->setRange(0, positions);
    row.slider->setSingleStep(1);
    row.slider->setPageStep(std::max(1, positions / 20));
    row.slider->setFocusPolicy(Qt::StrongFocus);
    row.slider->setToolTip(tip);
    row.slider->setAccessibleName(fullName(spec));
    // Never squeezed to a bare handle: the dock grows (or scrolls) before the groove shrinks.
    row.slider->setMinimumWidth(kMinSliderWidth);
    auto* typed = new ParameterSpinBox(box);
    typed->outOfRange = [this, spec](const QString& text) {
      showStatus(tr("%1: %2 is out of range (%3 … %4); the value stays %5")
                     .arg(fullName(spec), text)
                     .arg(spec.min)
                     .arg(spec.max)
                     .arg(settings_.parameters.get(spec.name)));
    };
    typed->setCorrectionMode(QAbstractSpinBox::CorrectToPreviousValue);
    row.spin = typed;
    row.spin->setObjectName(QStringLiteral("spin_") + name);
    const int decimals = spec.integer
                             ? 0
                             : std::max({decimalsOf(row.step), decimalsOf(spec.min),
                                         decimalsOf(spec.max), decimalsOf(spec.defaultValue)});
    row.spin->setDecimals(decimals);
    row.spin->setRange(spec.min, spec.max);
    row.spin->setSingleStep(spec.integer ? 1.0
                                         : std::pow(10.0, std::round(std::log10(range / 100.0))));
    row.spin->setSuffix(unitSuffix(spec.unit));
    row.spin->setKeyboardTracking(false);  // typing "0.15" re-maps once, on Enter
    row.spin->setToolTip(tip);
    row.spin->setAccessibleName(fullName(spec));
    // A parameter the rule makes no use of (update_rule.h) is shown disabled, with the reason:
    // a slider that changes nothing would teach the wrong lesson.
    const std::string unused = unusedParameterReason(settings_.model, settings_.rule, spec.name);
    if (!unused.empty()) {
      const QString why = tr("Not used by this rule: %1.").arg(qs(unused));
      for (QWidget* w : std::initializer_list<QWidget*>{label, row.slider, row.spin}) {
        w->setEnabled(false);
        w->setToolTip(why + QStringLiteral("\n\n") + tip);
      }
    }
    label->setBuddy(row.spin);
    grid->addWidget(label, line, 0);
    grid->addWidget(row.slider, line, 1);
    grid->addWidget(row.spin, line, 2);
    ++line;

    const std::string key = spec.name;
    QSlider* slider = row.slider;
    QDoubleSpinBox* spin = row.spin;
    const double min = spec.min, step = row.step, max = spec.max;
    connect(slider, &QSlider::valueChanged, this, [=, this](int position) {
      if (updating_) return;
      {
        const QSignalBlocker block(spin);
        spin->setValue(std::min(max, min + position * step));
      }
      commit(key, spin->value());  // the spin box's rounding keeps values short decimals
    });
    // A slider held down is a drag: the settings it emits meanwhile are one edit, which ends
    // when it is let go.
    connect(slider, &QSlider::sliderPressed, this, [this] { dragging_ = true; });
    connect(slider, &QSlider::sliderReleased, this, [this] {
      dragging_ = false;
      emit dragFinished();
    });
    connect(spin, &QDoubleSpinBox::valueChanged, this, [=, this](double value) {
      if (updating_) return;
      {
        const QSignalBlocker block(slider);
        slider->setValue(static_cast<int>(std::lround((value - min) / step)));
      }
      commit(key, value);
    });
    rows_.push_back(row);
  }
  rowsLayout_->insertWidget(rowsLayout_->count() - 1, box);
}

void ParameterPanel::showValues() {
  updating_ = true;
  for (const ParameterRow& row : rows_) {
    const double v = settings_.parameters.get(row.spec.name);
    row.spin->setValue(v);
    row.slider->setValue(static_cast<int>(std::lround((v - row.spec.min) / row.step)));
  }
  updating_ = false;
}

void ParameterPanel::commit(const std::string& name, double value) {
  const auto row = std::find_if(rows_.begin(), rows_.end(),
                                [&](const ParameterRow& r) { return r.spec.name == name; });
  if (row == rows_.end()) return;
  value = std::clamp(value, row->spec.min, row->spec.max);
  if (row->spec.integer) value = std::round(value);
  if (settings_.parameters.get(name) == value) return;  // no duplicate for the same value
  try {
    settings_.parameters.set(name, value);
  } catch (const ParameterError& e) {
    showStatus(qs(e.what()));
    return;
  }
  {
    const QSignalBlocker block(preset_);
    preset_->setCurrentIndex(0);
  }
  showStatus({}, /*keepRoom=*/true);  // a new value: the last note is history
  changed();
}

void ParameterPanel::changed() {
  emit settingsChanged(settings_);
}

void ParameterPanel::showStatus(const QString& text, bool keepRoom) {
  if (text.isEmpty() && keepRoom && status_->isVisible()) {
    // The note goes but its room stays, so that the sliders below do not jump under the pointer
    // of a drag that is under way (issue 49: about 90 px). Another model or rule, or the next
    // note, gives the room back.
    status_->setMinimumHeight(status_->height());
    status_->clear();
    return;
  }
  status_->setMinimumHeight(0);
  status_->setText(text);
  status_->setVisible(!text.isEmpty());
}

}  // namespace sg::ui
