// SPDX-License-Identifier: GPL-3.0-or-later
// The main window's parameter panel and beam-model view, offscreen: a key on a focused slider
// re-maps the log and the view shows exactly the map Mapper::mapDataset builds with the new value;
// a burst of slider moves delivers only the newest map; settings set from outside the panel (the
// Mapping menu, the command line) show in the panel without echoing back or mapping twice, and a
// rule the command line names is not noted as a change; the beam view shows a reading of the
// current scan with the panel's model.

#include <QComboBox>
#include <QLabel>
#include <QSignalSpy>
#include <QSlider>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QUndoStack>
#include <QtTest>

#include "beam_model_view.h"
#include "document.h"
#include "forward_range_view.h"
#include "grid_view.h"
#include "main_window.h"
#include "parameter_panel.h"
#include "remap_controller.h"
#include "sonargrid/export/map_export.h"
#include "sonargrid/forward/forward_em.h"
#include "sonargrid/io/sglog.h"
#include "timeline.h"

using namespace sg;

namespace {

const QString kRoom = QStringLiteral(SONARGRID_DATASETS "/room/room.sglog");

MapperSettings hpfAddition() {
  MapperSettings s;
  s.model = "hpf";
  s.rule = "addition";
  s.parameters = defaultParameters(s.model, s.rule);
  s.pose = PoseSource::Truth;
  return s;
}

// What `sonargrid-cli map --log room.sglog --pose truth --cell 0.05` maps with these settings.
OccupancyMap batchMap(const Dataset& data, const MapperSettings& settings) {
  Mapper m(data.ring, data.fittingGrid(PoseSource::Truth, 0.05), settings);
  m.mapDataset(data);
  return m.snapshot();
}

// The room log in `window`, mapped with HPF × addition on the true pose, 5 cm cells.
bool openRoom(app::MainWindow& window) {
  window.setCellSize(0.05);
  window.setMapperSettings(hpfAddition());
  window.show();
  return window.openLog(kRoom, true) && window.waitForMap(60000);
}

}  // namespace

class TestMainWindowPanel : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() {
    QStandardPaths::setTestModeEnabled(true);  // QSettings go to a scratch location
    QCoreApplication::setOrganizationName("SonarGridTest");
    QCoreApplication::setApplicationName("tst_main_window_panel");
    QSettings().clear();
    data_ = readSglog(kRoom.toStdString());
  }

  void sliderKeysRemapTheLog() {
    app::MainWindow window;
    QVERIFY(openRoom(window));
    const auto before = window.gridView()->map();
    QVERIFY(before->level == batchMap(data_, hpfAddition()).level);

    // HPF's ε spans [0.005, 1] m (hpf.cpp): 995 mm, so the slider moves in 1 mm steps
    // (ParameterPanel: the nice step ≥ range / 1000) over 995 positions, and PageUp moves
    // 995 / 20 = 49 of them. From the default 0.100 m (position 95) to position 144: 0.149 m.
    QSlider* slider = window.parameterPanel()->sliderFor("epsilon");
    QVERIFY(slider);
    QCOMPARE(slider->value(), 95);
    QSignalSpy changed(window.parameterPanel(), &ui::ParameterPanel::settingsChanged);
    QSignalSpy mapped(window.remapController(), &ui::RemapController::mapped);
    slider->setFocus();
    QTest::keyClick(slider, Qt::Key_PageUp);
    QCOMPARE(slider->value(), 144);
    QCOMPARE(changed.count(), 1);
    QCOMPARE(window.mapperSettings().parameters.get("epsilon"), 0.149);
    QCOMPARE(window.remapController()->settings().parameters.get("epsilon"), 0.149);
    QVERIFY(window.waitForMap(60000));
    QCOMPARE(mapped.count(), 1);

    MapperSettings expected = hpfAddition();
    expected.parameters.set("epsilon", 0.149);
    const OccupancyMap want = batchMap(data_, expected);
    const auto after = window.gridView()->map();
    QVERIFY(after->level == want.level);
    QVERIFY(after->native == want.native);
    QVERIFY(after->level != before->level);  // a wider occupied arc is a different map
    // The panel shows the time of that re-map; the beam view draws the new ε once the grid has
    // repainted (MainWindow defers it by 150 ms at most).
    QVERIFY(window.parameterPanel()->findChild<QLabel*>("remapTime")->text().contains("ms"));
    QTRY_COMPARE(window.beamModelView()->scenes().front().settings.parameters.get("epsilon"),
                 0.149);
  }

  void slowLogShowsAPreviewFirst() {
    // The window previews a change on 10 cm cells when the last full re-map took over a frame;
    // here the threshold is 0 so that the room log, fast or not, is previewed, and the time budget
    // is off, so the preview maps every scan (the thinned preview: tst_remap_controller). The
    // preview is what the CLI maps at 10 cm, shown in the same view, and the 5 cm map replaces it.
    app::MainWindow window;
    QVERIFY(openRoom(window));
    window.remapController()->setPreview(2, 0.0);
    window.remapController()->setPreviewBudget(0.0);
    const ui::ViewTransform view = window.gridView()->view();
    QSignalSpy previewed(window.remapController(), &ui::RemapController::previewed);
    QSlider* slider = window.parameterPanel()->sliderFor("epsilon");
    slider->setFocus();
    QTest::keyClick(slider, Qt::Key_PageUp);  // ε 0.100 → 0.149 m (sliderKeysRemapTheLog)
    QVERIFY(previewed.wait(60000));
    MapperSettings expected = hpfAddition();
    expected.parameters.set("epsilon", 0.149);
    const auto preview = window.gridView()->map();
    QCOMPARE(preview->spec.cellSize, 0.1);
    Mapper coarse(data_.ring, data_.fittingGrid(PoseSource::Truth, 0.1), expected);
    coarse.mapDataset(data_);
    QVERIFY(preview->level == coarse.snapshot().level);
    QCOMPARE(window.gridView()->view(), view);
    const auto* status = window.findChild<QLabel*>("remapStatus");
    QVERIFY(status);
    // "preview: 10 cm cells (N ms)…": every scan, so no "1 scan in N".
    QVERIFY2(status->text().startsWith("preview: 10 cm cells ("), qPrintable(status->text()));
    if (const QByteArray dir = qgetenv("SONARGRID_SNAPSHOT_DIR"); !dir.isEmpty())
      window.grab().save(QString::fromLocal8Bit(dir) + "/main-window-preview.png");
    QVERIFY(window.waitForMap(60000));
    QCOMPARE(window.gridView()->map()->spec.cellSize, 0.05);
    QVERIFY(window.gridView()->map()->level == batchMap(data_, expected).level);
    QCOMPARE(window.gridView()->view(), view);

    // Exporting while a preview is shown waits for the full map and writes it: the same bytes as
    // the 5 cm batch map written with the window's options (legend, 0.2 m / 0.05 m = 4 px a cell).
    QTest::keyClick(slider, Qt::Key_PageUp);  // ε 0.149 → 0.198 m
    QVERIFY(previewed.wait(60000));
    QCOMPARE(window.gridView()->map()->spec.cellSize, 0.1);
    QTemporaryDir dir;
    QVERIFY(window.exportMapPngTo(dir.filePath("map.png")));
    expected.parameters.set("epsilon", 0.198);
    PngOptions o;
    o.legend = true;
    o.unknown = kUnknownColour;  // the window draws never-observed cells in the unknown colour
    o.scale = 4;
    writeMapPng(batchMap(data_, expected), dir.filePath("want.png").toStdString(), o);
    QFile got(dir.filePath("map.png")), want(dir.filePath("want.png"));
    QVERIFY(got.open(QIODevice::ReadOnly) && want.open(QIODevice::ReadOnly));
    QVERIFY(got.readAll() == want.readAll());
  }

  void burstOfSliderMovesDeliversOnlyTheNewest() {
    app::MainWindow window;
    QVERIFY(openRoom(window));
    QSlider* slider = window.parameterPanel()->sliderFor("epsilon");
    QSignalSpy mapped(window.remapController(), &ui::RemapController::mapped);
    QSignalSpy cancelled(window.remapController(), &ui::RemapController::cancelled);
    const quint64 first = window.remapController()->latestGeneration() + 1;
    slider->setFocus();
    // Six moves with no event processing between them (QTest sends key events synchronously):
    // 0.100 m + 6 × 1 mm = 0.106 m.
    for (int i = 0; i < 6; ++i) QTest::keyClick(slider, Qt::Key_Right);
    QCOMPARE(window.remapController()->latestGeneration(), first + 5);
    QVERIFY(window.waitForMap(60000));
    QTRY_COMPARE_WITH_TIMEOUT(mapped.count() + cancelled.count(), 6, 30000);
    QCOMPARE(mapped.count(), 1);
    QCOMPARE(mapped.front().at(2).value<quint64>(), first + 5);
    QCOMPARE(cancelled.count(), 5);
    for (const QList<QVariant>& c : cancelled) QVERIFY(c.at(0).value<quint64>() < first + 5);

    MapperSettings expected = hpfAddition();
    expected.parameters.set("epsilon", 0.106);
    QCOMPARE(window.mapperSettings().parameters.get("epsilon"), 0.106);
    QVERIFY(window.gridView()->map()->level == batchMap(data_, expected).level);
  }

  void outsideChangesShowInThePanelOnce() {
    app::MainWindow window;
    QVERIFY(openRoom(window));
    QSignalSpy changed(window.parameterPanel(), &ui::ParameterPanel::settingsChanged);
    const quint64 generation = window.remapController()->latestGeneration();

    // As the Mapping menu does: another pair, its defaults.
    MapperSettings parameterized;
    parameterized.model = "parameterized";
    parameterized.rule = "bayes";
    parameterized.parameters = defaultParameters(parameterized.model, parameterized.rule);
    parameterized.pose = PoseSource::Truth;
    window.setMapperSettings(parameterized);
    QCOMPARE(changed.count(), 0);  // the panel shows it without sending it back
    QCOMPARE(window.remapController()->latestGeneration(), generation + 1);  // one re-map
    const MapperSettings shown = window.parameterPanel()->settings();
    QCOMPARE(shown.model, std::string("parameterized"));
    QCOMPARE(shown.rule, std::string("bayes"));
    QVERIFY(shown.parameters == parameterized.parameters);
    QVERIFY(window.parameterPanel()->sliderFor("p2"));
    QVERIFY(!window.parameterPanel()->sliderFor("epsilon"));
    QTRY_COMPARE(window.beamModelView()->scenes().front().settings.model,
                 std::string("parameterized"));

    // The same settings again map nothing.
    window.setMapperSettings(parameterized);
    QCOMPARE(window.remapController()->latestGeneration(), generation + 1);
    QVERIFY(window.waitForMap(60000));
    QVERIFY(window.gridView()->map()->level == batchMap(data_, parameterized).level);
  }

  void commandLineRuleIsNotNoted() {
    // The last session mapped with Konolige × log update; `sonargrid LOG --model parameterized
    // --rule bayes` names both (app/gui/main.cpp gives them with ruleNamed): the panel says
    // nothing of a rule change. Undo brings back a rule the user did not name: that is said.
    QSettings().setValue("mapping/model", "konolige");
    QSettings().setValue("mapping/rule", "log");
    app::MainWindow window;
    QCOMPARE(window.mapperSettings().rule, std::string("log"));
    MapperSettings named;
    named.model = "parameterized";
    named.rule = "bayes";
    named.parameters = defaultParameters(named.model, named.rule);
    window.setMapperSettings(named, /*ruleNamed=*/true);
    QCOMPARE(window.parameterPanel()->settings().rule, std::string("bayes"));
    QCOMPARE(window.parameterPanel()->statusText(), QString());
    window.document()->undoStack()->undo();
    QCOMPARE(window.parameterPanel()->settings().rule, std::string("log"));
    // "Rule changed from <title> to <title>" (ParameterPanel::ruleChangeNote; rules/bayes.cpp,
    // rules/log_rule.cpp).
    const QString note = window.parameterPanel()->statusText();
    QVERIFY2(note.startsWith(QStringLiteral("Rule changed from ") +
                             QString::fromStdString(updateRuleInfo("bayes").title) +
                             QStringLiteral(" to ") +
                             QString::fromStdString(updateRuleInfo("log").title)),
             qPrintable(note));
    QSettings().remove("mapping");
  }

  void beamViewShowsAReadingOfTheCurrentScan() {
    app::MainWindow window;
    QVERIFY(openRoom(window));
    window.timeline()->setTime(30.0);  // scan 300 of the 10 Hz log (tst_main_window)
    const Scan& scan = data_.scans[300];
    QCOMPARE(window.timeline()->currentScan(), std::size_t(300));

    // By default the first reading with an echo, its range as s, its beam highlighted.
    const auto firstEcho = std::find_if(scan.readings.begin(), scan.readings.end(),
                                        [](const Reading& r) { return r.echo(); });
    QVERIFY(firstEcho != scan.readings.end());
    QCOMPARE(window.beamSonar(), std::optional<std::size_t>(firstEcho->sonar));
    QCOMPARE(window.beamModelView()->range(), firstEcho->range);
    QCOMPARE(window.gridView()->scene().highlightedSonar, window.beamSonar());
    auto* chooser = window.findChild<QComboBox*>("readingChooser");
    QVERIFY(chooser);
    QCOMPARE(chooser->count(), static_cast<int>(scan.readings.size()));

    // The user picks the last reading with an echo; the choice follows the next scans.
    const auto lastEcho = std::find_if(scan.readings.rbegin(), scan.readings.rend(),
                                       [](const Reading& r) { return r.echo(); });
    QVERIFY(lastEcho->sonar != firstEcho->sonar);
    QVERIFY(window.chooseBeamSonar(lastEcho->sonar));
    QCOMPARE(window.beamModelView()->range(), lastEcho->range);
    QCOMPARE(window.gridView()->scene().highlightedSonar,
             std::optional<std::size_t>(lastEcho->sonar));
    window.timeline()->stepForward();
    const Scan& next = data_.scans[301];
    // Scan 301's reading of that sonar if it has one, else again its first reading with an echo.
    const Reading* want = nullptr;
    for (const Reading& r : next.readings)
      if (r.sonar == lastEcho->sonar) want = &r;
    for (const Reading& r : next.readings)
      if (!want && r.echo()) want = &r;
    QVERIFY(want);
    QCOMPARE(window.beamSonar(), std::optional<std::size_t>(want->sonar));
    // Without an echo the view draws a reading at the maximum range.
    QCOMPARE(window.beamModelView()->range(), want->echo() ? want->range : data_.ring.maxRange);
    QVERIFY(window.waitForMap(60000));
  }

  // docs/forward-model.md: with the forward model the beam dock shows, for the current reading,
  // the range distribution the EM map predicts, with the measured range on it; the distribution
  // is one (its density over [0, z_max] and P(no echo) add up to 1, up to the 400-sample sum and
  // the Gaussians of cells within 4σ of 0 or z_max that reach past them).
  void theForwardModelShowsItsPrediction() {
    app::MainWindow window;
    QVERIFY(openRoom(window));
    QVERIFY(!window.forwardRangeView()->isVisibleTo(&window));
    MapperSettings em;
    em.model = forward::kModelName;
    em.rule = forward::kRuleName;
    em.pose = PoseSource::Truth;
    em.parameters = forward::defaultForwardParameters();
    em.parameters.set("iterations", 5);
    window.setMapperSettings(em);
    QVERIFY(window.waitForMap(60000));
    QCOMPARE(window.gridView()->map()->model, std::string("forward-em"));
    QVERIFY(window.forwardRangeView()->isVisibleTo(&window));
    QVERIFY(!window.beamModelView()->isVisibleTo(&window));
    const ui::ForwardRangeView* view = window.forwardRangeView();
    QTRY_VERIFY(!view->ranges().empty());
    const auto sonar = window.beamSonar();
    QVERIFY(sonar);
    const Scan& scan = data_.scans[window.timeline()->currentScan()];
    for (const Reading& r : scan.readings) {
      if (r.sonar != *sonar) continue;
      if (r.echo() && r.range < data_.ring.maxRange)
        QCOMPARE(view->measured(), std::optional<double>(r.range));
      else
        QVERIFY(!view->measured());
    }
    double total = view->prediction().noEcho;
    const double dz = view->ranges()[1] - view->ranges()[0];
    for (const double d : view->prediction().density) total += d * dz;
    QVERIFY2(std::abs(total - 1.0) < 0.02, qPrintable(QString::number(total)));
  }

 private:
  Dataset data_;
};

QTEST_MAIN(TestMainWindowPanel)
#include "tst_main_window_panel.moc"
