// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The Beam Model dock's content: the beam-model view of one reading of the current scan, and the
// chooser of that reading. It keeps which sonar the user chose (the first reading with an echo
// until they choose) and paces the view's redraws while settings change: the picture costs 5-10 ms
// of GUI thread, and on two cores every ms of it is taken from the re-map.

#include <QElapsedTimer>
#include <QWidget>
#include <memory>
#include <optional>
#include <vector>

#include "sonargrid/data/dataset.h"
#include "sonargrid/engine/mapper.h"
#include "sonargrid/engine/occupancy_map.h"
#include "sonargrid/forward/forward_em.h"

class QComboBox;
class QTimer;

namespace sg::ui {
class BeamModelView;
class ForwardRangeView;
}  // namespace sg::ui

namespace sg::app {

class BeamDock : public QWidget {
  Q_OBJECT

 public:
  explicit BeamDock(const MapperSettings& settings, QWidget* parent = nullptr);

  ui::BeamModelView* view() const { return view_; }
  // The forward model's picture (forward_range_view.h), shown instead of the beam model view
  // while the settings are the forward model's: it has no inverse model to draw.
  ui::ForwardRangeView* forwardView() const { return forward_; }
  // The shown reading under the forward model's map (see forwardView()).
  void showForward(const forward::ForwardBeam& beam, std::shared_ptr<const OccupancyMap> map);
  // The sonar whose reading the view shows now.
  std::optional<std::size_t> sonar() const { return shown_; }

  // The current scan's readings: lists them, shows the chosen sonar's (else the first with an
  // echo, else the first) and returns its sonar. A reading without echo is drawn at `maxRange`.
  std::optional<std::size_t> showReadings(const std::vector<Reading>& readings, double maxRange);
  // The user's choice from now on, if `readings` has a reading of `sonar`.
  bool choose(const std::vector<Reading>& readings, std::size_t sonar);
  // A new log: no choice, no readings; the view's scale is `maxRange`.
  void startLog(double maxRange);
  // No log: nothing listed or shown.
  void clearReadings();

  // New settings for the view. `paced`: drawn once the grid shows the new map (gridRepainted), or
  // kIntervalMs after the change (a long re-map of a big log), but not more often than every
  // kIntervalMs, so that a dragged slider moves it several times a second without slowing the
  // map. Otherwise drawn now.
  void setSettings(const MapperSettings& settings, bool paced);
  void gridRepainted(bool remapBusy);

 signals:
  // The user chose a reading in the chooser.
  void sonarPicked(std::size_t sonar);

 private:
  void showSettings();

  static constexpr int kIntervalMs = 150;
  ui::BeamModelView* view_;
  ui::ForwardRangeView* forward_;
  QComboBox* chooser_;
  std::optional<std::size_t> chosen_;  // the user's pick; none: the first reading with echo
  std::optional<std::size_t> shown_;   // what the view shows now
  MapperSettings settings_;            // the newest settings
  bool pending_ = false;               // settings_ not drawn yet
  QTimer* timer_;
  QElapsedTimer shownAt_;  // since the view last took new settings
};

}  // namespace sg::app
