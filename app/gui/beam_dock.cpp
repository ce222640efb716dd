// SPDX-License-Identifier: GPL-3.0-or-later
#include "beam_dock.h"

#include <QComboBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QTimer>
#include <QVBoxLayout>

#include "beam_model_view.h"
#include "forward_range_view.h"
#include "sonargrid/forward/catalog.h"

namespace sg::app {

BeamDock::BeamDock(const MapperSettings& settings, QWidget* parent)
    : QWidget(parent),
      view_(new ui::BeamModelView(this)),
      forward_(new ui::ForwardRangeView(this)),
      chooser_(new QComboBox(this)),
      settings_(settings),
      timer_(new QTimer(this)) {
  settings_ = MapperSettings{};  // the beam view's own defaults until showSettings() below
  chooser_->setObjectName(QStringLiteral("readingChooser"));
  chooser_->setToolTip(
      tr("The reading of the current scan whose beam is drawn; its beam "
         "is highlighted in the grid view"));
  chooser_->setSizeAdjustPolicy(QComboBox::AdjustToContents);
  connect(chooser_, &QComboBox::activated, this,
          [this](int index) { emit sonarPicked(chooser_->itemData(index).value<std::size_t>()); });
  auto* label = new QLabel(tr("Current scan's r&eading:"), this);
  label->setBuddy(chooser_);
  auto* row = new QHBoxLayout;
  // Lined up with the beam view's own controls below.
  const QMargins inner = view_->layout()->contentsMargins();
  row->setContentsMargins(inner.left(), 0, inner.right(), 0);
  row->addWidget(label);
  row->addWidget(chooser_);
  row->addStretch(1);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 4, 0, 0);
  layout->addLayout(row);
  layout->addWidget(view_, 1);
  layout->addWidget(forward_, 1);
  settings_ = settings;
  showSettings();

  timer_->setSingleShot(true);
  timer_->setInterval(kIntervalMs);
  connect(timer_, &QTimer::timeout, this, &BeamDock::showSettings);
  shownAt_.start();
}

std::optional<std::size_t> BeamDock::showReadings(const std::vector<Reading>& readings,
                                                  double maxRange) {
  // The user's sonar while this scan has a reading of it, else the first reading with an echo.
  const Reading* shown = nullptr;
  for (const Reading& r : readings)
    if (chosen_ == static_cast<std::size_t>(r.sonar)) shown = &r;
  for (const Reading& r : readings)
    if (!shown && r.echo()) shown = &r;
  if (!shown && !readings.empty()) shown = &readings.front();

  const QSignalBlocker block(chooser_);
  chooser_->clear();
  for (const Reading& r : readings) {
    chooser_->addItem(r.echo() ? tr("sonar %1: %2 m").arg(r.sonar).arg(r.range, 0, 'f', 2)
                               : tr("sonar %1: no echo").arg(r.sonar),
                      QVariant::fromValue(static_cast<std::size_t>(r.sonar)));
    if (&r == shown) chooser_->setCurrentIndex(chooser_->count() - 1);
  }
  chooser_->setEnabled(!readings.empty());
  shown_ = shown ? std::optional<std::size_t>(shown->sonar) : std::nullopt;
  // No echo: the model's picture of a reading at the maximum range.
  if (shown) view_->setRange(shown->echo() ? shown->range : maxRange);
  if (!shown) forward_->clear();
  return shown_;
}

bool BeamDock::choose(const std::vector<Reading>& readings, std::size_t sonar) {
  for (const Reading& r : readings)
    if (r.sonar == sonar) {
      chosen_ = sonar;
      return true;
    }
  return false;
}

void BeamDock::startLog(double maxRange) {
  chosen_.reset();
  view_->setMaxRange(maxRange);
}

void BeamDock::clearReadings() {
  chooser_->clear();
  shown_.reset();
}

void BeamDock::setSettings(const MapperSettings& settings, bool paced) {
  settings_ = settings;
  if (!paced || forward::isForwardModel(settings.model)) {
    showSettings();
    return;
  }
  pending_ = true;
  if (!timer_->isActive()) timer_->start();
}

void BeamDock::gridRepainted(bool remapBusy) {
  if (pending_ && !remapBusy && shownAt_.elapsed() >= kIntervalMs) showSettings();
}

void BeamDock::showSettings() {
  timer_->stop();
  pending_ = false;
  shownAt_.restart();
  const bool forwardModel = forward::isForwardModel(settings_.model);
  view_->setVisible(!forwardModel);
  forward_->setVisible(forwardModel);
  // The beam model view draws an inverse model; the forward model's picture needs its map
  // (showForward()).
  if (!forwardModel) view_->setSettings(settings_);
}

void BeamDock::showForward(const forward::ForwardBeam& beam,
                           std::shared_ptr<const OccupancyMap> map) {
  if (!forward::isForwardModel(settings_.model)) return;
  forward_->show(beam, std::move(map), forward::settingsOf(settings_.parameters));
}

}  // namespace sg::app
