// SPDX-License-Identifier: GPL-3.0-or-later
#include "timeline.h"

#include <QComboBox>
#include <QDateTime>
#include <QHBoxLayout>
#include <QLabel>
#include <QSignalBlocker>
#include <QSlider>
#include <QStyle>
#include <QTimer>
#include <QToolButton>
#include <algorithm>
#include <cmath>

namespace sg::ui {
namespace {
constexpr int kTickMs = 33;           // about 30 frames a second while playing
constexpr double kSliderStep = 1e-3;  // one slider unit is a millisecond of log time
}  // namespace

const std::vector<double>& Timeline::speeds() {
  static const std::vector<double> s{1.0, 2.0, 5.0, 10.0, 20.0, 50.0};
  return s;
}

Timeline::Timeline(QWidget* parent)
    : QWidget(parent),
      slider_(new QSlider(Qt::Horizontal, this)),
      play_(new QToolButton(this)),
      back_(new QToolButton(this)),
      forward_(new QToolButton(this)),
      speedBox_(new QComboBox(this)),
      label_(new QLabel(this)),
      timer_(new QTimer(this)) {
  back_->setIcon(style()->standardIcon(QStyle::SP_MediaSkipBackward));
  back_->setToolTip(tr("Previous scan"));
  play_->setIcon(style()->standardIcon(QStyle::SP_MediaPlay));
  play_->setToolTip(tr("Play / pause"));
  play_->setCheckable(true);
  forward_->setIcon(style()->standardIcon(QStyle::SP_MediaSkipForward));
  forward_->setToolTip(tr("Next scan"));
  for (double s : speeds()) speedBox_->addItem(QStringLiteral("%1×").arg(s), s);
  speedBox_->setToolTip(tr("Playback speed"));
  slider_->setToolTip(tr("Drag to map the log up to a time"));
  label_->setMinimumWidth(
      label_->fontMetrics().horizontalAdvance(QStringLiteral("000.00 s / 000.00 s  scan 00000")));
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(4, 2, 4, 2);
  layout->addWidget(back_);
  layout->addWidget(play_);
  layout->addWidget(forward_);
  layout->addWidget(speedBox_);
  layout->addWidget(slider_, 1);
  layout->addWidget(label_);
  timer_->setInterval(kTickMs);

  connect(slider_, &QSlider::valueChanged, this,
          [this](int v) { setTime(startTime() + v * kSliderStep); });
  connect(play_, &QToolButton::toggled, this, &Timeline::setPlaying);
  connect(back_, &QToolButton::clicked, this, &Timeline::stepBackward);
  connect(forward_, &QToolButton::clicked, this, &Timeline::stepForward);
  connect(speedBox_, &QComboBox::currentIndexChanged, this,
          [this](int i) { speed_ = speedBox_->itemData(i).toDouble(); });
  connect(timer_, &QTimer::timeout, this, &Timeline::advance);
  setEnabled(false);
  showTime();
}

void Timeline::setScanTimes(std::vector<double> scanTimes, double endTime) {
  setPlaying(false);
  scanTimes_ = std::move(scanTimes);
  endTime_ = scanTimes_.empty() ? 0.0 : std::max(endTime, scanTimes_.back());
  time_ = endTime_;
  setRange();
  setEnabled(!scanTimes_.empty());
  showTime();
}

void Timeline::appendScanTimes(const std::vector<double>& scanTimes, double endTime) {
  if (scanTimes.empty() && !(endTime > endTime_)) return;
  const bool following = scanTimes_.empty() || atEnd();
  scanTimes_.insert(scanTimes_.end(), scanTimes.begin(), scanTimes.end());
  if (scanTimes_.empty()) return;
  endTime_ = std::max({endTime_, endTime, scanTimes_.back()});
  if (following) time_ = endTime_;
  setRange();
  setEnabled(true);
  showTime();
  if (following) emit timeChanged(time_, currentScan());
}

void Timeline::setRange() {
  const QSignalBlocker block(slider_);
  slider_->setRange(0, static_cast<int>(std::ceil((endTime_ - startTime()) / kSliderStep)));
  slider_->setValue(atEnd() ? slider_->maximum()
                            : static_cast<int>(std::lround((time_ - startTime()) / kSliderStep)));
  slider_->setPageStep(std::max(1, slider_->maximum() / 20));
}

std::size_t Timeline::currentScan() const {
  const auto it = std::upper_bound(scanTimes_.begin(), scanTimes_.end(), time_);
  return it == scanTimes_.begin() ? 0 : static_cast<std::size_t>(it - scanTimes_.begin() - 1);
}

bool Timeline::playing() const {
  return timer_->isActive();
}

void Timeline::setTime(double t) {
  if (scanTimes_.empty()) return;
  t = std::clamp(t, startTime(), endTime_);
  if (t == time_) return;
  time_ = t;
  {
    const QSignalBlocker block(slider_);
    slider_->setValue(static_cast<int>(std::lround((time_ - startTime()) / kSliderStep)));
  }
  showTime();
  emit timeChanged(time_, currentScan());
}

void Timeline::setPlaying(bool play) {
  if (play == playing()) return;
  if (play) {
    if (scanTimes_.empty()) return;
    if (atEnd()) setTime(startTime());
    lastTick_ = QDateTime::currentMSecsSinceEpoch();
    timer_->start();
  } else {
    timer_->stop();
  }
  {
    const QSignalBlocker block(play_);
    play_->setChecked(play);
  }
  play_->setIcon(style()->standardIcon(play ? QStyle::SP_MediaPause : QStyle::SP_MediaPlay));
  emit playingChanged(play);
}

void Timeline::setSpeed(double factor) {
  const auto& s = speeds();
  const auto it = std::min_element(s.begin(), s.end(), [factor](double a, double b) {
    return std::abs(a - factor) < std::abs(b - factor);
  });
  speedBox_->setCurrentIndex(static_cast<int>(it - s.begin()));
}

void Timeline::stepForward() {
  const auto it = std::upper_bound(scanTimes_.begin(), scanTimes_.end(), time_);
  setTime(it == scanTimes_.end() ? endTime_ : *it);
}

void Timeline::stepBackward() {
  auto it = std::lower_bound(scanTimes_.begin(), scanTimes_.end(), time_);
  if (it != scanTimes_.begin()) setTime(*(it - 1));
}

void Timeline::advance() {
  const qint64 now = QDateTime::currentMSecsSinceEpoch();
  const double dt = static_cast<double>(now - lastTick_) * 1e-3 * speed_;
  lastTick_ = now;
  setTime(time_ + dt);
  if (atEnd()) setPlaying(false);
}

void Timeline::showTime() {
  label_->setText(QStringLiteral("%1 s / %2 s  scan %3")
                      .arg(time_, 0, 'f', 2)
                      .arg(endTime_, 0, 'f', 2)
                      .arg(scanTimes_.empty() ? 0 : currentScan()));
}

}  // namespace sg::ui
