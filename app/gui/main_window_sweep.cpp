// SPDX-License-Identifier: GPL-3.0-or-later
#include "main_window_sweep.h"

#include <QAction>
#include <QFileInfo>
#include <QMenu>
#include <QMenuBar>
#include <QStatusBar>
#include <memory>
#include <string>

#include "document.h"
#include "main_window.h"
#include "sweep_view.h"

namespace sg::app {
namespace {

ui::SweepInputs inputsOf(const Document& d) {
  ui::SweepInputs in;
  in.run = d.dataset();
  in.secondRun = d.secondDataset();
  if (d.reference()) in.reference = std::make_shared<const ReferenceMap>(*d.reference());
  in.settings = d.mapperSettings();
  in.cellSize = d.cellSize();
  in.logName = d.logPath().isEmpty() ? QString() : QFileInfo(d.logPath()).fileName();
  return in;
}

// The choice the view shows: the document's plan when it was made for the model now chosen, else
// a start that suits that model (issue 49: HIMM got paper 002's tie "p1=1-p4" and could not
// sweep). Paper 002's grid, tie and VSDNS belong to the parameterized model; for the others no
// parameter is ticked. HIMM's model values are two constants, so VSDNS (their spread) is the
// same for every HIMM set: it starts with IOP against the reference, or derivative noise.
ui::SweepChoice choiceFor(const Document& d) {
  const SweepPlan& plan = d.sweep();
  const std::string& model = d.mapperSettings().model;
  if (plan.model == model) return {plan.axes, plan.ties, plan.metrics};
  if (model == "parameterized") {
    const SweepPlan paper002;
    return {paper002.axes, paper002.ties, paper002.metrics};
  }
  if (model == "himm")
    return {{}, {}, {d.reference() ? std::string("iop") : std::string("derivative")}};
  return {{}, {}, {"vsdns"}};
}

}  // namespace

void connectSweepView(ui::SweepView* view, Document* document) {
  view->setInputs(inputsOf(*document));
  view->setChoice(choiceFor(*document));
  auto showInputs = [view, document] { view->setInputs(inputsOf(*document)); };
  for (auto signal :
       {&Document::logChanged, &Document::secondLogChanged, &Document::referenceChanged})
    QObject::connect(document, signal, view, showInputs);
  QObject::connect(document, &Document::cellSizeChanged, view, showInputs);
  // Another model: the choice follows it (a slider of the same model leaves the form alone).
  auto shownModel = std::make_shared<std::string>(document->mapperSettings().model);
  QObject::connect(document, &Document::settingsChanged, view, [view, document, shownModel] {
    view->setInputs(inputsOf(*document));
    if (document->mapperSettings().model == *shownModel) return;
    *shownModel = document->mapperSettings().model;
    view->setChoice(choiceFor(*document));
  });
  // A reference that comes or goes changes the default metric (IOP needs one) of a choice the
  // user has not edited for this model.
  QObject::connect(document, &Document::referenceChanged, view, [view, document] {
    if (document->sweep().model != document->mapperSettings().model)
      view->setChoice(choiceFor(*document));
  });
  // Undo, redo and opening a project show the document's choice.
  QObject::connect(document, &Document::sweepChanged, view,
                   [view, document] { view->setChoice(choiceFor(*document)); });
  // An edit of the choice is an undoable edit of the document's sweep settings, which also
  // records what it sweeps over (model, rule, pose and the base values).
  QObject::connect(view, &ui::SweepView::choiceEdited, document,
                   [document](const ui::SweepChoice& choice) {
                     SweepPlan plan = document->sweep();
                     const MapperSettings& s = document->mapperSettings();
                     plan.model = s.model;
                     plan.rule = s.rule;
                     plan.pose = s.pose;
                     plan.base = s.parameters.values();
                     plan.axes = choice.axes;
                     plan.ties = choice.ties;
                     plan.metrics = choice.metrics;
                     document->setSweep(plan);
                   });
  // One click, one undo step; the window re-maps on settingsChanged.
  QObject::connect(view, &ui::SweepView::applyRequested, document,
                   [document](const MapperSettings& settings, const QString&) {
                     document->setMapperSettings(settings);
                   });
  QObject::connect(view, &ui::SweepView::pinRequested, document,
                   [document](const MapperSettings& settings, const QString& label) {
                     PinnedRow row;
                     row.label = label;
                     row.settings = settings;
                     row.cellSize = document->cellSize();
                     document->pinRow(std::move(row));
                   });
}

ui::SweepView* installSweepView(MainWindow* window) {
  auto* view = new ui::SweepView(window);
  view->setWindowFlag(Qt::Window);
  view->resize(1200, 820);
  connectSweepView(view, window->document());
  QObject::connect(view, &ui::SweepView::sweepFinished, window, [window, view](bool completed) {
    window->statusBar()->showMessage(
        completed ? QObject::tr("Sweep finished: %1").arg(view->statusText()) : view->statusText(),
        8000);
  });
  auto* action = new QAction(QObject::tr("S&weep Parameters…"), window);
  action->setObjectName(QStringLiteral("sweepAction"));
  action->setShortcut(QKeySequence(QObject::tr("Ctrl+Shift+W")));
  action->setToolTip(QObject::tr("Map the log once per parameter set and compare the maps"));
  QObject::connect(action, &QAction::triggered, view, [view] {
    view->show();
    view->raise();
    view->activateWindow();
  });
  window->addAction(action);
  for (QMenu* menu : window->menuBar()->findChildren<QMenu*>()) {
    if (menu->title() == QObject::tr("&Mapping")) {
      menu->addSeparator();
      menu->addAction(action);
      break;
    }
  }
  return view;
}

}  // namespace sg::app
