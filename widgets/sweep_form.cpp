// SPDX-License-Identifier: GPL-3.0-or-later
#include "sweep_form.h"

#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QRegularExpression>
#include <QTableWidget>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>
#include <set>

#include "sonargrid/base/concurrency.h"
#include "sonargrid/sweep/sweep_grid.h"
#include "sonargrid/sweep/sweep_metrics.h"

namespace sg::ui {
namespace {

enum ParameterColumn { kSweepColumn, kUnitColumn, kRangeColumn, kBaseColumn, kValuesColumn };

QString qs(const std::string& s) {
  return QString::fromStdString(s);
}

// Four values spread over the declared range, a start the user edits.
std::string suggestedValues(const ParameterSpec& spec) {
  std::vector<double> values;
  for (int k = 0; k < 4; ++k) {
    double v = spec.min + (spec.max - spec.min) * k / 3.0;
    if (spec.integer) {
      v = std::round(v);
    } else if (v != 0.0) {
      const double scale = std::pow(10.0, 2.0 - std::floor(std::log10(std::abs(v))));
      v = std::clamp(std::round(v * scale) / scale, spec.min, spec.max);
    }
    if (std::find(values.begin(), values.end(), v) == values.end()) values.push_back(v);
  }
  std::string out;
  for (double v : values) out += (out.empty() ? "" : ",") + shortestText(v);
  return out;
}

std::vector<std::string> splitTies(const QString& text) {
  std::vector<std::string> out;
  for (const QString& part :
       text.split(QRegularExpression(QStringLiteral("[;,]")), Qt::SkipEmptyParts)) {
    const QString t = part.trimmed();
    if (!t.isEmpty()) out.push_back(t.toStdString());
  }
  return out;
}

}  // namespace

std::pair<std::string, std::string> splitAxis(const std::string& axis) {
  const auto eq = axis.find('=');
  if (eq == std::string::npos) return {axis, {}};
  return {axis.substr(0, eq), axis.substr(eq + 1)};
}

QString setsText(std::size_t n) {
  return n == 1 ? SweepForm::tr("1 set") : SweepForm::tr("%1 sets").arg(n);
}

SweepForm::SweepForm(QWidget* parent) : QWidget(parent) {
  header_ = new QLabel(this);
  header_->setObjectName(QStringLiteral("sweepHeader"));
  header_->setWordWrap(true);

  parameters_ = new QTableWidget(0, 5, this);
  parameters_->setObjectName(QStringLiteral("sweepParameters"));
  parameters_->setHorizontalHeaderLabels(
      {tr("Sweep"), tr("Unit"), tr("Range"), tr("Now"), tr("Values (a:step:b or v1,v2,…)")});
  parameters_->verticalHeader()->hide();
  parameters_->horizontalHeader()->setStretchLastSection(true);
  parameters_->setSelectionMode(QAbstractItemView::NoSelection);
  parameters_->setToolTip(
      tr("Tick the parameters to sweep and give their values; the first ticked row is the "
         "outermost loop"));
  connect(parameters_, &QTableWidget::itemChanged, this, [this] {
    if (!updating_) readForm();
  });

  ties_ = new QLineEdit(this);
  ties_->setObjectName(QStringLiteral("sweepTies"));
  ties_->setPlaceholderText(tr("e.g. p1=1-p4; several separated by ;"));
  ties_->setToolTip(tr("Parameters set from others for every set: C, P, C-P, C+P or C*P"));
  connect(ties_, &QLineEdit::editingFinished, this, [this] {
    if (!updating_) readForm();
  });

  metrics_ = new QListWidget(this);
  metrics_->setObjectName(QStringLiteral("sweepMetrics"));
  metrics_->setMaximumHeight(120);
  for (const std::string& m : allSweepMetrics()) {
    auto* item = new QListWidgetItem(qs(m), metrics_);
    item->setData(Qt::UserRole, qs(m));
    item->setFlags(Qt::ItemIsUserCheckable | Qt::ItemIsEnabled);
    item->setCheckState(Qt::Unchecked);
  }
  metrics_->setFlow(QListView::LeftToRight);
  metrics_->setWrapping(true);
  metrics_->setResizeMode(QListView::Adjust);
  connect(metrics_, &QListWidget::itemChanged, this, [this] {
    if (!updating_) readForm();
  });

  setCount_ = new QLabel(this);
  setCount_->setObjectName(QStringLiteral("sweepSetCount"));

  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(header_);
  layout->addWidget(new QLabel(tr("Parameters (declared by the model and the rule):"), this));
  layout->addWidget(parameters_, 1);
  auto* tieLabel = new QLabel(tr("&Ties:"), this);
  tieLabel->setBuddy(ties_);
  auto* tieRow = new QHBoxLayout;
  tieRow->addWidget(tieLabel);
  tieRow->addWidget(ties_, 1);
  layout->addLayout(tieRow);
  layout->addWidget(new QLabel(tr("Metrics:"), this));
  layout->addWidget(metrics_);
  countRow_ = new QHBoxLayout;
  countRow_->addWidget(setCount_);
  countRow_->addStretch(1);
  layout->addLayout(countRow_);

  choice_.metrics = {"vsdns"};
  showChoice();
}

void SweepForm::addToCountRow(QWidget* widget) {
  countRow_->addWidget(widget);
}

void SweepForm::setInputs(const SweepInputs& inputs) {
  const bool specsChanged = inputs.settings.model != inputs_.settings.model ||
                            inputs.settings.rule != inputs_.settings.rule ||
                            parameters_->rowCount() == 0;
  inputs_ = inputs;
  header_->setText(
      tr("<b>%1 × %2</b>, pose %3, cell %4 m, log %5; %6 threads")
          .arg(qs(inputs_.settings.model), qs(inputs_.settings.rule),
               inputs_.settings.pose == PoseSource::Truth ? tr("truth") : tr("odometry"),
               QString::number(inputs_.cellSize),
               inputs_.logName.isEmpty() ? tr("(none)") : inputs_.logName.toHtmlEscaped())
          .arg(threadCount()));
  if (specsChanged) {
    rebuildParameterRows();
  } else {
    // The base values shown follow the document's.
    const QSignalBlocker block(parameters_);
    for (int r = 0; r < parameters_->rowCount(); ++r) {
      const std::string name =
          parameters_->item(r, kSweepColumn)->data(Qt::UserRole).toString().toStdString();
      if (inputs_.settings.parameters.has(name))
        parameters_->item(r, kBaseColumn)
            ->setText(qs(shortestText(inputs_.settings.parameters.get(name))));
    }
  }
  // Metrics that need what the document lacks are shown but cannot be chosen.
  const QSignalBlocker block(metrics_);
  for (int i = 0; i < metrics_->count(); ++i) {
    QListWidgetItem* item = metrics_->item(i);
    const std::string m = item->data(Qt::UserRole).toString().toStdString();
    QString why;
    if (isReferenceMetric(m) && !inputs_.reference) why = tr("needs a reference map");
    if (m == "two-run" && !inputs_.secondRun) why = tr("needs a second log of the same route");
    item->setFlags(why.isEmpty() ? (Qt::ItemIsUserCheckable | Qt::ItemIsEnabled)
                                 : Qt::ItemIsUserCheckable);
    item->setToolTip(why);
  }
  updateSetCount();
}

void SweepForm::rebuildParameterRows() {
  updating_ = true;
  const QSignalBlocker block(parameters_);
  parameters_->setRowCount(0);
  for (const ParameterSpec& spec : inputs_.settings.parameters.specs()) {
    const int r = parameters_->rowCount();
    parameters_->insertRow(r);
    const QString label = spec.symbol.empty() || spec.symbol == spec.name
                              ? qs(spec.name)
                              : QStringLiteral("%1 (%2)").arg(qs(spec.symbol), qs(spec.name));
    auto* check = new QTableWidgetItem(label);
    check->setFlags(Qt::ItemIsUserCheckable | Qt::ItemIsEnabled);
    check->setCheckState(Qt::Unchecked);
    check->setData(Qt::UserRole, qs(spec.name));
    check->setToolTip(qs(spec.description + (spec.source.empty() ? "" : " (" + spec.source + ")")));
    auto fixed = [](const QString& text) {
      auto* item = new QTableWidgetItem(text);
      item->setFlags(Qt::ItemIsEnabled);
      return item;
    };
    parameters_->setItem(r, kSweepColumn, check);
    parameters_->setItem(r, kUnitColumn, fixed(qs(spec.unit)));
    parameters_->setItem(r, kRangeColumn,
                         fixed(QStringLiteral("%1 … %2").arg(qs(shortestText(spec.min)),
                                                             qs(shortestText(spec.max)))));
    parameters_->setItem(r, kBaseColumn,
                         fixed(qs(shortestText(inputs_.settings.parameters.get(spec.name)))));
    auto* values = new QTableWidgetItem(qs(suggestedValues(spec)));
    values->setFlags(Qt::ItemIsEnabled | Qt::ItemIsEditable);
    parameters_->setItem(r, kValuesColumn, values);
  }
  parameters_->resizeColumnsToContents();
  updating_ = false;
  showChoice();
}

void SweepForm::setChoice(const SweepChoice& choice) {
  if (choice == choice_) return;
  choice_ = choice;
  showChoice();
}

void SweepForm::showChoice() {
  updating_ = true;
  {
    const QSignalBlocker block(parameters_);
    for (int r = 0; r < parameters_->rowCount(); ++r) {
      const std::string name =
          parameters_->item(r, kSweepColumn)->data(Qt::UserRole).toString().toStdString();
      bool swept = false;
      for (const std::string& axis : choice_.axes) {
        const auto [p, values] = splitAxis(axis);
        if (p != name) continue;
        swept = true;
        parameters_->item(r, kValuesColumn)->setText(qs(values));
      }
      parameters_->item(r, kSweepColumn)->setCheckState(swept ? Qt::Checked : Qt::Unchecked);
    }
  }
  QStringList ties;
  for (const std::string& t : choice_.ties) ties << qs(t);
  ties_->setText(ties.join(QStringLiteral("; ")));
  {
    const QSignalBlocker block(metrics_);
    for (int i = 0; i < metrics_->count(); ++i) {
      QListWidgetItem* item = metrics_->item(i);
      const std::string m = item->data(Qt::UserRole).toString().toStdString();
      const bool on =
          std::find(choice_.metrics.begin(), choice_.metrics.end(), m) != choice_.metrics.end();
      item->setCheckState(on ? Qt::Checked : Qt::Unchecked);
    }
  }
  updating_ = false;
  updateSetCount();
}

void SweepForm::readForm() {
  SweepChoice c;
  std::set<std::string> here;
  for (int r = 0; r < parameters_->rowCount(); ++r) {
    const std::string name =
        parameters_->item(r, kSweepColumn)->data(Qt::UserRole).toString().toStdString();
    here.insert(name);
    if (parameters_->item(r, kSweepColumn)->checkState() == Qt::Checked)
      c.axes.push_back(name + "=" +
                       parameters_->item(r, kValuesColumn)->text().trimmed().toStdString());
  }
  // Axes of parameters another model declares stay in the choice (for when it comes back).
  for (const std::string& axis : choice_.axes)
    if (!here.count(splitAxis(axis).first)) c.axes.push_back(axis);
  c.ties = splitTies(ties_->text());
  for (int i = 0; i < metrics_->count(); ++i)
    if (metrics_->item(i)->checkState() == Qt::Checked)
      c.metrics.push_back(metrics_->item(i)->data(Qt::UserRole).toString().toStdString());
  updateSetCount();
  if (c == choice_) return;
  choice_ = std::move(c);
  updateSetCount();
  emit choiceEdited(choice_);
}

void SweepForm::updateSetCount() {
  const ParameterSet& base = inputs_.settings.parameters;
  try {
    std::size_t n = 1;
    for (const std::string& axis : choice_.axes) {
      if (!base.has(splitAxis(axis).first)) continue;
      n *= parseSweepAxis(axis, base).values.size();
      if (n > kMaxSets) break;
    }
    for (const std::string& t : choice_.ties) parseSweepTie(t, base);
    setCount_->setText(n > kMaxSets ? tr("more than %1 sets").arg(kMaxSets) : setsText(n));
    setCount_->setStyleSheet(n > kMaxSets ? QStringLiteral("color: #b00020") : QString());
    setCount_->setToolTip({});
  } catch (const std::exception& e) {
    setCount_->setText(tr("cannot sweep"));
    setCount_->setStyleSheet(QStringLiteral("color: #b00020"));
    setCount_->setToolTip(QString::fromUtf8(e.what()));
  }
}

}  // namespace sg::ui
