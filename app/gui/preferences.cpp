// SPDX-License-Identifier: GPL-3.0-or-later
#include "preferences.h"
#include <QCheckBox>

#include <QDialogButtonBox>
#include <QFormLayout>
#include <QLabel>
#include <QSpinBox>
#include <QVBoxLayout>

#include "sonargrid/base/concurrency.h"

namespace sg::app {

unsigned applyMappingThreads() {
  const int stored = preferences::kMappingThreads.value();
  const bool valid = stored >= 0 && stored <= static_cast<int>(kMaxThreads);
  setThreadCount(valid ? static_cast<unsigned>(stored) : 0u);
  return threadCount();
}

QString automaticThreadsDescription() {
  try {
    if (const std::optional<unsigned> n = environmentThreadCount()) {
      return PreferencesDialog::tr("%1, from the environment variable %2")
          .arg(*n)
          .arg(QString::fromLatin1(kThreadsVariable));
    }
    return PreferencesDialog::tr("%1, the CPUs this process may use").arg(affinityThreadCount());
  } catch (const ThreadCountError& e) {
    return PreferencesDialog::tr("%1, the CPUs this process may use (%2 is ignored: %3)")
        .arg(affinityThreadCount())
        .arg(QString::fromLatin1(kThreadsVariable), QString::fromUtf8(e.what()));
  }
}

PreferencesDialog::PreferencesDialog(QWidget* parent) : QDialog(parent) {
  setWindowTitle(tr("Preferences"));
  threads_ = new QSpinBox(this);
  threads_->setRange(0, static_cast<int>(kMaxThreads));
  threads_->setSpecialValueText(tr("Automatic (%1)").arg(automaticThreadCount()));
  threads_->setValue(preferences::kMappingThreads.value());
  threads_->setToolTip(
      tr("How many threads a re-map, the snapshot and the cone tables use. The map is the same "
         "whatever the number; only its speed changes."));
  auto* automatic = new QLabel(tr("Automatic: %1.").arg(automaticThreadsDescription()), this);
  automatic->setWordWrap(true);
  automatic->setObjectName(QStringLiteral("automaticThreads"));

  fast_ = new QCheckBox(tr("&Fast engine: Bayes cells in 4 bytes"), this);
  fast_->setChecked(preferences::kFastEngine.value());
  fast_->setToolTip(
      tr("A cone model's Bayes cells (bayes, bayes-recursive) take four bytes instead of eight, "
         "within a tested tolerance of the exact engine (docs/models.md, \"Exact and fast "
         "engines\"); every other pair maps the same. Not yet faster: off by default."));

  auto* form = new QFormLayout;
  form->addRow(tr("Mapping &threads:"), threads_);
  form->addRow(QString(), automatic);
  form->addRow(tr("Engine:"), fast_);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, this);
  connect(buttons, &QDialogButtonBox::accepted, this, &QDialog::accept);
  connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
  auto* layout = new QVBoxLayout(this);
  layout->addLayout(form);
  layout->addWidget(buttons);
}

void PreferencesDialog::accept() {
  preferences::kMappingThreads.set(threads_->value());
  preferences::kFastEngine.set(fast_->isChecked());
  applyMappingThreads();
  QDialog::accept();
}

}  // namespace sg::app
