// SPDX-License-Identifier: GPL-3.0-or-later
#include "metrics_panel.h"

#include <QCoreApplication>
#include <QElapsedTimer>
#include <QHeaderView>
#include <QLabel>
#include <QTableWidget>
#include <QVBoxLayout>
#include <utility>

namespace sg::ui {

bool MetricsPanel::GoodnessKey::operator==(const GoodnessKey& o) const {
  return run == o.run && secondRun == o.secondRun && settings.model == o.settings.model &&
         settings.rule == o.settings.rule && settings.pose == o.settings.pose &&
         settings.parameters == o.settings.parameters && cellSize == o.cellSize &&
         goodness == o.goodness;
}

MetricsPanel::MetricsPanel(QWidget* parent)
    : QWidget(parent), status_(new QLabel(this)), table_(new QTableWidget(this)) {
  setObjectName(QStringLiteral("metricsPanel"));
  // One computation at a time: a stale one is cancelled, not raced by its successor.
  settle_.setSingleShot(true);
  settle_.setInterval(kSettleMs);
  connect(&settle_, &QTimer::timeout, this, &MetricsPanel::start);
  status_->setWordWrap(true);
  status_->setObjectName(QStringLiteral("metricsStatus"));
  status_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  table_->setObjectName(QStringLiteral("metricsTable"));
  table_->setColumnCount(3);
  table_->setHorizontalHeaderLabels({tr("Metric"), tr("Value"), tr("Unit")});
  table_->verticalHeader()->setVisible(false);
  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  table_->setSelectionBehavior(QAbstractItemView::SelectRows);
  table_->horizontalHeader()->setSectionResizeMode(0, QHeaderView::Stretch);
  table_->horizontalHeader()->setSectionResizeMode(1, QHeaderView::ResizeToContents);
  table_->horizontalHeader()->setSectionResizeMode(2, QHeaderView::ResizeToContents);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(6, 6, 6, 6);
  layout->addWidget(status_);
  layout->addWidget(table_, 1);
  fill();
}

MetricsPanel::~MetricsPanel() = default;

void MetricsPanel::setMap(std::shared_ptr<const OccupancyMap> map) {
  input_.map = std::move(map);
  if (std::exchange(awaitingMap_, false) && !atOnce_) {
    pending_ = true;
    settle_.start();
    return;
  }
  schedule();
}

void MetricsPanel::scoreAtOnce() {
  atOnce_ = true;
  endSettle();
}

void MetricsPanel::endSettle() {
  if (!settle_.isActive()) return;
  settle_.stop();
  start();
}

void MetricsPanel::awaitMap() {
  awaitingMap_ = true;
  atOnce_ = false;
  if (settle_.isActive()) {
    settle_.stop();
    pending_ = false;
  }
  jobs_.cancel();
  status_->setText(tr("Waiting for the new map…"));
}

void MetricsPanel::resume() {
  if (!awaitingMap_) return;
  awaitingMap_ = false;
  schedule();
}

void MetricsPanel::setReference(std::shared_ptr<const ReferenceMap> reference) {
  input_.reference = std::move(reference);
  schedule();
}

void MetricsPanel::setRuns(std::shared_ptr<const Dataset> run,
                           std::shared_ptr<const Dataset> secondRun, const MapperSettings& settings,
                           double cellSize) {
  input_.run = std::move(run);
  input_.secondRun = std::move(secondRun);
  input_.settings = settings;
  input_.cellSize = cellSize;
  schedule();
}

void MetricsPanel::setScoreOptions(const ScoreOptions& options) {
  input_.score = options;
  schedule();
}

void MetricsPanel::schedule() {
  if (pending_) return;
  pending_ = true;
  QTimer::singleShot(0, this, &MetricsPanel::start);
}

void MetricsPanel::start() {
  if (settle_.isActive()) return;  // its timeout starts the computation, with the newest inputs
  pending_ = false;
  if (awaitingMap_) return;  // setMap() or resume() schedules again
  const quint64 generation = jobs_.renew();
  MetricsInput input = input_;
  // Paper 002's goodness is for maps without a reference; the two-run comparison whenever a second
  // run is loaded.
  input.goodness = !input.reference;
  if (!input.map) {
    show(generation, MetricsResult{});
    return;
  }
  const GoodnessKey key{input.run, input.secondRun, input.settings, input.cellSize, input.goodness};
  std::optional<SetEvaluation> known;
  if (goodnessKey_ && *goodnessKey_ == key && goodness_) {
    known = goodness_;
    input.goodness = false;
    input.secondRun = nullptr;
  }
  status_->setText(tr("Computing…"));
  jobs_.run<std::optional<MetricsResult>>(
      [known, input = std::move(input)](const std::atomic<bool>* cancel) {
        std::optional<MetricsResult> result = computeMetrics(input, cancel);
        if (result && known) result->goodness = known;
        return result;
      },
      [this, key](JobOutcome<std::optional<MetricsResult>> outcome) {
        std::optional<MetricsResult> result;
        if (outcome.value) {
          result = std::move(*outcome.value);
        } else if (!outcome.skipped) {
          result = MetricsResult{};
          result->scoreError = outcome.error;
        }
        if (result && result->goodness) {
          goodnessKey_ = key;
          goodness_ = result->goodness;
        }
        show(outcome.generation, result);
      });
}

void MetricsPanel::show(quint64 generation, const std::optional<MetricsResult>& result) {
  // A superseded computation (cancelled or finished late) is never shown.
  if (generation != jobs_.generation() || !result) return;
  result_ = result;
  shownGeneration_ = generation;
  fill();
  emit dminTintChanged(result_->dminTint, result_->spec);
  emit updated();
}

bool MetricsPanel::waitForResult(int timeoutMs) {
  QElapsedTimer clock;
  clock.start();
  while ((busy() || shownGeneration_ != jobs_.generation()) && clock.elapsed() < timeoutMs)
    QCoreApplication::processEvents(QEventLoop::AllEvents, 20);
  return !busy() && shownGeneration_ == jobs_.generation();
}

void MetricsPanel::fill() {
  table_->setRowCount(0);
  const MetricsResult* r = result();
  QStringList notes;
  auto section = [this](const QString& title) {
    const int row = table_->rowCount();
    table_->insertRow(row);
    auto* item = new QTableWidgetItem(title);
    QFont bold = item->font();
    bold.setBold(true);
    item->setFont(bold);
    item->setFlags(Qt::ItemIsEnabled);
    table_->setItem(row, 0, item);
    table_->setSpan(row, 0, 1, 3);
  };
  auto add = [this, r](const MetricInfo& info) {
    const int row = table_->rowCount();
    table_->insertRow(row);
    auto* name = new QTableWidgetItem(info.label);
    auto* value = new QTableWidgetItem(formatValue(r->value(info.key), info.precision));
    auto* unit = new QTableWidgetItem(info.unit);
    value->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
    value->setData(Qt::UserRole, QString::fromLatin1(info.key));
    const QString tip =
        QStringLiteral("%1 (%2)\n%3").arg(info.label, QString::fromLatin1(info.key), info.source);
    for (QTableWidgetItem* item : {name, value, unit}) item->setToolTip(tip);
    table_->setItem(row, 0, name);
    table_->setItem(row, 1, value);
    table_->setItem(row, 2, unit);
  };
  if (!r || (!input_.map && !r->score && !r->goodness)) {
    status_->setText(input_.map ? tr("Computing…")
                                : tr("No map yet: open a log (Ctrl+O) to see its metrics."));
    return;
  }
  if (r->score) {
    section(tr("Against the reference"));
    for (const MetricInfo& info : referenceMetricInfo()) add(info);
  } else if (!r->scoreError.isEmpty()) {
    notes << tr("Not scored: %1").arg(r->scoreError);
  } else if (!input_.reference) {
    notes << tr(
        "No reference map: open one (File ▸ Open Reference) or draw one (Edit ▸ "
        "Reference Edit Mode) to see IOP and the other metrics of the reference.");
  }
  if (r->goodness) {
    section(r->goodness->vsdns ? tr("Goodness without a reference") : tr("Two runs"));
    for (const MetricInfo& info : goodnessMetricInfo())
      if (r->value(info.key) || (r->goodness->vsdns && !QByteArray(info.key).startsWith("two_")))
        add(info);
    if (!r->goodness->twoRun) notes << tr("Load a second run of the same route to compare runs.");
  } else if (!r->goodnessError.isEmpty()) {
    notes << tr("Goodness not computed: %1").arg(r->goodnessError);
  }
  QString head;
  if (r->score || r->goodness)
    head = tr("%1 × %2 cells of %3 m; computed in %4 ms.")
               .arg(r->spec.width)
               .arg(r->spec.height)
               .arg(r->spec.cellSize)
               .arg(r->elapsedMs, 0, 'f', 0);
  notes.prepend(head);
  notes.removeAll(QString());
  status_->setText(notes.join(QLatin1Char('\n')));
}

}  // namespace sg::ui
