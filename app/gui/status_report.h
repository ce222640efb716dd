// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The window's status bar: the hint (what the cell under the pointer holds, or what to do next),
// the re-map's state and time, and a log load's progress with its Cancel button.

#include <QObject>
#include <QString>

class QLabel;
class QProgressBar;
class QPushButton;
class QStatusBar;

namespace sg::app {

class StatusReport : public QObject {
  Q_OBJECT

 public:
  explicit StatusReport(QStatusBar* bar);

  void setHint(const QString& text);
  void mapping();
  void mapped(double ms);
  void previewed(double cellCm, double ms);
  void mappingFailed();
  // The time of the last mapped(), in ms.
  double lastMapMs() const { return lastMapMs_; }

  void loadStarted(const QString& fileName);
  void loadProgress(int percent);
  void loadEnded();

 signals:
  void cancelLoadClicked();

 private:
  QLabel* hint_;
  QLabel* remap_;
  QProgressBar* loadBar_;
  QPushButton* cancel_;
  double lastMapMs_ = 0.0;
};

}  // namespace sg::app
