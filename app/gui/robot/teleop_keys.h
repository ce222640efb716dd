// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Teleoperation with the arrow keys (Robot ▸ Teleoperate): up and down drive forward and back,
// left and right turn, together they arc; releasing a key stops what it started. While on, the
// arrow keys pressed anywhere in the window drive the robot (the grid view does not pan with
// them), except in fields that edit text or numbers. Key repeats are ignored: ARCOS's VEL and RVEL
// hold until changed, and the link's keep-alive feeds the robot's watchdog.

#include <QObject>
#include <QPointer>

class QWidget;

namespace sg::app {

class RobotSession;

class TeleopKeys : public QObject {
  Q_OBJECT

 public:
  TeleopKeys(QWidget* window, RobotSession* session, QObject* parent = nullptr);
  ~TeleopKeys() override;

  void setEnabled(bool on);
  bool isEnabled() const { return enabled_; }
  // m/s with up or down held; rad/s with left or right held.
  void setSpeeds(double metresPerSecond, double radiansPerSecond);
  double speed() const { return speed_; }
  double turnRate() const { return turnRate_; }

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  void send();

  QPointer<QWidget> window_;
  RobotSession* session_;
  bool enabled_ = false;
  double speed_ = 0.3;
  double turnRate_ = 0.6;
  int forward_ = 0;  // keys held: +1 up, -1 down
  int left_ = 0;     // +1 left, -1 right
  bool up_ = false, down_ = false, leftKey_ = false, rightKey_ = false;
};

}  // namespace sg::app
