// SPDX-License-Identifier: GPL-3.0-or-later
#include "cell_inspector.h"

#include <QComboBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLocale>
#include <QPointer>
#include <QSplitter>
#include <QTreeWidget>
#include <QVBoxLayout>

namespace sg::ui {

namespace {

enum Column { kTime, kSonar, kRange, kEmpty, kOccupied, kNative, kProbability, kColumns };

QString number(double v, int decimals) {
  return QString::number(v, 'f', decimals);
}

}  // namespace

CellInspector::CellInspector(QWidget* parent) : QWidget(parent) {
  header_ = new QLabel(this);
  header_->setObjectName(QStringLiteral("cellInspectorHeader"));
  header_->setWordWrap(true);
  header_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  quantity_ = new QComboBox(this);
  quantity_->setObjectName(QStringLiteral("cellInspectorQuantity"));
  quantity_->addItem(tr("Rule's value"), int(CellTracePlot::Quantity::Native));
  quantity_->addItem(tr("p(occ)"), int(CellTracePlot::Quantity::Probability));
  quantity_->addItem(tr("CV level"), int(CellTracePlot::Quantity::Level));
  quantity_->setToolTip(tr("What the plot shows on y"));
  auto* quantityLabel = new QLabel(tr("&Plot:"), this);
  quantityLabel->setBuddy(quantity_);

  plot_ = new CellTracePlot(this);
  plot_->setObjectName(QStringLiteral("cellTracePlot"));
  list_ = new QTreeWidget(this);
  list_->setObjectName(QStringLiteral("cellReadings"));
  list_->setRootIsDecorated(false);
  list_->setUniformRowHeights(true);
  list_->setAlternatingRowColors(true);
  list_->setSelectionMode(QAbstractItemView::SingleSelection);
  list_->setColumnCount(kColumns);
  list_->setHeaderLabels({tr("Time (s)"), tr("Sonar"), tr("Range (m)"), tr("pE"), tr("pO"),
                          tr("Value after"), tr("p(occ) after")});
  list_->headerItem()->setToolTip(kEmpty, tr("The model's free evidence at this cell"));
  list_->headerItem()->setToolTip(kOccupied, tr("The model's occupied evidence at this cell"));
  list_->headerItem()->setToolTip(kNative, tr("The rule's value of the cell after this reading"));
  list_->header()->setSectionResizeMode(QHeaderView::ResizeToContents);
  list_->setToolTip(tr("The readings that wrote this cell; select one to see it in the beam view"));

  auto* split = new QSplitter(Qt::Horizontal, this);
  split->addWidget(plot_);
  split->addWidget(list_);
  split->setStretchFactor(0, 1);
  split->setStretchFactor(1, 1);
  split->setChildrenCollapsible(false);

  auto* top = new QHBoxLayout;
  top->addWidget(header_, 1);
  top->addWidget(quantityLabel);
  top->addWidget(quantity_);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(6, 4, 6, 4);
  layout->addLayout(top);
  layout->addWidget(split, 1);

  connect(quantity_, &QComboBox::currentIndexChanged, this, [this](int index) {
    plot_->setQuantity(static_cast<CellTracePlot::Quantity>(quantity_->itemData(index).toInt()));
  });
  connect(plot_, &CellTracePlot::stepClicked, this, &CellInspector::selectStep);
  connect(list_, &QTreeWidget::currentItemChanged, this, [this](QTreeWidgetItem* item) {
    if (!item || !trace_) return;
    const auto step = static_cast<std::size_t>(list_->indexOfTopLevelItem(item));
    plot_->setSelectedStep(step);
    const CellTraceStep& s = trace_->steps[step];
    emit readingChosen(s.scan, s.sonar);
  });
  status_ = tr("Shift+click a cell of the grid to inspect it.");
  updateHeader();
}

CellInspector::~CellInspector() = default;

void CellInspector::setContext(std::shared_ptr<const Dataset> log, const GridSpec& grid,
                               const MapperSettings& settings) {
  const bool same = log == data_ && grid_ == grid && settings == settings_;
  if (same) return;
  // A new grid (another cell size or log) keeps the same place of the world inspected.
  std::optional<Position> world = cellCentre();
  data_ = std::move(log);
  grid_ = grid;
  settings_ = settings;
  if (world) {
    const CellIndex c = grid.worldToCell(*world);
    if (grid.contains(c)) {
      cell_ = c;
    } else {
      cell_.reset();
      trace_.reset();
      plot_->setTrace(nullptr);
      fillList();
      emit cellChanged();
    }
  }
  if (cell_) start();
  updateHeader();
}

void CellInspector::clearContext(const QString& why) {
  if (!data_ && !grid_ && !cell_ && status_ == why) return;  // a live map's every append
  jobs_.renew();
  data_.reset();
  grid_.reset();
  trace_.reset();
  cell_.reset();
  status_ = why;
  plot_->setTrace(nullptr);
  fillList();
  updateHeader();
  emit cellChanged();
}

std::optional<Position> CellInspector::cellCentre() const {
  if (!cell_ || !grid_) return std::nullopt;
  return grid_->cellCentre(*cell_);
}

bool CellInspector::inspectAt(const Position& world) {
  if (!grid_) return false;
  return inspect(grid_->worldToCell(world));
}

bool CellInspector::inspect(const CellIndex& cell) {
  if (!grid_ || !data_ || !grid_->contains(cell)) return false;
  cell_ = cell;
  trace_.reset();
  plot_->setTrace(nullptr);
  fillList();
  emit cellChanged();
  start();
  updateHeader();
  return true;
}

void CellInspector::start() {
  jobs_.renew();
  status_ = tr("Tracing…");
  // The job holds its own copies.
  jobs_.run<std::shared_ptr<const CellTrace>>(
      [data = data_, grid = *grid_, settings = settings_,
       cell = *cell_](const std::atomic<bool>* cancel) -> std::shared_ptr<const CellTrace> {
        auto t = std::make_shared<CellTrace>(traceCell(
            *data, grid, settings, cell, std::numeric_limits<double>::infinity(), cancel));
        if (!t->complete) return nullptr;
        return t;
      },
      [this](JobOutcome<std::shared_ptr<const CellTrace>> outcome) {
        deliver(outcome.generation, outcome.value ? *outcome.value : nullptr, outcome.error);
      });
}

void CellInspector::deliver(quint64 generation, std::shared_ptr<const CellTrace> trace,
                            const QString& error) {
  if (generation != jobs_.generation()) return;  // a newer cell or context took its place
  if (!error.isEmpty()) {
    status_ = error;
    updateHeader();
    emit traceFailed(error);
    return;
  }
  if (!trace) return;
  trace_ = std::move(trace);
  status_.clear();
  plot_->setTrace(trace_);
  fillList();
  updateHeader();
  emit traced(trace_);
}

void CellInspector::fillList() {
  const QSignalBlocker block(list_);
  list_->clear();
  if (!trace_) return;
  QList<QTreeWidgetItem*> items;
  items.reserve(static_cast<qsizetype>(trace_->steps.size()));
  for (const CellTraceStep& s : trace_->steps) {
    auto* item = new QTreeWidgetItem;
    item->setText(kTime, number(s.time, 2));
    item->setText(kSonar, QString::number(s.sonar));
    item->setText(kRange, std::isfinite(s.range) ? number(s.range, 3) : tr("no echo"));
    item->setText(kEmpty, number(s.empty, 3));
    item->setText(kOccupied, number(s.occupied, 3));
    item->setText(kNative, QString::number(s.after.native, 'g', 6));
    item->setText(kProbability, number(s.after.probability, 3));
    for (int c = kTime; c < kColumns; ++c)
      if (c != kTime) item->setTextAlignment(c, Qt::AlignRight | Qt::AlignVCenter);
    item->setToolTip(kTime, tr("Reading %1 of the log, scan %2; level after %3")
                                .arg(s.reading)
                                .arg(s.scan)
                                .arg(s.after.level));
    items.append(item);
  }
  list_->addTopLevelItems(items);
}

void CellInspector::selectStep(std::size_t step) {
  if (!trace_ || step >= trace_->steps.size()) return;
  QTreeWidgetItem* item = list_->topLevelItem(static_cast<int>(step));
  if (list_->currentItem() == item) {
    // Chosen again: show it again (the timeline may have moved since).
    const CellTraceStep& s = trace_->steps[step];
    emit readingChosen(s.scan, s.sonar);
    return;
  }
  list_->setCurrentItem(item);  // emits readingChosen through currentItemChanged
  list_->scrollToItem(item);
}

void CellInspector::setCurrentTime(double t) {
  plot_->setMarkerTime(t);
}

void CellInspector::updateHeader() {
  QString text;
  if (cell_ && grid_) {
    const Position c = grid_->cellCentre(*cell_);
    text =
        tr("<b>Cell (%1, %2)</b> at (%3, %4) m · %5 × %6")
            .arg(cell_->x())
            .arg(cell_->y())
            .arg(c.x(), 0, 'f', 2)
            .arg(c.y(), 0, 'f', 2)
            .arg(QString::fromStdString(settings_.model), QString::fromStdString(settings_.rule));
    if (trace_) {
      const CellValue& v = trace_->final();
      text += tr("<br>%1 of %2 readings wrote it; at the end of the log %3 = %4, p(occ) %5, "
                 "level %6")
                  .arg(QLocale().toString(static_cast<qulonglong>(trace_->steps.size())),
                       QLocale().toString(static_cast<qulonglong>(trace_->readings)),
                       QString::fromStdString(trace_->nativeName).toHtmlEscaped())
                  .arg(v.native, 0, 'g', 6)
                  .arg(v.probability, 0, 'f', 3)
                  .arg(v.level);
    }
  }
  if (!status_.isEmpty()) text += (text.isEmpty() ? QString() : QStringLiteral("<br>")) + status_;
  header_->setText(text);
}

}  // namespace sg::ui
