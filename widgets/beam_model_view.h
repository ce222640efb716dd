// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The beam-model view (for teaching; paper 002 Figs 2, 3 and 5): for the chosen model, its
// parameters and a reading s, the 2-D map of P(occ) over the cone, the axial profile with its
// regions, a 3-D surface, and optionally a second model beside it. The pictures are the pure
// renderBeamModel() of beam_model_render.h; this widget adds the controls and caches the image.

#include <QImage>
#include <QWidget>
#include <optional>
#include <vector>

#include "beam_model_render.h"
#include "sonargrid/engine/mapper.h"

class QComboBox;
class QDoubleSpinBox;
class QSlider;

namespace sg::ui {

class BeamModelView : public QWidget {
  Q_OBJECT

 public:
  explicit BeamModelView(QWidget* parent = nullptr);

  void setSettings(const sg::MapperSettings& settings);
  // The reading s in metres (clamped to [0.05 m, the maximum range]).
  void setRange(double s);
  double range() const { return range_; }
  // The transducer's maximum range (metres); it bounds s.
  void setMaxRange(double metres);
  // A second model drawn beside the first to compare; nullopt for one model.
  void setComparisonSettings(const std::optional<sg::MapperSettings>& settings);

  // A configuration the "Compare with" chooser offers besides the models at their defaults and the
  // paper presets: the document's pinned rows.
  struct NamedSettings {
    QString label;
    sg::MapperSettings settings;
  };
  void setPinnedConfigurations(std::vector<NamedSettings> pinned);
  // Compares with the chooser's entry `key`: "model:NAME" (at its defaults), "preset:NAME",
  // "pinned:INDEX", "current" (the settings shown now, frozen) or "" (one model). False when the
  // chooser has no such entry.
  bool compareWith(const QString& key);
  const std::optional<sg::MapperSettings>& comparisonSettings() const { return comparison_; }

  // The scenes drawn (one or two) and the picture at `size`, as the widget paints it.
  std::vector<BeamScene> scenes() const;
  QImage render(QSize size) const { return renderBeamModel(scenes(), size); }

  QSize sizeHint() const override { return {420, 460}; }

 signals:
  // The user moved s.
  void rangeChanged(double s);

 private:
  class Canvas;
  void showRange();
  void invalidate();
  void rebuildCompareChooser();
  std::optional<sg::MapperSettings> settingsFor(const QString& key) const;

  sg::MapperSettings settings_;
  std::optional<sg::MapperSettings> comparison_;
  QString comparisonKey_;  // the chooser entry the comparison came from ("" when set directly)
  std::vector<NamedSettings> pinned_;
  double range_ = 2.0;
  double maxRange_ = 5.0;
  QSlider* rangeSlider_ = nullptr;
  QDoubleSpinBox* rangeSpin_ = nullptr;
  QComboBox* compare_ = nullptr;
  Canvas* canvas_ = nullptr;
};

}  // namespace sg::ui
