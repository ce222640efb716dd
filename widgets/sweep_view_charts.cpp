// SPDX-License-Identifier: GPL-3.0-or-later
#include "sweep_view_charts.h"

#include <QBarCategoryAxis>
#include <QBarSeries>
#include <QBarSet>
#include <QChart>
#include <QChartView>
#include <QFont>
#include <QGridLayout>
#include <QLineSeries>
#include <QScatterSeries>
#include <QValueAxis>
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "sonargrid/sweep/optimal_sets.h"

namespace sg::ui {
namespace {

void resetChart(QChart* chart, const QString& title) {
  chart->removeAllSeries();
  for (QAbstractAxis* axis : chart->axes()) {
    chart->removeAxis(axis);
    delete axis;
  }
  chart->setTitle(title);
}

// [lo, hi] widened by 5 % (or ±1 around a single value) so points do not sit on the frame.
std::pair<double, double> padded(double lo, double hi) {
  if (!(hi > lo))
    return {lo - (lo == 0.0 ? 1.0 : std::abs(lo) * 0.05),
            hi + (hi == 0.0 ? 1.0 : std::abs(hi) * 0.05)};
  const double pad = (hi - lo) * 0.05;
  return {lo - pad, hi + pad};
}

}  // namespace

SweepCharts::SweepCharts(QWidget* parent) : QWidget(parent), grid_(new QGridLayout(this)) {
  grid_->setContentsMargins(0, 0, 0, 0);
  grid_->setSpacing(2);
}

QChartView* SweepCharts::viewAt(std::size_t i) {
  while (views_.size() <= i) {
    auto* view = new QChartView(new QChart, this);
    view->setObjectName(views_.empty() ? QStringLiteral("histogramChart")
                                       : QStringLiteral("parameterChart%1").arg(views_.size()));
    view->setRenderHint(QPainter::Antialiasing);
    view->setMinimumSize(240, 180);
    view->chart()->legend()->setAlignment(Qt::AlignBottom);
    view->chart()->setMargins(QMargins(2, 2, 2, 2));
    const int n = static_cast<int>(views_.size());
    grid_->addWidget(view, n / 2, n % 2);
    views_.push_back(view);
  }
  views_[i]->show();
  return views_[i];
}

void SweepCharts::clear() {
  for (QChartView* v : views_) {
    resetChart(v->chart(), {});
    v->hide();
  }
  counts_.clear();
}

QStringList SweepCharts::parameterChartTitles() const {
  QStringList out;
  for (std::size_t i = 1; i < views_.size(); ++i)
    if (!views_[i]->isHidden()) out << views_[i]->chart()->title();
  return out;
}

void SweepCharts::plot(const std::vector<ParameterSet>& sets,
                       const std::vector<std::string>& parameters, const QString& metric,
                       const std::vector<std::optional<double>>& values, int bins) {
  plotHistogram(viewAt(0)->chart(), metric, values, bins);
  for (std::size_t p = 0; p < parameters.size(); ++p)
    plotParameter(viewAt(p + 1)->chart(), sets, parameters[p], metric, values);
  for (std::size_t i = parameters.size() + 1; i < views_.size(); ++i) views_[i]->hide();
}

void SweepCharts::plotParameter(QChart* chart, const std::vector<ParameterSet>& sets,
                                const std::string& parameter, const QString& metric,
                                const std::vector<std::optional<double>>& values) {
  const QString name = QString::fromStdString(parameter);
  resetChart(chart, tr("%1 against %2").arg(metric, name));
  auto* points = new QScatterSeries;
  points->setName(tr("sets"));
  points->setMarkerSize(7.0);
  std::map<double, std::pair<double, std::size_t>> byValue;  // value → (sum, count)
  double xlo = INFINITY, xhi = -INFINITY, ylo = INFINITY, yhi = -INFINITY;
  for (std::size_t i = 0; i < sets.size() && i < values.size(); ++i) {
    const double x = sets[i].get(parameter);
    xlo = std::min(xlo, x);
    xhi = std::max(xhi, x);
    if (!values[i]) continue;
    const double y = *values[i];
    points->append(x, y);
    auto& [sum, count] = byValue[x];
    sum += y;
    ++count;
    ylo = std::min(ylo, y);
    yhi = std::max(yhi, y);
  }
  auto* mean = new QLineSeries;
  mean->setName(tr("mean per value"));
  for (const auto& [x, sc] : byValue) mean->append(x, sc.first / static_cast<double>(sc.second));
  chart->addSeries(mean);
  chart->addSeries(points);
  auto* ax = new QValueAxis;
  ax->setTitleText(name);
  auto* ay = new QValueAxis;
  ay->setTitleText(metric);
  ax->setLabelFormat(QStringLiteral("%.3g"));
  ay->setLabelFormat(QStringLiteral("%.3g"));
  if (std::isfinite(xlo)) {
    const auto [a, b] = padded(xlo, xhi);
    ax->setRange(a, b);
    ax->applyNiceNumbers();
  }
  if (std::isfinite(ylo)) {
    const auto [a, b] = padded(ylo, yhi);
    ay->setRange(a, b);
  }
  chart->addAxis(ax, Qt::AlignBottom);
  chart->addAxis(ay, Qt::AlignLeft);
  for (QAbstractSeries* s :
       {static_cast<QAbstractSeries*>(mean), static_cast<QAbstractSeries*>(points)}) {
    s->attachAxis(ax);
    s->attachAxis(ay);
  }
}

void SweepCharts::plotHistogram(QChart* chart, const QString& metric,
                                const std::vector<std::optional<double>>& values, int bins) {
  resetChart(chart,
             metric == QStringLiteral("vsdns")
                 ? tr("Histogram of VSDNS over the sets, %1 bins (paper 002 Fig. 7)").arg(bins)
                 : tr("Histogram of %1 over the sets, %2 bins").arg(metric).arg(bins));
  counts_.clear();
  Histogram h;
  try {
    h = histogramOf(values, bins);
  } catch (const std::invalid_argument&) {
    return;  // nothing evaluated yet
  }
  counts_ = h.counts;
  auto* set = new QBarSet(tr("sets per bin"));
  QStringList labels;
  std::size_t most = 0;
  for (int b = 0; b < bins; ++b) {
    const std::size_t n = h.counts[static_cast<std::size_t>(b)];
    *set << static_cast<double>(n);
    most = std::max(most, n);
    labels << QString::number((h.lowerEdge(b) + h.upperEdge(b)) / 2.0, 'g', 3);
  }
  auto* series = new QBarSeries;
  series->append(set);
  series->setBarWidth(0.95);
  chart->addSeries(series);
  auto* ax = new QBarCategoryAxis;
  ax->append(labels);
  ax->setTitleText(tr("%1 (bin centre)").arg(metric));
  ax->setLabelsAngle(-90);
  QFont small = ax->labelsFont();
  small.setPointSizeF(small.pointSizeF() * 0.75);
  ax->setLabelsFont(small);
  auto* ay = new QValueAxis;
  ay->setRange(0, static_cast<double>(std::max<std::size_t>(most, 1)));
  ay->setLabelFormat(QStringLiteral("%d"));
  ay->setTitleText(tr("sets"));
  chart->addAxis(ax, Qt::AlignBottom);
  chart->addAxis(ay, Qt::AlignLeft);
  series->attachAxis(ax);
  series->attachAxis(ay);
  chart->legend()->hide();
}

}  // namespace sg::ui
