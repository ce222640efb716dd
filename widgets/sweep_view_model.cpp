// SPDX-License-Identifier: GPL-3.0-or-later
#include "sweep_view_model.h"

#include "sonargrid/sweep/sweep_grid.h"

namespace sg::ui {

SweepResultsModel::SweepResultsModel(QObject* parent) : QAbstractTableModel(parent) {}

void SweepResultsModel::reset(std::vector<ParameterSet> sets, std::vector<std::string> parameters,
                              std::vector<std::string> columns) {
  beginResetModel();
  sets_ = std::move(sets);
  parameters_ = std::move(parameters);
  columns_ = std::move(columns);
  results_.assign(sets_.size(), std::nullopt);
  finished_ = 0;
  endResetModel();
}

void SweepResultsModel::setResult(std::size_t index, std::vector<std::optional<double>> values) {
  if (index >= results_.size()) return;
  if (!results_[index]) ++finished_;
  results_[index] = std::move(values);
  const int row = static_cast<int>(index);
  emit dataChanged(this->index(row, 0), this->index(row, columnCount() - 1));
}

std::vector<std::optional<double>> SweepResultsModel::columnValues(std::size_t column) const {
  std::vector<std::optional<double>> out;
  out.reserve(results_.size());
  for (const auto& r : results_)
    out.push_back(r && column < r->size() ? (*r)[column] : std::nullopt);
  return out;
}

int SweepResultsModel::rowCount(const QModelIndex& parent) const {
  return parent.isValid() ? 0 : static_cast<int>(sets_.size());
}

int SweepResultsModel::columnCount(const QModelIndex& parent) const {
  return parent.isValid() ? 0 : static_cast<int>(1 + parameters_.size() + columns_.size());
}

QVariant SweepResultsModel::data(const QModelIndex& index, int role) const {
  if (!index.isValid() || index.row() >= rowCount()) return {};
  const auto row = static_cast<std::size_t>(index.row());
  const auto column = static_cast<std::size_t>(index.column());
  if (role == Qt::TextAlignmentRole) return static_cast<int>(Qt::AlignRight | Qt::AlignVCenter);
  if (role != Qt::DisplayRole && role != Qt::UserRole) return {};
  if (column == 0) return static_cast<qulonglong>(row);
  if (column <= parameters_.size()) {
    const double v = sets_[row].get(parameters_[column - 1]);
    return role == Qt::UserRole ? QVariant(v) : QVariant(QString::fromStdString(shortestText(v)));
  }
  const std::size_t metric = column - 1 - parameters_.size();
  if (!results_[row]) return role == Qt::UserRole ? QVariant() : QVariant(QStringLiteral("…"));
  const std::optional<double> v = (*results_[row])[metric];
  if (!v) return role == Qt::UserRole ? QVariant() : QVariant(QStringLiteral("—"));
  return role == Qt::UserRole ? QVariant(*v) : QVariant(QString::number(*v, 'g', 6));
}

QVariant SweepResultsModel::headerData(int section, Qt::Orientation orientation, int role) const {
  if (role != Qt::DisplayRole) return {};
  if (orientation == Qt::Vertical) return section;
  const auto s = static_cast<std::size_t>(section);
  if (s == 0) return tr("set");
  if (s <= parameters_.size()) return QString::fromStdString(parameters_[s - 1]);
  if (s - 1 - parameters_.size() < columns_.size())
    return QString::fromStdString(columns_[s - 1 - parameters_.size()]);
  return {};
}

}  // namespace sg::ui
