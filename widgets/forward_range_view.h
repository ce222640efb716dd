// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The forward model's picture of one reading (docs/forward-model.md): the range distribution the
// map learned by EM predicts for the reading's beam, p(z | m), drawn over [0, z_max] with the
// no-echo probability as a bar at the right, and the measured range marked on it. Where an inverse
// model's beam view shows what one reading writes into the cells, this shows what the whole map
// expects the reading to be: a reading far from the curve's mass is one the map explains as
// random.

#include <QWidget>
#include <memory>
#include <optional>

#include "sonargrid/engine/occupancy_map.h"
#include "sonargrid/forward/forward_em.h"

namespace sg::ui {

class ForwardRangeView : public QWidget {
  Q_OBJECT

 public:
  explicit ForwardRangeView(QWidget* parent = nullptr);

  // The reading to show (its `range`, or kNoEcho) under `map`, a forward-model map whose native
  // layer is EM's occupancy (forward_em.h), with the settings it was learned with. A null map, or
  // one of another model, shows a note instead.
  void show(const forward::ForwardBeam& beam, std::shared_ptr<const OccupancyMap> map,
            const forward::ForwardSettings& settings);
  void clear();

  // What is drawn: the ranges sampled, the density at each, P(no echo); empty with no prediction.
  const std::vector<double>& ranges() const { return ranges_; }
  const forward::RangePrediction& prediction() const { return prediction_; }
  std::optional<double> measured() const { return measured_; }

  QSize sizeHint() const override { return {360, 240}; }

 protected:
  void paintEvent(QPaintEvent* event) override;

 private:
  std::vector<double> ranges_;
  forward::RangePrediction prediction_;
  std::optional<double> measured_;  // none: no echo
  double maxRange_ = 5.0;
  QString note_;
};

}  // namespace sg::ui
