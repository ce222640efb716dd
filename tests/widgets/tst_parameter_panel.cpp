// SPDX-License-Identifier: GPL-3.0-or-later
// The parameter panel driven as a user drives it (QTest keys and mouse), watched with QSignalSpy.
// Expected parameter lists are the declarations in core/sonargrid/models/*.cpp and rules/*.cpp;
// expected values are worked out in the comment beside each.

#include <QtTest>

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QPushButton>
#include <QScrollArea>
#include <QSlider>
#include <QStandardItemModel>

#include "parameter_panel.h"
#include "sonargrid/forward/forward_em.h"
#include "sonargrid/params/presets.h"

using namespace sg;
using sg::ui::ParameterPanel;

Q_DECLARE_METATYPE(sg::MapperSettings)

namespace {

void choose(QComboBox* combo, const QString& name) {
  const int index = combo->findData(name);
  QVERIFY2(index >= 0, qPrintable(name));
  combo->setCurrentIndex(index);
}

QStringList sliderNames(const ParameterPanel& panel) {
  QStringList names;
  for (const QSlider* s : panel.findChildren<QSlider*>()) {
    if (s->objectName().startsWith("slider_")) names << s->objectName().mid(7);
  }
  names.sort();
  return names;
}

MapperSettings lastEmitted(const QSignalSpy& spy) {
  return spy.last().at(0).value<MapperSettings>();
}

// Presses the left button on the slider's handle, moves to `to` with the button held, releases.
void drag(QSlider* slider, const QPoint& to) {
  QStyleOptionSlider option;
  option.initFrom(slider);
  option.orientation = slider->orientation();
  option.minimum = slider->minimum();
  option.maximum = slider->maximum();
  option.sliderPosition = slider->sliderPosition();
  option.sliderValue = slider->value();
  const QRect handle =
      slider->style()->subControlRect(QStyle::CC_Slider, &option, QStyle::SC_SliderHandle, slider);
  const QPoint from = handle.center();
  QTest::mousePress(slider, Qt::LeftButton, Qt::NoModifier, from);
  for (int i = 1; i <= 8; ++i) {
    const QPoint at = from + (to - from) * i / 8;
    QMouseEvent move(QEvent::MouseMove, at, slider->mapToGlobal(at), Qt::NoButton, Qt::LeftButton,
                     Qt::NoModifier);
    QApplication::sendEvent(slider, &move);
  }
  QTest::mouseRelease(slider, Qt::LeftButton, Qt::NoModifier, to);
}

}  // namespace

class TstParameterPanel : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() { qRegisterMetaType<MapperSettings>(); }
  void rowsFollowModelAndRule_data();
  void rowsFollowModelAndRule();
  void incompatibleRulesAreDisabled();
  void parametersTheRuleDoesNotUseAreDisabled();
  void noteKeepsItsRoomWhileSlidersMove();
  void modelsThatLookPoorSaySo();
  void modelChangeMovesAnIncompatibleRule();
  void theForwardModelTakesEmAlone();
  void modelChangePrefersThePapersRule_data();
  void modelChangePrefersThePapersRule();
  void ruleNoteOnlyForARuleThatCameWithTheModel_data();
  void ruleNoteOnlyForARuleThatCameWithTheModel();
  void slidersKeepTheirWidth_data();
  void slidersKeepTheirWidth();
  void outOfRangeIsSaid();
  void sliderKeysChangeSettings();
  void sliderDragChangesSettings();
  void spinBoxTyping();
  void presetsSetCitedValues();
  void resetRestoresDefaults();
  void setSettingsIsSilentAndChecked();
  void remapTime();
};

void TstParameterPanel::rowsFollowModelAndRule_data() {
  QTest::addColumn<QString>("model");
  QTest::addColumn<QString>("rule");
  QTest::addColumn<QStringList>("expected");
  // hpf.cpp: ε, ω, R_min, no_echo; addition.cpp: combine, normalise.
  QTest::newRow("hpf+addition") << "hpf"
                                << "addition" << QStringList{"combine",   "epsilon", "no_echo",
                                                             "normalise", "omega",   "r_min"};
  // konolige.cpp: ω, F, a₀, k, d₀, d₁, no_echo; log_rule.cpp: cut_min, cut_max.
  QTest::newRow("konolige+log") << "konolige"
                                << "log"
                                << QStringList{"attenuation", "attenuation_slope", "cut_max",
                                               "cut_min",     "false_rate",        "no_echo",
                                               "omega",       "range_sd0",         "range_sd1"};
  // murphy.cpp: R, β, tol, Max_occ, no_echo; bayes.cpp: prior.
  QTest::newRow("murphy+bayes-recursive")
      << "murphy"
      << "bayes-recursive"
      << QStringList{"beta", "max_occupied", "max_range", "no_echo", "prior", "tolerance"};
  // parameterized.cpp: P1–P5, no_echo; log_odds.cpp: prior, clamp_min, clamp_max.
  QTest::newRow("parameterized+logodds")
      << "parameterized"
      << "logodds"
      << QStringList{"clamp_max", "clamp_min", "no_echo", "p1", "p2", "p3", "p4", "p5", "prior"};
  // himm_model.cpp: p_hit, p_miss, no_echo; himm_rule.cpp: I⁺, I⁻, CV_max.
  QTest::newRow("himm+himm") << "himm"
                             << "himm" << QStringList{"cv_max",  "decrement", "increment",
                                                      "no_echo", "p_hit",     "p_miss"};
  // dempster_shafer.cpp declares nothing.
  QTest::newRow("murphy+dempster-shafer")
      << "murphy"
      << "dempster-shafer"
      << QStringList{"beta", "max_occupied", "max_range", "no_echo", "tolerance"};
}

void TstParameterPanel::parametersTheRuleDoesNotUseAreDisabled() {
  // Issue 49 item 7: under HIMM × HIMM the p_hit and p_miss sliders changed nothing: the rule
  // adds I+ or subtracts I- whatever they are (paper 000 §2.2), and their ranges ([0.5, 1] and
  // [0, 0.5]) already put them on the side of 0.5 it reads. They are shown disabled with that
  // reason; the increments stay live, and under HIMM × log-odds (OctoMap's update, which reads
  // them as the hit and miss probabilities) they are live again.
  ParameterPanel panel;
  MapperSettings s;
  s.model = "himm";
  s.rule = "himm";
  s.parameters = defaultParameters("himm", "himm");
  panel.setSettings(s, true);
  for (const QString& name : {QStringLiteral("p_hit"), QStringLiteral("p_miss")}) {
    QVERIFY2(!panel.sliderFor(name)->isEnabled(), qPrintable(name));
    QVERIFY(!panel.spinBoxFor(name)->isEnabled());
    QVERIFY2(panel.sliderFor(name)->toolTip().startsWith("Not used by this rule: the himm rule"),
             qPrintable(panel.sliderFor(name)->toolTip()));
  }
  QVERIFY(panel.sliderFor("increment")->isEnabled());
  QVERIFY(panel.sliderFor("decrement")->isEnabled());
  QVERIFY(panel.sliderFor("no_echo")->isEnabled());
  s.rule = "logodds";
  s.parameters = defaultParameters("himm", "logodds");
  panel.setSettings(s, true);
  QVERIFY(panel.sliderFor("p_hit")->isEnabled());
  QVERIFY(panel.spinBoxFor("p_miss")->isEnabled());
}

void TstParameterPanel::noteKeepsItsRoomWhileSlidersMove() {
  // Issue 49 item 9: the "Rule changed" note vanished on the first slider change and every slider
  // below jumped about 90 px under the pointer mid-drag. The note's text goes, its room stays.
  ParameterPanel panel;
  panel.resize(360, 760);
  panel.show();
  QVERIFY(QTest::qWaitForWindowExposed(&panel));
  MapperSettings s;
  s.model = "hpf";
  s.rule = "addition";
  s.parameters = defaultParameters("hpf", "addition");
  panel.setSettings(s);
  s.model = "himm";  // with its paper's rule: the note says the rule changed too
  s.rule = "himm";
  s.parameters = defaultParameters("himm", "himm");
  panel.setSettings(s);
  QVERIFY2(panel.statusText().startsWith("Rule changed"), qPrintable(panel.statusText()));
  QApplication::processEvents();
  QSlider* slider = panel.sliderFor("increment");
  const int before = slider->mapTo(&panel, QPoint(0, 0)).y();
  slider->setValue(slider->value() + 1);  // the user's change: the note is history
  QVERIFY(panel.statusText().isEmpty());
  QApplication::processEvents();
  QCOMPARE(slider->mapTo(&panel, QPoint(0, 0)).y(), before);
  // Another model gives the room back.
  s.model = "hpf";
  s.rule = "bayes";
  s.parameters = defaultParameters("hpf", "bayes");
  panel.setSettings(s, true);
  QApplication::processEvents();
  QVERIFY(panel.sliderFor("epsilon")->mapTo(&panel, QPoint(0, 0)).y() < before);
}

void TstParameterPanel::modelsThatLookPoorSaySo() {
  // Issue 49 item 6: Murphy × recursive Bayes fills the room log with occupied wedges (IOP 545 mm
  // against HIMM's 79) as paper 002 §3.2 says of the model; the panel says why in one line. A model
  // without such a caveat (HIMM) shows none.
  ParameterPanel panel;
  auto* caveat = panel.findChild<QLabel*>("modelCaveat");
  QVERIFY(caveat);
  MapperSettings s;
  s.model = "murphy";
  s.rule = "bayes-recursive";
  s.parameters = defaultParameters("murphy", "bayes-recursive");
  panel.setSettings(s, true);
  QVERIFY(!caveat->isHidden());
  QVERIFY2(caveat->text().contains("section 3.2") && caveat->text().contains("wedges"),
           qPrintable(caveat->text()));
  QCOMPARE(caveat->text(), QString::fromStdString(sensorModelCaveat("murphy")));
  s.model = "himm";
  s.rule = "himm";
  s.parameters = defaultParameters("himm", "himm");
  panel.setSettings(s, true);
  QVERIFY(caveat->isHidden());
}

void TstParameterPanel::rowsFollowModelAndRule() {
  QFETCH(QString, model);
  QFETCH(QString, rule);
  QFETCH(QStringList, expected);
  ParameterPanel panel;
  choose(panel.findChild<QComboBox*>("modelChooser"), model);
  choose(panel.findChild<QComboBox*>("ruleChooser"), rule);
  QCOMPARE(QString::fromStdString(panel.settings().model), model);
  QCOMPARE(QString::fromStdString(panel.settings().rule), rule);
  QCOMPARE(sliderNames(panel), expected);
  // Each spin box spans exactly its declaration and shows the default.
  const MapperSettings settings = panel.settings();
  for (const ParameterSpec& spec : settings.parameters.specs()) {
    const QDoubleSpinBox* spin = panel.spinBoxFor(QString::fromStdString(spec.name));
    QVERIFY(spin);
    QCOMPARE(spin->minimum(), spec.min);
    QCOMPARE(spin->maximum(), spec.max);
    QCOMPARE(spin->value(), spec.defaultValue);
    QVERIFY(spin->toolTip().contains(QString::fromStdString(spec.source).toHtmlEscaped()));
  }
}

void TstParameterPanel::incompatibleRulesAreDisabled() {
  ParameterPanel panel;  // hpf + addition
  auto* rules = panel.findChild<QComboBox*>("ruleChooser");
  auto* items = qobject_cast<QStandardItemModel*>(rules->model());
  const QStandardItem* himm = items->item(rules->findData("himm"));
  QVERIFY(!himm->isEnabled());
  // rules/registry.cpp: the HIMM rule raises one axis cell per reading (paper 000 §2.2).
  QVERIFY(himm->toolTip().contains("paper 000 §2.2"));
  QVERIFY(items->item(rules->findData("bayes"))->isEnabled());

  choose(panel.findChild<QComboBox*>("modelChooser"), "himm");
  QVERIFY(items->item(rules->findData("himm"))->isEnabled());
  const QStandardItem* addition = items->item(rules->findData("addition"));
  QVERIFY(!addition->isEnabled());
  QVERIFY(addition->toolTip().contains("paper 001"));
  // A disabled rule set by program is refused too.
  rules->setCurrentIndex(rules->findData("addition"));
  QVERIFY(panel.settings().rule != "addition");
}

void TstParameterPanel::modelChangeMovesAnIncompatibleRule() {
  ParameterPanel panel;  // hpf + addition
  QSignalSpy spy(&panel, &ParameterPanel::settingsChanged);
  choose(panel.findChild<QComboBox*>("modelChooser"), "himm");
  // himm + addition is refused; HIMM's paper pairs it with its histogram rule (paper 000 §2.2).
  QCOMPARE(panel.settings().rule, std::string("himm"));
  QCOMPARE(spy.count(), 1);
  QVERIFY(panel.findChild<QLabel*>("status")->text().contains("addition"));
  QCOMPARE(sliderNames(panel),
           (QStringList{"cv_max", "decrement", "increment", "no_echo", "p_hit", "p_miss"}));
}

// The forward model learned by EM (docs/forward-model.md) beside the inverse models: its rule is
// EM alone (every update rule disabled for it, EM disabled for the others), its rows are its own
// declarations, and the panel says it is a batch method.
void TstParameterPanel::theForwardModelTakesEmAlone() {
  ParameterPanel panel;  // hpf + addition
  auto* rules = panel.findChild<QComboBox*>("ruleChooser");
  auto* items = qobject_cast<QStandardItemModel*>(rules->model());
  QVERIFY(!items->item(rules->findData("em"))->isEnabled());
  QSignalSpy spy(&panel, &ParameterPanel::settingsChanged);
  choose(panel.findChild<QComboBox*>("modelChooser"), "forward-em");
  QCOMPARE(spy.count(), 1);
  QCOMPARE(lastEmitted(spy).model, std::string("forward-em"));
  QCOMPARE(lastEmitted(spy).rule, std::string("em"));
  QCOMPARE(lastEmitted(spy).parameters, sg::forward::defaultForwardParameters());
  QVERIFY(items->item(rules->findData("em"))->isEnabled());
  for (const char* rule : {"addition", "bayes", "logodds", "himm", "dempster-shafer"})
    QVERIFY2(!items->item(rules->findData(rule))->isEnabled(), rule);
  QCOMPARE(sliderNames(panel),
           (QStringList{"iterations", "omega", "p_init", "p_max", "p_rand", "sigma"}));
  QVERIFY(panel.findChild<QLabel*>("modelCaveat")->text().contains("EM"));
  // Back to an inverse model: its paper's rule again.
  choose(panel.findChild<QComboBox*>("modelChooser"), "konolige");
  QCOMPARE(panel.settings().rule, std::string("log"));
}

void TstParameterPanel::modelChangePrefersThePapersRule_data() {
  QTest::addColumn<QString>("from");
  QTest::addColumn<QString>("fromRule");
  QTest::addColumn<QString>("model");
  QTest::addColumn<QString>("rule");
  // The pairings each ModelInfo declares: paper 000 §2.1–2.2 (HPF with probability addition,
  // HIMM with its histogram), paper 001 §5.1 (models compared on the log update), paper 002
  // §3.3–§4 (Murphy and P1–P5 with recursive Bayes).
  QTest::newRow("himm → parameterized") << "himm"
                                        << "himm"
                                        << "parameterized"
                                        << "bayes-recursive";
  QTest::newRow("himm → murphy") << "himm"
                                 << "himm"
                                 << "murphy"
                                 << "bayes-recursive";
  QTest::newRow("himm → hpf") << "himm"
                              << "himm"
                              << "hpf"
                              << "addition";
  QTest::newRow("himm → konolige") << "himm"
                                   << "himm"
                                   << "konolige"
                                   << "log";
  QTest::newRow("murphy → himm") << "murphy"
                                 << "bayes-recursive"
                                 << "himm"
                                 << "himm";
}

void TstParameterPanel::modelChangePrefersThePapersRule() {
  QFETCH(QString, from);
  QFETCH(QString, fromRule);
  QFETCH(QString, model);
  QFETCH(QString, rule);
  ParameterPanel panel;
  MapperSettings start;
  start.model = from.toStdString();
  start.rule = fromRule.toStdString();
  start.parameters = defaultParameters(start.model, start.rule);
  panel.setSettings(start);
  QCOMPARE(panel.statusText(), QString());
  QSignalSpy spy(&panel, &ParameterPanel::settingsChanged);
  choose(panel.findChild<QComboBox*>("modelChooser"), model);
  QCOMPARE(spy.count(), 1);
  QCOMPARE(panel.settings().rule, rule.toStdString());
  QCOMPARE(panel.findChild<QComboBox*>("ruleChooser")->currentData().toString(), rule);
  // The note names both rules' titles and stays when the window shows the settings back (the
  // app calls setSettings with what the panel emitted).
  const QString note = panel.statusText();
  QVERIFY2(note.contains(QString::fromStdString(updateRuleInfo(fromRule.toStdString()).title)),
           qPrintable(note));
  QVERIFY2(note.contains(QString::fromStdString(updateRuleInfo(rule.toStdString()).title)),
           qPrintable(note));
  panel.setSettings(lastEmitted(spy));
  QCOMPARE(panel.statusText(), note);
  QVERIFY(panel.findChild<QLabel*>("status")->isVisibleTo(&panel));
  // The next change (one slider step) ends it. (The first slider the rule uses: HIMM's rule
  // leaves p_hit and p_miss disabled.)
  QSlider* slider = nullptr;
  for (QSlider* s : panel.findChildren<QSlider*>())
    if (!slider && s->isEnabled()) slider = s;
  QVERIFY(slider);
  QTest::keyClick(slider, slider->value() < slider->maximum() ? Qt::Key_Right : Qt::Key_Left);
  QCOMPARE(spy.count(), 2);
  QCOMPARE(panel.statusText(), QString());
}

void TstParameterPanel::ruleNoteOnlyForARuleThatCameWithTheModel_data() {
  QTest::addColumn<QString>("fromModel");
  QTest::addColumn<QString>("fromRule");
  QTest::addColumn<QString>("model");
  QTest::addColumn<QString>("rule");
  QTest::addColumn<bool>("ruleNamed");
  QTest::addColumn<bool>("noted");
  // The window shows the last session's settings first, then what the command line names
  // (`sonargrid LOG --model parameterized --rule bayes`, app/gui/main.cpp): the user named the
  // rule, so nothing is said of a rule change. The Mapping menu's model (with its paper's rule)
  // and undo bring a rule the user did not name: the note says so.
  QTest::newRow("command line, log → bayes") << "konolige"
                                             << "log"
                                             << "parameterized"
                                             << "bayes" << true << false;
  QTest::newRow("command line, himm → bayes") << "himm"
                                              << "himm"
                                              << "parameterized"
                                              << "bayes" << true << false;
  QTest::newRow("Mapping menu, log → bayes-recursive") << "konolige"
                                                       << "log"
                                                       << "parameterized"
                                                       << "bayes-recursive" << false << true;
  QTest::newRow("undo, bayes → log") << "parameterized"
                                     << "bayes"
                                     << "konolige"
                                     << "log" << false << true;
}

void TstParameterPanel::ruleNoteOnlyForARuleThatCameWithTheModel() {
  QFETCH(QString, fromModel);
  QFETCH(QString, fromRule);
  QFETCH(QString, model);
  QFETCH(QString, rule);
  QFETCH(bool, ruleNamed);
  QFETCH(bool, noted);
  auto settings = [](const QString& m, const QString& r) {
    MapperSettings s;
    s.model = m.toStdString();
    s.rule = r.toStdString();
    s.parameters = defaultParameters(s.model, s.rule);
    return s;
  };
  ParameterPanel panel;
  panel.setSettings(settings(fromModel, fromRule));  // the window's first: never noted
  QCOMPARE(panel.statusText(), QString());
  QSignalSpy spy(&panel, &ParameterPanel::settingsChanged);
  panel.setSettings(settings(model, rule), ruleNamed);
  QCOMPARE(spy.count(), 0);
  QCOMPARE(panel.settings().model, model.toStdString());
  QCOMPARE(panel.settings().rule, rule.toStdString());
  const QString note = panel.statusText();
  QVERIFY2(note.isEmpty() != noted, qPrintable(note));
  if (noted) {
    // "Rule changed from <old title> to <new title>…" (ParameterPanel::ruleChangeNote).
    QVERIFY2(note.startsWith(QStringLiteral("Rule changed from ") +
                             QString::fromStdString(updateRuleInfo(fromRule.toStdString()).title) +
                             QStringLiteral(" to ") +
                             QString::fromStdString(updateRuleInfo(rule.toStdString()).title)),
             qPrintable(note));
  }
}

void TstParameterPanel::slidersKeepTheirWidth_data() {
  QTest::addColumn<QString>("model");
  QTest::addColumn<QString>("rule");
  // Every model with its paper's rule; Konolige's rows ("k (attenuation_slope) [1/m]") were the
  // widest labels.
  for (const std::string& m : sensorModelNames()) {
    const std::string& r = sensorModelInfo(m).preferredRule;
    QTest::newRow((m + " × " + r).c_str())
        << QString::fromStdString(m) << QString::fromStdString(r);
  }
}

void TstParameterPanel::slidersKeepTheirWidth() {
  QFETCH(QString, model);
  QFETCH(QString, rule);
  ParameterPanel panel;
  MapperSettings s;
  s.model = model.toStdString();
  s.rule = rule.toStdString();
  s.parameters = defaultParameters(s.model, s.rule);
  panel.setSettings(s);
  // At its smallest: the panel never lays a groove out narrower than 80 px.
  panel.resize(panel.minimumSizeHint().width(), 700);
  panel.show();
  QVERIFY(QTest::qWaitForWindowExposed(&panel));
  const QList<QSlider*> sliders = panel.findChildren<QSlider*>();
  QVERIFY(!sliders.isEmpty());
  for (QSlider* slider : sliders) {
    QStyleOptionSlider option;
    option.initFrom(slider);
    option.orientation = slider->orientation();
    const QRect groove = slider->style()->subControlRect(QStyle::CC_Slider, &option,
                                                         QStyle::SC_SliderGroove, slider);
    QVERIFY2(groove.width() >= 80,
             qPrintable(
                 QStringLiteral("%1: groove %2 px").arg(slider->objectName()).arg(groove.width())));
    QVERIFY2(
        slider->width() >= ParameterPanel::kMinSliderWidth,
        qPrintable(QStringLiteral("%1: %2 px").arg(slider->objectName()).arg(slider->width())));
    // Not cut by the scroll area: the whole slider lies across its viewport.
    const QWidget* viewport = panel.findChild<QScrollArea*>()->viewport();
    const QRect r(slider->mapTo(viewport, QPoint(0, 0)), slider->size());
    QVERIFY2(r.left() >= 0 && r.right() < viewport->width(), qPrintable(slider->objectName()));
    // The long name stays reachable: tooltip and accessible name.
    QVERIFY(slider->toolTip().contains(slider->objectName().mid(7)));
  }
}

void TstParameterPanel::outOfRangeIsSaid() {
  MapperSettings s;
  s.model = "himm";
  s.rule = "himm";
  s.parameters = defaultParameters(s.model, s.rule);
  ParameterPanel panel;
  panel.setSettings(s);
  QSignalSpy spy(&panel, &ParameterPanel::settingsChanged);
  // I⁺ is declared in [1, 15], default 3 (rules/himm_rule.cpp; paper 000 §2.2).
  QDoubleSpinBox* spin = panel.spinBoxFor("increment");
  spin->setFocus();
  spin->selectAll();
  QTest::keyClicks(spin, "1e9");
  QTest::keyClick(spin, Qt::Key_Return);
  QCOMPARE(spy.count(), 0);
  QCOMPARE(panel.settings().parameters.get("increment"), 3.0);
  QVERIFY2(panel.statusText().contains("out of range"), qPrintable(panel.statusText()));
  QVERIFY2(panel.statusText().contains("1e9"), qPrintable(panel.statusText()));
  // A value in range is taken and ends the note.
  spin->selectAll();
  QTest::keyClicks(spin, "5");
  QTest::keyClick(spin, Qt::Key_Return);
  QCOMPARE(spy.count(), 1);
  QCOMPARE(panel.settings().parameters.get("increment"), 5.0);
  QCOMPARE(panel.statusText(), QString());
}

void TstParameterPanel::sliderKeysChangeSettings() {
  ParameterPanel panel;  // hpf: ε in [0.005, 1] m, default 0.1
  QSlider* slider = panel.sliderFor("epsilon");
  QVERIFY(slider);
  QSignalSpy spy(&panel, &ParameterPanel::settingsChanged);
  // Slider step: the smallest 1/2/5·10^k ≥ 0.995/1000 is 0.001 m; one Right = +0.001.
  QTest::keyClick(slider, Qt::Key_Right);
  QCOMPARE(spy.count(), 1);
  QCOMPARE(panel.settings().parameters.get("epsilon"), 0.101);
  QCOMPARE(lastEmitted(spy).parameters.get("epsilon"), 0.101);
  QCOMPARE(panel.spinBoxFor("epsilon")->value(), 0.101);
  // Page step: 995 positions / 20 = 49 → 0.101 + 0.049 = 0.150.
  QTest::keyClick(slider, Qt::Key_PageUp);
  QCOMPARE(spy.count(), 2);
  QCOMPARE(panel.settings().parameters.get("epsilon"), 0.15);
  // End = the maximum, 1 m; a second End is the same value and emits nothing.
  QTest::keyClick(slider, Qt::Key_End);
  QTest::keyClick(slider, Qt::Key_End);
  QCOMPARE(spy.count(), 3);
  QCOMPARE(panel.settings().parameters.get("epsilon"), 1.0);
  // Left from the end: 0.005 + 994 · 0.001 = 0.999.
  QTest::keyClick(slider, Qt::Key_Left);
  QCOMPARE(panel.settings().parameters.get("epsilon"), 0.999);
  QCOMPARE(spy.count(), 4);
}

void TstParameterPanel::sliderDragChangesSettings() {
  ParameterPanel panel;
  choose(panel.findChild<QComboBox*>("modelChooser"), "parameterized");
  panel.resize(600, 700);
  panel.show();
  QVERIFY(QTest::qWaitForWindowExposed(&panel));
  QSlider* slider = panel.sliderFor("p5");
  QVERIFY(slider);
  QSignalSpy spy(&panel, &ParameterPanel::settingsChanged);
  // Dragging the handle far past the right end: P5 ends at its declared maximum, 45°.
  drag(slider, QPoint(slider->width() + 200, slider->height() / 2));
  QVERIFY(spy.count() >= 1);
  QCOMPARE(panel.settings().parameters.get("p5"), 45.0);
  // Every emission carries a value different from the one before it.
  double previous = 15.0;  // parameterized.cpp default
  for (const QList<QVariant>& args : spy) {
    const double p5 = args.at(0).value<MapperSettings>().parameters.get("p5");
    QVERIFY(p5 != previous);
    previous = p5;
  }
}

void TstParameterPanel::spinBoxTyping() {
  ParameterPanel panel;
  QDoubleSpinBox* spin = panel.spinBoxFor("omega");
  QSignalSpy spy(&panel, &ParameterPanel::settingsChanged);
  spin->selectAll();
  QTest::keyClicks(spin, "30");
  QCOMPARE(spy.count(), 0);  // no keyboard tracking: nothing until Enter
  QTest::keyClick(spin, Qt::Key_Return);
  QCOMPARE(spy.count(), 1);
  QCOMPARE(panel.settings().parameters.get("omega"), 30.0);
  // The slider follows: ω in [5, 90]°, step 0.1° (smallest nice ≥ 0.085) → (30 − 5)/0.1 = 250.
  QCOMPARE(panel.sliderFor("omega")->value(), 250);
}

void TstParameterPanel::presetsSetCitedValues() {
  ParameterPanel panel;
  QSignalSpy spy(&panel, &ParameterPanel::settingsChanged);
  auto* presets = panel.findChild<QComboBox*>("presetChooser");
  // Keyboard: the chooser starts on "Custom"; Down moves to the first preset, paper 000 HPF.
  presets->setFocus();
  QTest::keyClick(presets, Qt::Key_Down);
  QCOMPARE(presets->currentData().toString(), QString("paper000-hpf"));
  QCOMPARE(spy.count(), 1);
  // Paper 000 eqs 7–8: combine = 0.
  QCOMPARE(panel.settings().parameters.get("combine"), 0.0);

  // Paper 002 Table 1 col. 5: P1 0.03, P2 0.171, 2·P3 0.786, P4 0.97, P5 6.14.
  QVERIFY(panel.applyPreset("paper002-table1-histogram"));
  QCOMPARE(spy.count(), 2);
  // hpf × addition → parameterized × bayes-recursive: the preset names both, so no note says the
  // rule changed with the model.
  QCOMPARE(panel.statusText(), QString());
  const MapperSettings s = panel.settings();
  QCOMPARE(s.model, std::string("parameterized"));
  QCOMPARE(s.rule, std::string("bayes-recursive"));
  QCOMPARE(s.parameters.get("p1"), 0.03);
  QCOMPARE(s.parameters.get("p2"), 0.171);
  QCOMPARE(s.parameters.get("p3"), 0.393);
  QCOMPARE(s.parameters.get("p4"), 0.97);
  QCOMPARE(s.parameters.get("p5"), 6.14);
  QCOMPARE(panel.spinBoxFor("p3")->value(), 0.393);
  QCOMPARE(panel.spinBoxFor("p5")->value(), 6.14);
  QCOMPARE(presets->currentData().toString(), QString("paper002-table1-histogram"));
  // Applying it again changes nothing and emits nothing; moving a slider makes it "Custom".
  QVERIFY(panel.applyPreset("paper002-table1-histogram"));
  QCOMPARE(spy.count(), 2);
  // hpf × addition → parameterized × bayes-recursive: the preset names both, so no note says the
  // rule changed with the model.
  QCOMPARE(panel.statusText(), QString());
  QTest::keyClick(panel.sliderFor("p2"), Qt::Key_Right);
  QCOMPARE(presets->currentIndex(), 0);
  QVERIFY(!panel.applyPreset("no-such-preset"));
}

void TstParameterPanel::resetRestoresDefaults() {
  ParameterPanel panel;
  choose(panel.findChild<QComboBox*>("modelChooser"), "murphy");
  QTest::keyClick(panel.sliderFor("beta"), Qt::Key_End);
  QCOMPARE(panel.settings().parameters.get("beta"), 45.0);  // murphy.cpp: β ≤ 45°
  QSignalSpy spy(&panel, &ParameterPanel::settingsChanged);
  auto* reset = panel.findChild<QPushButton*>("resetToDefaults");
  QTest::mouseClick(reset, Qt::LeftButton);
  QCOMPARE(spy.count(), 1);
  // Murphy's model comes with its paper's recursive Bayes (paper 002 §3.3).
  QVERIFY(panel.settings().parameters == defaultParameters("murphy", "bayes-recursive"));
  QCOMPARE(panel.settings().parameters.get("beta"), 15.0);  // murphy.cpp default
  QCOMPARE(panel.spinBoxFor("beta")->value(), 15.0);
  QTest::mouseClick(reset, Qt::LeftButton);
  QCOMPARE(spy.count(), 1);  // already at the defaults
}

void TstParameterPanel::setSettingsIsSilentAndChecked() {
  ParameterPanel panel;
  QSignalSpy spy(&panel, &ParameterPanel::settingsChanged);
  MapperSettings s = applyPreset(*findPreset("paper002-fig6-standard"));
  panel.setSettings(s);
  QCOMPARE(spy.count(), 0);
  QCOMPARE(panel.settings().model, std::string("murphy"));
  QCOMPARE(panel.spinBoxFor("tolerance")->value(), 1.0);  // paper 002 Fig. 6
  QCOMPARE(panel.findChild<QComboBox*>("presetChooser")->currentData().toString(),
           QString("paper002-fig6-standard"));
  MapperSettings bad;
  bad.model = "hpf";
  bad.rule = "himm";
  panel.setSettings(bad);
  QCOMPARE(panel.settings().model, std::string("murphy"));  // refused, kept
  QVERIFY(panel.findChild<QLabel*>("status")->text().contains("refused"));
}

void TstParameterPanel::remapTime() {
  ParameterPanel panel;
  panel.showRemapTime(123.4);
  QCOMPARE(panel.findChild<QLabel*>("remapTime")->text(), QString("Re-map: 123 ms"));
  panel.showRemapTime(4.26);
  QCOMPARE(panel.findChild<QLabel*>("remapTime")->text(), QString("Re-map: 4.3 ms"));
}

QTEST_MAIN(TstParameterPanel)
#include "tst_parameter_panel.moc"
