// SPDX-License-Identifier: GPL-3.0-or-later
#include "robot/teleop_keys.h"

#include <QAbstractSpinBox>
#include <QApplication>
#include <QKeyEvent>
#include <QLineEdit>
#include <QPlainTextEdit>
#include <QTextEdit>
#include <QWidget>

#include "robot/robot_session.h"

namespace sg::app {

TeleopKeys::TeleopKeys(QWidget* window, RobotSession* session, QObject* parent)
    : QObject(parent), window_(window), session_(session) {}

TeleopKeys::~TeleopKeys() {
  setEnabled(false);
}

void TeleopKeys::setEnabled(bool on) {
  if (on == enabled_) return;
  enabled_ = on;
  up_ = down_ = leftKey_ = rightKey_ = false;
  if (on) {
    qApp->installEventFilter(this);
  } else {
    qApp->removeEventFilter(this);
    // A robot driven by the keys stops when they stop driving it.
    if (forward_ != 0 || left_ != 0) {
      forward_ = left_ = 0;
      session_->drive(0.0, 0.0);
    }
  }
}

void TeleopKeys::setSpeeds(double metresPerSecond, double radiansPerSecond) {
  speed_ = metresPerSecond;
  turnRate_ = radiansPerSecond;
}

bool TeleopKeys::eventFilter(QObject* watched, QEvent* event) {
  const QEvent::Type type = event->type();
  if (type == QEvent::ApplicationDeactivate) {
    // Keys released in another window never come here: stop rather than drive on.
    up_ = down_ = leftKey_ = rightKey_ = false;
    send();
    return false;
  }
  if (type != QEvent::KeyPress && type != QEvent::KeyRelease && type != QEvent::ShortcutOverride)
    return false;
  auto* widget = qobject_cast<QWidget*>(watched);
  if (!widget || !window_ || widget->window() != window_) return false;
  if (qobject_cast<QLineEdit*>(widget) || qobject_cast<QAbstractSpinBox*>(widget) ||
      qobject_cast<QTextEdit*>(widget) || qobject_cast<QPlainTextEdit*>(widget))
    return false;
  auto* key = static_cast<QKeyEvent*>(event);
  if (key->modifiers() & (Qt::ControlModifier | Qt::AltModifier | Qt::MetaModifier)) return false;
  bool* held = nullptr;
  switch (key->key()) {
    case Qt::Key_Up:
      held = &up_;
      break;
    case Qt::Key_Down:
      held = &down_;
      break;
    case Qt::Key_Left:
      held = &leftKey_;
      break;
    case Qt::Key_Right:
      held = &rightKey_;
      break;
    default:
      return false;
  }
  if (type == QEvent::ShortcutOverride) {
    // Claimed as a key press: no shortcut of the window takes an arrow key while driving.
    event->accept();
    return true;
  }
  if (!key->isAutoRepeat()) {
    *held = type == QEvent::KeyPress;
    send();
  }
  return true;
}

void TeleopKeys::send() {
  const int forward = (up_ ? 1 : 0) - (down_ ? 1 : 0);
  const int left = (leftKey_ ? 1 : 0) - (rightKey_ ? 1 : 0);
  if (forward == forward_ && left == left_) return;
  forward_ = forward;
  left_ = left;
  session_->drive(forward * speed_, left * turnRate_);
}

}  // namespace sg::app
