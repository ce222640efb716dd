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
  void previewed(double cellCm, int scanStride, double ms);
  void mappingFailed();
  // The forward model's EM (docs/forward-model.md): iteration `iteration` of at most `cap` done,
  // shown as a bar with a Stop EM button until emEnded().
  void emProgress(int iteration, int cap, double logLikelihood);
  void emEnded();
  // Stop EM ended a run: the map shown is the last one made.
  void emStopped();
  // The time of the last mapped(), in ms.
  double lastMapMs() const { return lastMapMs_; }

  void loadStarted(const QString& fileName);
  void loadProgress(int percent);
  void loadEnded();

 signals:
  void cancelLoadClicked();
  void stopEmClicked();

 private:
  QLabel* hint_;
  QLabel* remap_;
  QProgressBar* loadBar_;
  QPushButton* cancel_;
  QProgressBar* emBar_;
  QPushButton* stopEm_;
  double lastMapMs_ = 0.0;
};

}  // namespace sg::app
