// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The sweep view's table: one row per parameter set of the sweep, in set order (the core's
// sweepSets() order), with the set's index, the parameters the sweep varies (swept and tied) and
// one column per metric column (sweep_metrics.h), empty until the set has been evaluated.

#include <QAbstractTableModel>
#include <optional>
#include <string>
#include <vector>

#include "sonargrid/params/parameters.h"

namespace sg::ui {

class SweepResultsModel : public QAbstractTableModel {
  Q_OBJECT

 public:
  explicit SweepResultsModel(QObject* parent = nullptr);

  // A new sweep: its sets, the parameters shown (swept, then tied) and the metric columns; every
  // result empty.
  void reset(std::vector<ParameterSet> sets, std::vector<std::string> parameters,
             std::vector<std::string> columns);
  void setResult(std::size_t index, std::vector<std::optional<double>> values);

  const std::vector<ParameterSet>& sets() const { return sets_; }
  const std::vector<std::string>& parameters() const { return parameters_; }
  const std::vector<std::string>& columns() const { return columns_; }
  // Per set: its values (one per column), or empty while not evaluated.
  const std::vector<std::optional<std::vector<std::optional<double>>>>& results() const {
    return results_;
  }
  std::size_t finishedCount() const { return finished_; }
  // One column's values over every set: empty for a set not evaluated or a metric undefined.
  std::vector<std::optional<double>> columnValues(std::size_t column) const;

  int rowCount(const QModelIndex& parent = {}) const override;
  int columnCount(const QModelIndex& parent = {}) const override;
  QVariant data(const QModelIndex& index, int role = Qt::DisplayRole) const override;
  QVariant headerData(int section, Qt::Orientation orientation,
                      int role = Qt::DisplayRole) const override;

 private:
  std::vector<ParameterSet> sets_;
  std::vector<std::string> parameters_;
  std::vector<std::string> columns_;
  std::vector<std::optional<std::vector<std::optional<double>>>> results_;
  std::size_t finished_ = 0;
};

}  // namespace sg::ui
