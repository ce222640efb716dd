// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The sweep view's form (docs/user-guide.md, "Sweeping parameters"): what the sweep maps (a
// header), the parameters the model and the rule declare (name, symbol, unit, range, the value
// now) with a tick and the values to sweep ("a:step:b" or "v1,v2,..."), the ties ("p1=1-p4") and
// the metrics, and how many sets that makes. It edits a SweepChoice; the sweep itself is the
// view's (sweep_view.h).

#include <QWidget>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "sonargrid/data/dataset.h"
#include "sonargrid/engine/mapper.h"
#include "sonargrid/reference/reference_map.h"

class QHBoxLayout;
class QLabel;
class QLineEdit;
class QListWidget;
class QTableWidget;

namespace sg::ui {

// What a sweep maps: the document's logs, reference, mapper settings (model, rule, pose and the
// base values of every parameter) and cell size.
struct SweepInputs {
  std::shared_ptr<const Dataset> run;
  std::shared_ptr<const Dataset> secondRun;
  std::shared_ptr<const ReferenceMap> reference;
  MapperSettings settings;
  double cellSize = 0.05;
  QString logName;
};

// What the user chose, as `sonargrid-cli sweep` flags: --grid texts ("p2=0.05:0.05:0.2"), --tie
// texts ("p1=1-p4") and --metric names. Saved with the project.
struct SweepChoice {
  std::vector<std::string> axes;
  std::vector<std::string> ties;
  std::vector<std::string> metrics;
  bool operator==(const SweepChoice&) const = default;
};

// "p=text" (a --grid text) split at the first '='.
std::pair<std::string, std::string> splitAxis(const std::string& axis);
// "1 set", "12 sets" (the app ships no translations, so %n plurals would print "set(s)").
QString setsText(std::size_t n);

class SweepForm : public QWidget {
  Q_OBJECT

 public:
  // More sets than this are said to be too many (SweepView::kMaxViewSets).
  static constexpr std::size_t kMaxSets = 100000;

  explicit SweepForm(QWidget* parent = nullptr);

  // The header, the parameter rows (rebuilt when the model or the rule changes, else their values
  // now follow the document's) and which metrics can be chosen.
  void setInputs(const SweepInputs& inputs);
  // Shows `choice` without emitting choiceEdited.
  void setChoice(const SweepChoice& choice);
  SweepChoice choice() const { return choice_; }

  // Puts `widget` at the end of the row of the set count (the view's Run and Cancel buttons).
  void addToCountRow(QWidget* widget);

 signals:
  void choiceEdited(const sg::ui::SweepChoice& choice);

 private:
  void rebuildParameterRows();
  void showChoice();
  void readForm();  // the form into choice_, then choiceEdited
  void updateSetCount();

  SweepInputs inputs_;
  SweepChoice choice_;
  bool updating_ = false;

  QLabel* header_ = nullptr;
  QTableWidget* parameters_ = nullptr;
  QLineEdit* ties_ = nullptr;
  QListWidget* metrics_ = nullptr;
  QLabel* setCount_ = nullptr;
  QHBoxLayout* countRow_ = nullptr;
};

}  // namespace sg::ui
