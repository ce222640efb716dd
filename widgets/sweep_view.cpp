// SPDX-License-Identifier: GPL-3.0-or-later
#include "sweep_view.h"

#include <QCloseEvent>
#include <QComboBox>
#include <QCoreApplication>
#include <QElapsedTimer>
#include <QEventLoop>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QItemSelectionModel>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QSplitter>
#include <QTableView>
#include <QTimer>
#include <QVBoxLayout>
#include <algorithm>
#include <stdexcept>

#include "sonargrid/base/concurrency.h"
#include "sonargrid/sweep/sweep_grid.h"
#include "sonargrid/sweep/sweep_metrics.h"
#include "sweep_view_charts.h"
#include "sweep_view_model.h"
#include "sweep_view_runner.h"

namespace sg::ui {
namespace {

QString qs(const std::string& s) {
  return QString::fromStdString(s);
}

}  // namespace

SweepView::SweepView(QWidget* parent) : QWidget(parent) {
  setObjectName(QStringLiteral("sweepView"));
  setWindowTitle(tr("Parameter Sweep"));
  runner_ = new SweepRunner(this);
  connect(runner_, &SweepRunner::setFinished, this, &SweepView::onSetFinished);
  connect(runner_, &SweepRunner::finished, this, &SweepView::onFinished);
  plotTimer_ = new QTimer(this);
  plotTimer_->setSingleShot(true);
  plotTimer_->setInterval(250);
  connect(plotTimer_, &QTimer::timeout, this, [this] {
    refreshPlots();
    refreshBest();
  });
  buildView();
}

SweepView::~SweepView() {
  // The runner (a child) cancels and joins in its destructor; stop it first so that no set
  // finishing now reaches a half-destroyed view.
  runner_->cancel();
  delete runner_;
  runner_ = nullptr;
}

void SweepView::buildView() {
  form_ = new SweepForm(this);
  connect(form_, &SweepForm::choiceEdited, this, &SweepView::choiceEdited);
  runButton_ = new QPushButton(tr("&Run Sweep"), this);
  runButton_->setObjectName(QStringLiteral("runSweep"));
  cancelButton_ = new QPushButton(tr("&Cancel"), this);
  cancelButton_->setObjectName(QStringLiteral("cancelSweep"));
  progress_ = new QProgressBar(this);
  progress_->setObjectName(QStringLiteral("sweepProgress"));
  progress_->setFormat(tr("%v / %m sets"));
  progress_->setRange(0, 1);
  progress_->setValue(0);
  status_ = new QLabel(this);
  status_->setObjectName(QStringLiteral("sweepStatus"));
  status_->setWordWrap(true);
  status_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  connect(runButton_, &QPushButton::clicked, this, [this] { run(); });
  connect(cancelButton_, &QPushButton::clicked, this, &SweepView::cancel);

  // The form, its set count beside the Run and Cancel buttons, the progress and the status.
  form_->addToCountRow(runButton_);
  form_->addToCountRow(cancelButton_);
  auto* left = new QWidget(this);
  auto* leftLayout = new QVBoxLayout(left);
  leftLayout->setContentsMargins(0, 0, 0, 0);
  leftLayout->addWidget(form_, 1);
  leftLayout->addWidget(progress_);
  leftLayout->addWidget(status_);

  model_ = new SweepResultsModel(this);
  table_ = new QTableView(this);
  table_->setObjectName(QStringLiteral("sweepResults"));
  table_->setModel(model_);
  table_->verticalHeader()->hide();
  table_->setSelectionBehavior(QAbstractItemView::SelectRows);
  table_->setSelectionMode(QAbstractItemView::ExtendedSelection);
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  connect(table_, &QTableView::doubleClicked, this,
          [this](const QModelIndex& index) { applyRow(static_cast<std::size_t>(index.row())); });

  plotColumn_ = new QComboBox(this);
  plotColumn_->setObjectName(QStringLiteral("plotMetric"));
  bestRule_ = new QComboBox(this);
  bestRule_->setObjectName(QStringLiteral("bestRule"));
  connect(plotColumn_, &QComboBox::currentIndexChanged, this, [this] {
    if (updating_) return;
    refillBestRules();
    refreshPlots();
    refreshBest();
  });
  connect(bestRule_, &QComboBox::currentIndexChanged, this, [this] {
    if (!updating_) refreshBest();
  });
  bestLabel_ = new QLabel(this);
  bestLabel_->setObjectName(QStringLiteral("bestSet"));
  bestLabel_->setWordWrap(true);
  bestLabel_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  applyBest_ = new QPushButton(tr("&Apply Best"), this);
  applyBest_->setObjectName(QStringLiteral("applyBest"));
  applyBest_->setToolTip(tr("Make the best set the document's parameters (one undo step)"));
  pinBest_ = new QPushButton(tr("Pin Best"), this);
  pinBest_->setObjectName(QStringLiteral("pinBest"));
  applySelected_ = new QPushButton(tr("Apply Selected"), this);
  applySelected_->setObjectName(QStringLiteral("applySelected"));
  pinSelected_ = new QPushButton(tr("&Pin Selected"), this);
  pinSelected_->setObjectName(QStringLiteral("pinSelected"));
  pinSelected_->setToolTip(tr("Pin the selected sets to the comparison table"));
  connect(applyBest_, &QPushButton::clicked, this, [this] { applyBest(); });
  connect(pinBest_, &QPushButton::clicked, this, [this] { pinBest(); });
  connect(applySelected_, &QPushButton::clicked, this, [this] {
    const QModelIndexList rows = table_->selectionModel()->selectedRows();
    if (!rows.isEmpty()) applyRow(static_cast<std::size_t>(rows.front().row()));
  });
  connect(pinSelected_, &QPushButton::clicked, this, [this] {
    QModelIndexList rows = table_->selectionModel()->selectedRows();
    std::sort(rows.begin(), rows.end());
    for (const QModelIndex& r : rows) pinRow(static_cast<std::size_t>(r.row()));
  });
  connect(table_->selectionModel(), &QItemSelectionModel::selectionChanged, this,
          &SweepView::updateButtons);

  auto* bestBox = new QWidget(this);
  auto* bestLayout = new QVBoxLayout(bestBox);
  bestLayout->setContentsMargins(0, 0, 0, 0);
  auto* chooseRow = new QHBoxLayout;
  auto* plotLabel = new QLabel(tr("&Metric:"), bestBox);
  plotLabel->setBuddy(plotColumn_);
  auto* ruleLabel = new QLabel(tr("&Best by:"), bestBox);
  ruleLabel->setBuddy(bestRule_);
  chooseRow->addWidget(plotLabel);
  chooseRow->addWidget(plotColumn_);
  chooseRow->addWidget(ruleLabel);
  chooseRow->addWidget(bestRule_, 1);
  bestLayout->addLayout(chooseRow);
  bestLayout->addWidget(bestLabel_);
  auto* buttonRow = new QHBoxLayout;
  buttonRow->addWidget(applyBest_);
  buttonRow->addWidget(pinBest_);
  buttonRow->addStretch(1);
  buttonRow->addWidget(applySelected_);
  buttonRow->addWidget(pinSelected_);
  bestLayout->addLayout(buttonRow);

  charts_ = new SweepCharts(this);
  charts_->setObjectName(QStringLiteral("sweepCharts"));

  auto* resultsHost = new QWidget(this);
  auto* resultsLayout = new QVBoxLayout(resultsHost);
  resultsLayout->setContentsMargins(0, 0, 0, 0);
  resultsLayout->addWidget(table_, 1);
  resultsLayout->addWidget(bestBox);

  auto* right = new QSplitter(Qt::Vertical, this);
  right->addWidget(resultsHost);
  right->addWidget(charts_);
  right->setStretchFactor(0, 2);
  right->setStretchFactor(1, 3);
  auto* split = new QSplitter(Qt::Horizontal, this);
  split->addWidget(left);
  split->addWidget(right);
  split->setStretchFactor(0, 2);
  split->setStretchFactor(1, 3);
  auto* layout = new QVBoxLayout(this);
  layout->addWidget(split);
  updateButtons();
}

void SweepView::setInputs(SweepInputs inputs) {
  inputs_ = std::move(inputs);
  form_->setInputs(inputs_);
  updateButtons();
}

void SweepView::setChoice(const SweepChoice& choice) {
  form_->setChoice(choice);
}

SweepChoice SweepView::choice() const {
  return form_->choice();
}

std::shared_ptr<SweepJob> SweepView::makeJob() const {
  if (!inputs_.run) throw std::invalid_argument(tr("Open a log first.").toStdString());
  const ParameterSet& base = inputs_.settings.parameters;
  const SweepChoice choice = form_->choice();
  auto job = std::make_shared<SweepJob>();
  job->run = inputs_.run;
  std::vector<std::string> metrics = choice.metrics;
  // IOP prefers sparse maps (a map of a few sure cells scores well): the table shows the recall
  // of the occupied cells beside it, so that a nearly empty "best" map shows as one (issue 49).
  if (std::find(metrics.begin(), metrics.end(), "iop") != metrics.end())
    metrics.push_back("recall");
  job->metrics = parseSweepMetrics(metrics);
  if (job->metrics.empty())
    throw std::invalid_argument(tr("Choose at least one metric.").toStdString());
  const SetMeasures measures = measuresOf(job->metrics);
  if (!measures.reference.empty()) {
    if (!inputs_.reference)
      throw std::invalid_argument(tr("The reference metrics need a reference map.").toStdString());
    job->reference = inputs_.reference;
  }
  std::vector<SweepAxis> axes;
  for (const std::string& axis : choice.axes)
    if (base.has(splitAxis(axis).first)) axes.push_back(parseSweepAxis(axis, base));
  if (axes.empty()) throw std::invalid_argument(tr("Tick a parameter to sweep.").toStdString());
  std::vector<SweepTie> ties;
  for (const std::string& t : choice.ties) ties.push_back(parseSweepTie(t, base));
  std::size_t n = 1;
  for (const SweepAxis& a : axes) {
    n *= a.values.size();
    if (n > kMaxViewSets)
      throw std::invalid_argument(tr("More than %1 sets: sweep them with sonargrid-cli sweep "
                                     "--shard (docs/sweeps.md).")
                                      .arg(kMaxViewSets)
                                      .toStdString());
  }
  job->sets = sweepSets(base, axes, ties);
  job->settings.model = inputs_.settings.model;
  job->settings.rule = inputs_.settings.rule;
  job->settings.pose = inputs_.settings.pose;
  job->settings.grid = inputs_.run->fittingGrid(inputs_.settings.pose, inputs_.cellSize);
  if (measures.twoRun) {
    if (!inputs_.secondRun)
      throw std::invalid_argument(
          tr("two-run needs a second log of the same route.").toStdString());
    job->secondRun = inputs_.secondRun;
    // One grid over both runs, as `sonargrid-cli sweep --second-log` makes it.
    job->settings.grid =
        gridOverRuns(job->settings.grid,
                     inputs_.secondRun->fittingGrid(inputs_.settings.pose, inputs_.cellSize));
  }
  return job;
}

bool SweepView::run() {
  if (isRunning()) return false;
  std::shared_ptr<SweepJob> job;
  try {
    job = makeJob();
  } catch (const std::exception& e) {
    setStatus(QString::fromUtf8(e.what()), true);
    return false;
  }
  job_ = job;
  const SweepChoice choice = form_->choice();
  sweptParameters_.clear();
  shownParameters_.clear();
  for (const std::string& axis : choice.axes) {
    const std::string p = splitAxis(axis).first;
    if (inputs_.settings.parameters.has(p)) sweptParameters_.push_back(p);
  }
  shownParameters_ = sweptParameters_;
  for (const std::string& t : choice.ties)
    shownParameters_.push_back(parseSweepTie(t, inputs_.settings.parameters).parameter);
  model_->reset(job->sets, shownParameters_, metricColumns(job->metrics));
  {
    updating_ = true;
    const QString previous = plotColumn_->currentText();
    plotColumn_->clear();
    for (const std::string& c : model_->columns()) plotColumn_->addItem(qs(c));
    const int keep = plotColumn_->findText(previous);
    plotColumn_->setCurrentIndex(keep >= 0 ? keep : 0);
    updating_ = false;
  }
  refillBestRules();
  charts_->clear();
  bestLabel_->clear();
  progress_->setRange(0, static_cast<int>(job->sets.size()));
  progress_->setValue(0);
  running_ = runner_->start(job);
  setStatus(tr("Sweeping %1 on %2 threads…").arg(setsText(job->sets.size())).arg(threadCount()));
  updateButtons();
  return running_;
}

void SweepView::cancel() {
  if (!isRunning()) return;
  runner_->cancel();
  setStatus(tr("Cancelling…"));
}

bool SweepView::isRunning() const {
  return running_;
}

bool SweepView::waitForSweep(int timeoutMs) {
  QElapsedTimer t;
  t.start();
  while (running_) {
    if (t.elapsed() > timeoutMs) return false;
    QCoreApplication::processEvents(QEventLoop::AllEvents, 20);
  }
  return true;
}

QString SweepView::statusText() const {
  return status_->text();
}

void SweepView::setStatus(const QString& text, bool error) {
  status_->setText(text);
  status_->setStyleSheet(error ? QStringLiteral("color: #b00020") : QString());
}

void SweepView::onSetFinished(std::size_t index, const std::vector<std::optional<double>>& values) {
  model_->setResult(index, values);
  progress_->setValue(static_cast<int>(model_->finishedCount()));
  if (!plotTimer_->isActive()) plotTimer_->start();
}

void SweepView::onFinished(bool completed, const QString& error) {
  running_ = false;
  plotTimer_->stop();
  const auto done = static_cast<int>(model_->finishedCount());
  const auto total = static_cast<int>(model_->sets().size());
  if (!error.isEmpty())
    setStatus(tr("The sweep stopped after %1 of %2 sets: %3").arg(done).arg(total).arg(error),
              true);
  else if (completed)
    setStatus(tr("Swept %1.").arg(setsText(static_cast<std::size_t>(total))));
  else
    setStatus(tr("Cancelled after %1 of %2 sets; the table holds the finished ones.")
                  .arg(done)
                  .arg(total));
  refreshPlots();
  refreshBest();
  updateButtons();
  emit sweepFinished(completed);
}

void SweepView::closeEvent(QCloseEvent* event) {
  // A sweep nobody watches is stopped; its finished sets stay in the table.
  cancel();
  QWidget::closeEvent(event);
}

int SweepView::plotColumn() const {
  const int i = plotColumn_->currentIndex();
  return i >= 0 && static_cast<std::size_t>(i) < model_->columns().size() ? i : -1;
}

bool SweepView::setPlotColumn(const QString& column) {
  const int i = plotColumn_->findText(column);
  if (i < 0) return false;
  plotColumn_->setCurrentIndex(i);
  return true;
}

bool SweepView::setBestRule(BestRule rule) {
  const int i = bestRule_->findData(static_cast<int>(rule));
  if (i < 0) return false;
  bestRule_->setCurrentIndex(i);
  return true;
}

void SweepView::refillBestRules() {
  updating_ = true;
  const QVariant previous = bestRule_->currentData();
  bestRule_->clear();
  const int c = plotColumn();
  if (c >= 0 && model_->columns()[static_cast<std::size_t>(c)] == "vsdns") {
    bestRule_->addItem(tr("lowest histogram bin, averaged (paper 002)"),
                       static_cast<int>(BestRule::LowestBin));
    bestRule_->addItem(tr("minimum VSDNS (paper 002)"), static_cast<int>(BestRule::Minimum));
    bestRule_->addItem(tr("nearest the mean VSDNS (paper 002)"),
                       static_cast<int>(BestRule::NearestMean));
  } else if (c >= 0) {
    const bool higher = betterDirection(model_->columns()[static_cast<std::size_t>(c)]) > 0;
    bestRule_->addItem(higher ? tr("largest value") : tr("smallest value"),
                       static_cast<int>(BestRule::BestValue));
  }
  const int keep = bestRule_->findData(previous);
  bestRule_->setCurrentIndex(keep >= 0 ? keep : 0);
  updating_ = false;
}

std::optional<OptimalSet> SweepView::best(QString* why) const {
  // Called from slots and the plot timer: nothing may leave it (an exception through the event
  // loop ends the app). What the rule could not choose is said in the best label instead.
  try {
    return chooseBest();
  } catch (const std::exception& e) {
    if (why) *why = QString::fromUtf8(e.what());
    return std::nullopt;
  }
}

std::optional<OptimalSet> SweepView::chooseBest() const {
  const int c = plotColumn();
  if (c < 0 || !job_) return std::nullopt;
  const std::vector<std::optional<double>> values =
      model_->columnValues(static_cast<std::size_t>(c));
  if (std::none_of(values.begin(), values.end(), [](const auto& v) { return v.has_value(); }))
    return std::nullopt;
  // A metric that is the same for every set cannot tell them apart (VSDNS of HIMM's two
  // constant model values, say): said as such, not a "best" set.
  // (Only once two sets have a value: a sweep under way with one finished set says nothing.)
  const auto first =
      std::find_if(values.begin(), values.end(), [](const auto& v) { return v.has_value(); });
  const auto defined =
      std::count_if(values.begin(), values.end(), [](const auto& v) { return v.has_value(); });
  if (defined > 1 &&
      std::all_of(values.begin(), values.end(), [&](const auto& v) { return !v || *v == **first; }))
    throw std::invalid_argument(tr("%1 is the same for every set (%2): it cannot tell them apart")
                                    .arg(plotColumn_->currentText())
                                    .arg(**first, 0, 'g', 6)
                                    .toStdString());
  const auto rule = static_cast<BestRule>(bestRule_->currentData().toInt());
  switch (rule) {
    case BestRule::LowestBin:
      return lowestBinAverage(values, job_->sets);
    case BestRule::Minimum:
      return minimumVsdns(values, job_->sets);
    case BestRule::NearestMean:
      return nearestMeanVsdns(values, job_->sets);
    case BestRule::BestValue:
      break;
  }
  const int direction = betterDirection(model_->columns()[static_cast<std::size_t>(c)]);
  std::optional<std::size_t> at;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!values[i]) continue;
    // Ties go to the earliest set (as optimal_sets.h).
    if (!at || direction * (*values[i] - *values[*at]) > 0) at = i;
  }
  OptimalSet o;
  o.parameters = job_->sets[*at];
  o.members = {*at};
  o.criterion = *values[*at];
  return o;
}

QString SweepView::describe(const ParameterSet& set) const {
  QStringList parts;
  for (const std::string& p : shownParameters_)
    parts << QStringLiteral("%1=%2").arg(qs(p), qs(shortestText(set.get(p))));
  return parts.join(QStringLiteral(", "));
}

MapperSettings SweepView::settingsOf(const ParameterSet& set) const {
  MapperSettings s;
  s.model = job_->settings.model;
  s.rule = job_->settings.rule;
  s.pose = job_->settings.pose;
  s.parameters = set;
  return s;
}

void SweepView::refreshBest() {
  QString why;
  const std::optional<OptimalSet> b = best(&why);
  if (!b) {
    bestLabel_->setText(!job_           ? QString()
                        : why.isEmpty() ? tr("No set has a value of this metric yet.")
                                        : tr("Cannot choose a best set: %1").arg(why));
  } else {
    const QString members =
        b->members.size() == 1
            ? tr("set %1").arg(b->members.front())
            : tr("average of the %1 of the lowest bin").arg(setsText(b->members.size()));
    bestLabel_->setText(tr("Best: %1 (%2; %3 = %4)")
                            .arg(describe(b->parameters), members, plotColumn_->currentText())
                            .arg(b->criterion, 0, 'g', 6));
  }
  updateButtons();
}

void SweepView::refreshPlots() {
  const int c = plotColumn();
  if (c < 0 || !job_) {
    charts_->clear();
    return;
  }
  charts_->plot(job_->sets, sweptParameters_, plotColumn_->currentText(),
                model_->columnValues(static_cast<std::size_t>(c)), kPaper002HistogramBins);
}

bool SweepView::applyBest() {
  const std::optional<OptimalSet> b = best();
  if (!b) return false;
  emit applyRequested(
      settingsOf(b->parameters),
      tr("Sweep best (%1): %2").arg(bestRule_->currentText(), describe(b->parameters)));
  return true;
}

bool SweepView::pinBest() {
  const std::optional<OptimalSet> b = best();
  if (!b) return false;
  emit pinRequested(settingsOf(b->parameters), tr("sweep best: %1").arg(describe(b->parameters)));
  return true;
}

bool SweepView::applyRow(std::size_t index) {
  if (!job_ || index >= job_->sets.size()) return false;
  emit applyRequested(settingsOf(job_->sets[index]),
                      tr("Sweep set %1: %2").arg(index).arg(describe(job_->sets[index])));
  return true;
}

bool SweepView::pinRow(std::size_t index) {
  if (!job_ || index >= job_->sets.size()) return false;
  emit pinRequested(settingsOf(job_->sets[index]),
                    tr("sweep set %1: %2").arg(index).arg(describe(job_->sets[index])));
  return true;
}

void SweepView::updateButtons() {
  const bool running = isRunning();
  runButton_->setEnabled(!running && inputs_.run != nullptr);
  cancelButton_->setEnabled(running);
  const bool hasBest = !bestLabel_->text().isEmpty() && best().has_value();
  applyBest_->setEnabled(hasBest);
  pinBest_->setEnabled(hasBest);
  const bool selected = job_ && table_->selectionModel()->hasSelection();
  applySelected_->setEnabled(selected);
  pinSelected_->setEnabled(selected);
}

}  // namespace sg::ui
