// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Help ▸ Sonar Models in 5 Minutes: a first-run tour for teaching. A plain, non-modal dialog with
// one short text per step and Back / Next; each step sets the window up for what it says (opens
// raschke-multi with its reference, switches between HIMM and HPF, shows the beam view's regions,
// moves one slider), so that the class sees what the text describes.

#include <QDialog>
#include <QString>
#include <functional>
#include <vector>

class QLabel;
class QPushButton;

namespace sg::app {

class MainWindow;

class TourDialog : public QDialog {
  Q_OBJECT

 public:
  explicit TourDialog(MainWindow* window);

  int stepCount() const { return static_cast<int>(steps_.size()); }
  int step() const { return step_; }
  // Shows step `index` (clamped) and sets the window up for it.
  void showStep(int index);
  void next() { showStep(step_ + 1); }
  void back() { showStep(step_ - 1); }
  QString stepTitle() const;

 private:
  struct Step {
    QString title;
    QString text;
    std::function<void(MainWindow&)> apply;
  };

  MainWindow* window_;
  std::vector<Step> steps_;
  int step_ = -1;
  QLabel* heading_;
  QLabel* body_;
  QLabel* counter_;
  QPushButton* back_;
  QPushButton* next_;
};

}  // namespace sg::app
