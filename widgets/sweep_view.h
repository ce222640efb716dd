// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The sweep view (docs/user-guide.md, "Sweeping parameters"): the app's face of `sonargrid-cli
// sweep` (docs/sweeps.md), with the same grammar and the same core code. The user picks the
// parameters to sweep from the model's and rule's declared specs (name, symbol, unit, range) with
// their values ("a:step:b" or "v1,v2,..."), ties ("p1=1-p4") and metrics in its form
// (sweep_form.h); the core builds the sets (sweepSets) and evaluates them (evaluateSets) on worker
// threads (SweepRunner) while the view shows progress, a table of every set, the metric against
// each parameter and its histogram (paper 002 Fig. 7). The best set by paper 002's rules
// (optimal_sets.h) or by a metric's best value is applied, or rows are pinned, through signals the
// window turns into Document edits.

#include <QWidget>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sonargrid/sweep/optimal_sets.h"
#include "sweep_form.h"  // SweepInputs, SweepChoice

class QComboBox;
class QLabel;
class QProgressBar;
class QPushButton;
class QTableView;
class QTimer;

namespace sg::ui {

class SweepCharts;
class SweepResultsModel;
class SweepRunner;
struct SweepJob;

class SweepView : public QWidget {
  Q_OBJECT

 public:
  // More sets than this are refused here (the CLI's --shard spreads bigger sweeps over machines).
  static constexpr std::size_t kMaxViewSets = SweepForm::kMaxSets;

  enum class BestRule { LowestBin, Minimum, NearestMean, BestValue };

  explicit SweepView(QWidget* parent = nullptr);
  ~SweepView() override;  // cancels a running sweep and waits for its threads

  void setInputs(SweepInputs inputs);
  // Shows `choice` without emitting choiceEdited.
  void setChoice(const SweepChoice& choice);
  SweepChoice choice() const;

  // Starts the sweep of the current choice; false (the reason in statusText()) when the choice
  // cannot be swept or a sweep is running.
  bool run();
  void cancel();
  bool isRunning() const;
  // Runs the event loop until the running sweep has finished; false on timeout.
  bool waitForSweep(int timeoutMs);

  const SweepResultsModel* results() const { return model_; }
  // The sweep shown (its sets, metrics and settings); null before the first run.
  const SweepJob* job() const { return job_.get(); }
  QString statusText() const;

  // The metric column the plots and the best set use, and the rule picking the best set.
  bool setPlotColumn(const QString& column);
  bool setBestRule(BestRule rule);
  // The best set by the rule over the finished sets; empty when none has a value or the rule
  // cannot choose one (then `why`, when given, says why). Never throws.
  std::optional<OptimalSet> best(QString* why = nullptr) const;
  // Emit applyRequested / pinRequested for the best set or for rows of the table.
  bool applyBest();
  bool applyRow(std::size_t index);
  bool pinBest();
  bool pinRow(std::size_t index);

 signals:
  void choiceEdited(const sg::ui::SweepChoice& choice);
  // The mapper settings of a set of the sweep shown (its model, rule, pose; the set's values).
  void applyRequested(const sg::MapperSettings& settings, const QString& label);
  void pinRequested(const sg::MapperSettings& settings, const QString& label);
  void sweepFinished(bool completed);

 protected:
  void closeEvent(QCloseEvent* event) override;

 private:
  std::optional<OptimalSet> chooseBest() const;  // best(), throwing what the rules throw
  void buildView();
  // The sweep of choice() over inputs_; throws SweepSpecError / std::exception with the reason.
  std::shared_ptr<SweepJob> makeJob() const;
  void onSetFinished(std::size_t index, const std::vector<std::optional<double>>& values);
  void onFinished(bool completed, const QString& error);
  void refreshPlots();
  void refreshBest();
  void refillBestRules();
  int plotColumn() const;  // index into the results' columns, -1 for none
  MapperSettings settingsOf(const ParameterSet& set) const;
  QString describe(const ParameterSet& set) const;
  void setStatus(const QString& text, bool error = false);
  void updateButtons();

  SweepInputs inputs_;
  std::shared_ptr<const SweepJob> job_;
  std::vector<std::string> shownParameters_;  // swept, then tied, of job_
  std::vector<std::string> sweptParameters_;
  bool updating_ = false;
  bool running_ = false;

  SweepForm* form_ = nullptr;
  QPushButton* runButton_ = nullptr;
  QPushButton* cancelButton_ = nullptr;
  QProgressBar* progress_ = nullptr;
  QLabel* status_ = nullptr;
  QTableView* table_ = nullptr;
  SweepResultsModel* model_ = nullptr;
  QComboBox* plotColumn_ = nullptr;
  QComboBox* bestRule_ = nullptr;
  QLabel* bestLabel_ = nullptr;
  QPushButton* applyBest_ = nullptr;
  QPushButton* pinBest_ = nullptr;
  QPushButton* applySelected_ = nullptr;
  QPushButton* pinSelected_ = nullptr;
  SweepCharts* charts_ = nullptr;
  SweepRunner* runner_ = nullptr;
  QTimer* plotTimer_ = nullptr;
};

}  // namespace sg::ui
