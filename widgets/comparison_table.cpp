// SPDX-License-Identifier: GPL-3.0-or-later
#include "comparison_table.h"

#include <QComboBox>
#include <QCoreApplication>
#include <QElapsedTimer>
#include <QFileDialog>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLocale>
#include <QMessageBox>
#include <QPushButton>
#include <QTableWidget>
#include <QTimer>
#include <QVBoxLayout>
#include <limits>

#include "sonargrid/base/atomic_file.h"

namespace sg::ui {
namespace {

constexpr int kFixedColumns = 3;  // row, configuration, cell size

std::string configurationKey(const ComparisonRow& row) {
  std::string key = row.settings.model + '|' + row.settings.rule + '|' +
                    (row.settings.pose == PoseSource::Truth ? "truth" : "odom") + '|' +
                    QString::number(row.cellSize, 'g', 17).toStdString();
  for (const auto& [name, value] : row.settings.parameters.values())
    key += '|' + name + '=' + QString::number(value, 'g', 17).toStdString();
  return key;
}

QString parametersText(const MapperSettings& s) {
  QStringList out;
  for (const auto& [name, value] : s.parameters.values())
    out << QStringLiteral("%1=%2").arg(QString::fromStdString(name)).arg(value, 0, 'g', 6);
  return out.join(QLatin1Char(' '));
}

QString poseText(PoseSource pose) {
  return pose == PoseSource::Truth ? QStringLiteral("truth") : QStringLiteral("odom");
}

QString csvField(QString text) {
  if (text.contains(QLatin1Char(',')) || text.contains(QLatin1Char('"')) ||
      text.contains(QLatin1Char('\n')))
    return QLatin1Char('"') + text.replace(QLatin1Char('"'), QStringLiteral("\"\"")) +
           QLatin1Char('"');
  return text;
}

}  // namespace

struct ComparisonTable::Outcome {
  std::vector<RowResult> rows;
  std::shared_ptr<const std::map<std::string, std::shared_ptr<const OccupancyMap>>> maps;
};

ComparisonTable::ComparisonTable(QWidget* parent)
    : QWidget(parent),
      status_(new QLabel(this)),
      cellSetChooser_(new QComboBox(this)),
      removeButton_(new QPushButton(tr("Unpin"), this)),
      table_(new QTableWidget(this)) {
  setObjectName(QStringLiteral("comparisonTable"));
  auto* pin = new QPushButton(tr("Pin Current"), this);
  pin->setObjectName(QStringLiteral("pinCurrent"));
  pin->setToolTip(tr("Add the current model, rule, parameters, pose and cell size as a row"));
  connect(pin, &QPushButton::clicked, this, &ComparisonTable::pinRequested);
  removeButton_->setObjectName(QStringLiteral("unpinRow"));
  removeButton_->setToolTip(tr("Remove the selected row"));
  connect(removeButton_, &QPushButton::clicked, this, [this] {
    const int row = table_->currentRow();
    if (row >= 0) emit removeRequested(static_cast<std::size_t>(row));
  });
  cellSetChooser_->setObjectName(QStringLiteral("cellSet"));
  cellSetChooser_->addItem(tr("Cells all maps observed"), int(CellSet::Common));
  cellSetChooser_->addItem(tr("Each map's own cells"), int(CellSet::EachMap));
  cellSetChooser_->setToolTip(
      tr("Score every row on the same cells (those every pinned map observed), or each map on "
         "the cells it observed itself"));
  connect(cellSetChooser_, &QComboBox::activated, this, [this](int index) {
    setCellSet(static_cast<CellSet>(cellSetChooser_->itemData(index).toInt()));
  });
  auto* exportButton = new QPushButton(tr("Export…"), this);
  exportButton->setObjectName(QStringLiteral("exportComparison"));
  exportButton->setToolTip(tr("Save the table as CSV or Markdown"));
  connect(exportButton, &QPushButton::clicked, this, &ComparisonTable::exportDialog);
  auto* bar = new QHBoxLayout;
  bar->addWidget(pin);
  bar->addWidget(removeButton_);
  bar->addWidget(cellSetChooser_);
  bar->addStretch(1);
  bar->addWidget(exportButton);

  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  table_->setSelectionBehavior(QAbstractItemView::SelectRows);
  table_->setSelectionMode(QAbstractItemView::SingleSelection);
  table_->verticalHeader()->setVisible(false);
  // A header and a row at the least: the dock shares the bottom with the one-row timeline, and
  // what it does not need goes to the grid and the parameter panel.
  table_->setMinimumHeight(table_->fontMetrics().height() * 3);
  table_->setToolTip(tr("Click a row to restore its configuration (undoable)"));
  connect(table_, &QTableWidget::cellClicked, this,
          [this](int row, int) { emit rowActivated(static_cast<std::size_t>(row)); });
  status_->setWordWrap(true);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(6, 6, 6, 6);
  layout->addLayout(bar);
  layout->addWidget(status_);
  layout->addWidget(table_, 1);
  fill();
}

ComparisonTable::~ComparisonTable() = default;

void ComparisonTable::setRows(std::vector<ComparisonRow> rows) {
  rows_ = std::move(rows);
  schedule();
}

void ComparisonTable::setRuns(std::shared_ptr<const Dataset> run,
                              std::shared_ptr<const Dataset> secondRun) {
  if (run != run_) maps_.reset();  // maps of another log
  run_ = std::move(run);
  secondRun_ = std::move(secondRun);
  schedule();
}

void ComparisonTable::setReference(std::shared_ptr<const ReferenceMap> reference) {
  reference_ = std::move(reference);
  schedule();
}

void ComparisonTable::setCellSet(CellSet set) {
  cellSet_ = set;
  cellSetChooser_->setCurrentIndex(cellSetChooser_->findData(int(set)));
  fill();
}

const MetricsResult* ComparisonTable::result(std::size_t row, CellSet set) const {
  if (row >= results_.size() || !results_[row]) return nullptr;
  return set == CellSet::Common ? &results_[row]->common : &results_[row]->each;
}

const MetricsResult* ComparisonTable::result(std::size_t row) const {
  return result(row, cellSet_);
}

void ComparisonTable::schedule() {
  results_.assign(rows_.size(), std::nullopt);
  fill();
  if (pending_) return;
  pending_ = true;
  QTimer::singleShot(0, this, &ComparisonTable::start);
}

void ComparisonTable::start() {
  pending_ = false;
  jobs_.renew();
  if (rows_.empty() || !run_) {
    fill();
    emit updated();
    return;
  }
  fill();
  jobs_.run<Outcome>(
      [rows = rows_, run = run_, second = secondRun_, reference = reference_,
       known = maps_](const std::atomic<bool>* cancel) {
        Outcome o;
        auto maps = std::make_shared<std::map<std::string, std::shared_ptr<const OccupancyMap>>>();
        std::vector<const OccupancyMap*> built;
        for (const ComparisonRow& row : rows) {
          const std::string key = configurationKey(row);
          std::shared_ptr<const OccupancyMap> map;
          if (known && known->count(key)) map = known->at(key);
          if (!map) {
            Mapper mapper(run->ring, run->fittingGrid(row.settings.pose, row.cellSize),
                          row.settings);
            if (!mapper.mapDataset(*run, std::numeric_limits<double>::infinity(), cancel))
              throw std::runtime_error("cancelled");
            map = std::make_shared<const OccupancyMap>(mapper.snapshot());
          }
          (*maps)[key] = map;
          built.push_back(map.get());
        }
        for (std::size_t i = 0; i < rows.size(); ++i) {
          MetricsInput in;
          in.map = (*maps)[configurationKey(rows[i])];
          in.reference = reference;
          in.run = run;
          in.secondRun = second;
          in.settings = rows[i].settings;
          in.cellSize = rows[i].cellSize;
          in.goodness = !reference;
          in.dminOverlay = false;
          RowResult r;
          const std::optional<MetricsResult> each = computeMetrics(in, cancel);
          if (!each) throw std::runtime_error("cancelled");
          r.each = *each;
          if (reference) {
            in.goodness = false;
            in.secondRun = nullptr;  // the two runs are compared once, in the view of each map
            in.score.cellMask = commonObservedCells(built, i);
            const std::optional<MetricsResult> common = computeMetrics(in, cancel);
            if (!common) throw std::runtime_error("cancelled");
            r.common = *common;
          } else {
            r.common = r.each;  // goodness has no cell set: the same numbers in both views
          }
          o.rows.push_back(std::move(r));
        }
        o.maps = std::move(maps);
        return o;
      },
      [this](JobOutcome<Outcome> outcome) {
        if (!outcome.current) return;  // superseded
        if (outcome.value) {
          maps_ = outcome.value->maps;
          for (std::size_t i = 0; i < outcome.value->rows.size() && i < results_.size(); ++i)
            results_[i] = outcome.value->rows[i];
          status_->clear();
        } else {
          status_->setText(tr("Not computed: %1").arg(outcome.error));
        }
        fill();
        emit updated();
      });
}

bool ComparisonTable::waitForResult(int timeoutMs) {
  QElapsedTimer clock;
  clock.start();
  while (busy() && clock.elapsed() < timeoutMs)
    QCoreApplication::processEvents(QEventLoop::AllEvents, 20);
  return !busy();
}

std::vector<const MetricInfo*> ComparisonTable::columns() const {
  std::vector<const MetricInfo*> out;
  if (reference_) {
    for (const MetricInfo& info : referenceMetricInfo()) out.push_back(&info);
  } else {
    for (const MetricInfo& info : goodnessMetricInfo()) {
      const bool twoRun = QByteArray(info.key).startsWith("two_run");
      if (!twoRun || secondRun_) out.push_back(&info);
    }
  }
  return out;
}

void ComparisonTable::fill() {
  const std::vector<const MetricInfo*> cols = columns();
  const int selected = table_->currentRow();
  table_->clear();
  table_->setColumnCount(kFixedColumns + static_cast<int>(cols.size()));
  table_->setRowCount(static_cast<int>(rows_.size()));
  QStringList headers{tr("Row"), tr("Model × rule, pose"), tr("Cell (m)")};
  for (const MetricInfo* info : cols)
    headers << (info->unit.isEmpty() ? info->label
                                     : QStringLiteral("%1 (%2)").arg(info->label, info->unit));
  table_->setHorizontalHeaderLabels(headers);
  for (std::size_t c = 0; c < cols.size(); ++c)
    table_->horizontalHeaderItem(kFixedColumns + static_cast<int>(c))->setToolTip(cols[c]->source);
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    const ComparisonRow& row = rows_[r];
    const int tr = static_cast<int>(r);
    auto* label = new QTableWidgetItem(row.label);
    label->setToolTip(parametersText(row.settings));
    table_->setItem(tr, 0, label);
    table_->setItem(tr, 1,
                    new QTableWidgetItem(QStringLiteral("%1 × %2, %3")
                                             .arg(QString::fromStdString(row.settings.model),
                                                  QString::fromStdString(row.settings.rule),
                                                  poseText(row.settings.pose))));
    table_->setItem(tr, 2, new QTableWidgetItem(QString::number(row.cellSize)));
    const MetricsResult* res = result(r);
    for (std::size_t c = 0; c < cols.size(); ++c) {
      const QString text =
          !res ? QStringLiteral("…") : formatValue(res->value(cols[c]->key), cols[c]->precision);
      auto* item = new QTableWidgetItem(text);
      item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
      table_->setItem(tr, kFixedColumns + static_cast<int>(c), item);
    }
  }
  if (selected >= 0 && selected < table_->rowCount()) table_->selectRow(selected);
  table_->resizeColumnsToContents();
  removeButton_->setEnabled(!rows_.empty());
  if (rows_.empty())
    status_->setText(tr("Pin the current configuration to compare it with others."));
  else if (busy())
    status_->setText(tr("Computing %n map(s)…", nullptr, static_cast<int>(rows_.size())));
  else if (!run_)
    status_->setText(tr("Open the log the rows were pinned for."));
  else if (status_->text().startsWith(tr("Computing")))
    status_->clear();
}

QString ComparisonTable::csv() const {
  const std::vector<const MetricInfo*> cols = columns();
  QStringList header{QStringLiteral("label"),  QStringLiteral("model"),
                     QStringLiteral("rule"),   QStringLiteral("pose"),
                     QStringLiteral("cell_m"), QStringLiteral("parameters"),
                     QStringLiteral("cells")};
  for (const MetricInfo* info : cols) header << QString::fromLatin1(info->key);
  QString out = header.join(QLatin1Char(',')) + QLatin1Char('\n');
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    const ComparisonRow& row = rows_[r];
    QStringList fields{
        csvField(row.label),
        QString::fromStdString(row.settings.model),
        QString::fromStdString(row.settings.rule),
        poseText(row.settings.pose),
        QString::number(row.cellSize, 'g', QLocale::FloatingPointShortest),
        csvField(parametersText(row.settings)),
        cellSet_ == CellSet::Common ? QStringLiteral("common") : QStringLiteral("own")};
    const MetricsResult* res = result(r);
    for (const MetricInfo* info : cols) {
      const std::optional<double> v = res ? res->value(info->key) : std::nullopt;
      fields << (v ? QString::number(*v, 'g', QLocale::FloatingPointShortest) : QString());
    }
    out += fields.join(QLatin1Char(',')) + QLatin1Char('\n');
  }
  return out;
}

QString ComparisonTable::markdown() const {
  const std::vector<const MetricInfo*> cols = columns();
  QStringList header{tr("row"), tr("model × rule"), tr("pose"), tr("cell (m)")};
  for (const MetricInfo* info : cols)
    header << (info->unit.isEmpty() ? info->label
                                    : QStringLiteral("%1 (%2)").arg(info->label, info->unit));
  QString out = QStringLiteral("| ") + header.join(QStringLiteral(" | ")) + QStringLiteral(" |\n|");
  for (qsizetype c = 0; c < header.size(); ++c)
    out += c < 4 ? QStringLiteral("---|") : QStringLiteral("---:|");
  out += QLatin1Char('\n');
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    const ComparisonRow& row = rows_[r];
    QStringList fields{row.label,
                       QStringLiteral("%1 × %2").arg(QString::fromStdString(row.settings.model),
                                                     QString::fromStdString(row.settings.rule)),
                       poseText(row.settings.pose), QString::number(row.cellSize)};
    const MetricsResult* res = result(r);
    for (const MetricInfo* info : cols)
      fields << (res ? formatValue(res->value(info->key), info->precision) : QString());
    out += QStringLiteral("| ") + fields.join(QStringLiteral(" | ")) + QStringLiteral(" |\n");
  }
  out += cellSet_ == CellSet::Common ? tr("\nScored on the cells every pinned map observed.\n")
                                     : tr("\nEach map scored on the cells it observed.\n");
  return out;
}

QString ComparisonTable::exportTo(const QString& path) const {
  const bool md = QFileInfo(path).suffix().compare(QLatin1String("md"), Qt::CaseInsensitive) == 0;
  const QByteArray bytes = (md ? markdown() : csv()).toUtf8();
  try {
    writeFileAtomically(
        QFile::encodeName(path).toStdString(),
        std::string_view(bytes.constData(), static_cast<std::size_t>(bytes.size())));
  } catch (const std::exception& e) {
    return QString::fromUtf8(e.what());
  }
  return {};
}

void ComparisonTable::exportDialog() {
  QString filter;
  const QString path =
      QFileDialog::getSaveFileName(this, tr("Export Comparison"), QStringLiteral("comparison.csv"),
                                   tr("CSV (*.csv);;Markdown (*.md)"), &filter);
  if (path.isEmpty()) return;
  const QString error = exportTo(path);
  if (!error.isEmpty()) QMessageBox::warning(this, tr("Export Comparison"), error);
}

}  // namespace sg::ui
