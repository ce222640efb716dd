// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The parameter panel: model and rule choosers, a slider and a spin box for every parameter the
// chosen model and rule declare (built from their ParameterSpecs, nothing restated here), the paper
// presets, Reset to defaults and the last re-map time. Every distinct value change emits
// settingsChanged once; the re-mapping controller cancels runs that a newer change made stale.

#include <QWidget>
#include <string>
#include <vector>

#include "sonargrid/engine/mapper.h"

class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QPushButton;
class QScrollArea;
class QSlider;
class QVBoxLayout;

namespace sg::ui {

class ParameterPanel : public QWidget {
  Q_OBJECT

 public:
  explicit ParameterPanel(QWidget* parent = nullptr);

  // Shows `settings` without emitting settingsChanged. An unknown model or rule name, or an
  // incompatible pair, is refused (the panel keeps its settings) and reported in the status line.
  // When the model and the rule both change (the Mapping menu's model, undo, a project) a note
  // says that the rule changed with the model; not when `ruleNamed` (the user named this rule
  // themselves, e.g. on the command line).
  void setSettings(const sg::MapperSettings& settings, bool ruleNamed = false);
  sg::MapperSettings settings() const { return settings_; }

  // The widgets of one parameter (objectNames "slider_<name>" and "spin_<name>"), or nullptr.
  QSlider* sliderFor(const QString& name) const;
  QDoubleSpinBox* spinBoxFor(const QString& name) const;

  // A non-integer parameter's slider moves in "nice" steps (1, 2 or 5 × 10^k) of at least
  // 1/kSliderResolution of its range, so slider values print as short decimals.
  static constexpr int kSliderResolution = 1000;
  // No slider is laid out narrower than this (the panel's rows keep the symbol only, the long
  // name goes to the tooltip).
  static constexpr int kMinSliderWidth = 96;  // a groove of at least 80 px in any style

  // True while one of the panel's sliders is held down: the settingsChanged() it emits are steps
  // of one drag, which dragFinished() ends.
  bool dragging() const { return dragging_; }

  // The note under the choosers ("Rule changed from …", an out-of-range value), or "" when none
  // is shown.
  QString statusText() const;

  // The rule to use with `model` when the user switches to it from a map with rule `current`: the
  // paper's pairing (ModelInfo::preferredRule), else `current` if it fits, else the first that
  // fits.
  static std::string ruleForModel(const std::string& model, const std::string& current);

 public slots:
  void showRemapTime(double milliseconds);
  void resetToDefaults();
  // Applies the paper preset with this registry name (sonargrid/params/presets.h); false when
  // unknown.
  bool applyPreset(const QString& name);

 signals:
  void settingsChanged(const sg::MapperSettings& settings);
  // A held slider was let go: the drag's steps are over.
  void dragFinished();

 private:
  struct ParameterRow {
    sg::ParameterSpec spec;
    double step = 1.0;  // value change per slider position
    QSlider* slider = nullptr;
    QDoubleSpinBox* spin = nullptr;
  };

  void chooseModel(int index);
  void chooseRule(int index);
  void rebuildRows();
  void addRows(const std::vector<sg::ParameterSpec>& specs, const QString& heading);
  void refreshRuleAvailability();
  void showValues();
  void commit(const std::string& name, double value);
  void changed();
  // The note under the choosers; with `keepRoom`, clearing a shown note keeps its height.
  void showStatus(const QString& text, bool keepRoom = false);
  QString ruleChangeNote(const std::string& fromRule, const std::string& model,
                         const std::string& toRule) const;

  sg::MapperSettings settings_;
  QComboBox* model_ = nullptr;
  QComboBox* rule_ = nullptr;
  QComboBox* preset_ = nullptr;
  QPushButton* reset_ = nullptr;
  QLabel* caveat_ = nullptr;
  QLabel* status_ = nullptr;
  QLabel* remapTime_ = nullptr;
  QWidget* rowsHost_ = nullptr;
  QScrollArea* scroll_ = nullptr;
  QVBoxLayout* rowsLayout_ = nullptr;
  std::vector<ParameterRow> rows_;
  bool dragging_ = false;  // a slider of the panel is held down (dragging())
  bool updating_ = false;  // true while the panel itself moves widgets to show settings_
};

}  // namespace sg::ui
