// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The sweep view's plots (Qt Charts): one metric against each swept parameter (every set as a
// point, and the mean over the sets sharing each value as a line) and the metric's histogram over
// the sets in equal-width bins (paper 002 Fig. 7: VSDNS over the sweep's sets, 14 bins; the bins
// are the core's histogramOf(), optimal_sets.h).

#include <QWidget>
#include <optional>
#include <string>
#include <vector>

#include "sonargrid/params/parameters.h"

class QChart;
class QChartView;
class QGridLayout;

namespace sg::ui {

class SweepCharts : public QWidget {
  Q_OBJECT

 public:
  explicit SweepCharts(QWidget* parent = nullptr);

  // Draws `metric`'s `values` (one per set, empty where not evaluated) against each of
  // `parameters`, and its histogram with `bins` bins.
  void plot(const std::vector<ParameterSet>& sets, const std::vector<std::string>& parameters,
            const QString& metric, const std::vector<std::optional<double>>& values, int bins);
  void clear();

  // For tests: the histogram's bin counts as drawn, and the per-parameter charts' titles.
  const std::vector<std::size_t>& histogramCounts() const { return counts_; }
  QStringList parameterChartTitles() const;

 private:
  QChartView* viewAt(std::size_t i);
  void plotParameter(QChart* chart, const std::vector<ParameterSet>& sets,
                     const std::string& parameter, const QString& metric,
                     const std::vector<std::optional<double>>& values);
  void plotHistogram(QChart* chart, const QString& metric,
                     const std::vector<std::optional<double>>& values, int bins);

  QGridLayout* grid_;
  std::vector<QChartView*> views_;  // [0] the histogram, then one per parameter
  std::vector<std::size_t> counts_;
};

}  // namespace sg::ui
