// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The timeline under the views: scrub to a time t (the map then holds every reading up to t), play
// and pause at 1x to 50x, and step scan by scan. It only reports times; the window hands them to
// the RemapController (setUntil) and to the views (the robot and beams of the current scan).

#include <QWidget>
#include <vector>

class QComboBox;
class QLabel;
class QSlider;
class QTimer;
class QToolButton;

namespace sg::ui {

class Timeline : public QWidget {
  Q_OBJECT

 public:
  explicit Timeline(QWidget* parent = nullptr);

  // The time of every scan (ascending) and the time of the log's last reading. The timeline then
  // stands at the end.
  void setScanTimes(std::vector<double> scanTimes, double endTime);
  // Scans appended to a live log: their times (ascending, after the last) and the time of the
  // log's last reading now. The range grows; a user standing at the end follows the live edge (the
  // time moves to the new end, and timeChanged() says so); anywhere else the time stays, and so
  // does the slider's knob. The first scans of an empty timeline enable it, at the end.
  void appendScanTimes(const std::vector<double>& scanTimes, double endTime);
  double time() const { return time_; }
  double startTime() const { return scanTimes_.empty() ? 0.0 : scanTimes_.front(); }
  double endTime() const { return endTime_; }
  bool atEnd() const { return time_ >= endTime_; }
  // The last scan taken at or before time(), or 0.
  std::size_t currentScan() const;
  bool playing() const;
  double speed() const { return speed_; }

  static const std::vector<double>& speeds();  // 1x ... 50x

 public slots:
  void setTime(double t);  // clamped to [start, end]
  void setPlaying(bool play);
  void setSpeed(double factor);
  void stepForward();   // to the next scan
  void stepBackward();  // to the previous scan

 signals:
  // The time moved (scrub, play, step): map up to `t`, show scan `scan`.
  void timeChanged(double t, std::size_t scan);
  void playingChanged(bool playing);

 private:
  void advance();
  void showTime();
  void setRange();  // the slider's range from the scan times, without moving the time

  std::vector<double> scanTimes_;
  double endTime_ = 0.0;
  double time_ = 0.0;
  double speed_ = 1.0;
  qint64 lastTick_ = 0;
  QSlider* slider_;
  QToolButton* play_;
  QToolButton* back_;
  QToolButton* forward_;
  QComboBox* speedBox_;
  QLabel* label_;
  QTimer* timer_;
};

}  // namespace sg::ui
