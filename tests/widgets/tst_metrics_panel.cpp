// SPDX-License-Identifier: GPL-3.0-or-later
// The metrics panel and the comparison table in the window, offscreen (issue 12 items 3 and 4):
// the panel shows what `sonargrid-cli score` computes for the same log, reference and settings
// (the CLI's own core calls repeated here: read the log, map it on its fitting grid at --cell,
// scoreAgainstReference with the default options), goodness without a reference as `goodness`
// computes it, the D_min tint of the scored map, and the comparison table's rows, CSV and
// common cells.

#include <QDockWidget>
#include <QSlider>
#include <QStandardPaths>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QUndoStack>
#include <QtTest>

#include "comparison_table.h"
#include "dmin_overlay.h"
#include "document.h"
#include "grid_view.h"
#include "main_window.h"
#include "metrics_panel.h"
#include "parameter_panel.h"
#include "remap_controller.h"
#include "sonargrid/io/sglog.h"
#include "sonargrid/metrics/derivative_noise.h"
#include "sonargrid/metrics/vsdns.h"
#include "sonargrid/reference/reference_json.h"

using namespace sg;
using namespace sg::ui;

namespace {

const char* kRoomLog = SONARGRID_DATASETS "/room/room.sglog";
const char* kRoomReference = SONARGRID_DATASETS "/room/room.json";

MapperSettings settingsOf(const std::string& model, const std::string& rule) {
  MapperSettings s;
  s.model = model;
  s.rule = rule;
  s.parameters = defaultParameters(model, rule);
  return s;
}

// What `sonargrid-cli score --log LOG --model M --rule R --cell C` maps: the log on its fitting
// grid at C with the default parameters (command_map.cpp buildMap).
OccupancyMap cliMap(const Dataset& data, const MapperSettings& settings, double cell) {
  Mapper mapper(data.ring, data.fittingGrid(settings.pose, cell), settings);
  mapper.mapDataset(data);
  return mapper.snapshot();
}

// Opens the room log in a window with `settings` at `cell` (and the room reference) and waits for
// the panel's numbers.
bool openRoom(app::MainWindow& window, const MapperSettings& settings, double cell,
              bool reference) {
  window.setCellSize(cell);
  window.setMapperSettings(settings);
  if (reference && !window.openReference(kRoomReference, true)) return false;
  if (!window.openLog(kRoomLog, true) || !window.waitForMap(120000)) return false;
  // The window takes room.json beside room.sglog along: closed for a run without a reference.
  if (!reference) window.document()->setReference(std::nullopt, {});
  auto* panel = window.findChild<MetricsPanel*>();
  return panel && panel->waitForResult(120000) && panel->result();
}

}  // namespace

class TestMetricsPanel : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() {
    QStandardPaths::setTestModeEnabled(true);  // QSettings go to a scratch location
    QCoreApplication::setOrganizationName("SonarGridTests");
    QCoreApplication::setApplicationName("tst_metrics_panel");
  }

  void dminColours_data() {
    QTest::addColumn<double>("mm");
    QTest::addColumn<QColor>("colour");
    // The scale of dmin_overlay.h: green on the reference, yellow at 150 mm, red from 300 mm;
    // 75 mm is half way from green (0, 200, 60) to yellow (255, 220, 0): (127.5, 210, 30).
    QTest::newRow("on the reference") << 0.0 << QColor(0, 200, 60);
    QTest::newRow("half way to yellow") << 75.0 << QColor(128, 210, 30);
    QTest::newRow("yellow") << 150.0 << QColor(255, 220, 0);
    QTest::newRow("red") << 300.0 << QColor(230, 20, 20);
    QTest::newRow("far") << 5000.0 << QColor(230, 20, 20);
  }

  void dminColours() {
    QFETCH(double, mm);
    QFETCH(QColor, colour);
    const QColor c = dminColour(mm);
    QVERIFY2(std::abs(c.red() - colour.red()) <= 1 && std::abs(c.green() - colour.green()) <= 1 &&
                 std::abs(c.blue() - colour.blue()) <= 1,
             qPrintable(c.name() + " vs " + colour.name()));
  }

  void dminTintColoursFilledCellsOnly() {
    // 3 x 2 cells of 10 cm; filled: (0, 0) on the reference, (2, 0) 2 cells = 200 mm away,
    // (1, 1) 4 cells = 400 mm away. The image's row 0 is the grid's top row (iy = 1).
    GridSpec spec;
    spec.cellSize = 0.1;
    spec.width = 3;
    spec.height = 2;
    OccupancyMap map = OccupancyMap::unobserved(spec);
    map.filled = {1, 0, 1, 0, 1, 0};
    const QImage tint = dminTintImage(map, {0.f, 1.f, 2.f, 3.f, 4.f, 5.f});
    QCOMPARE(tint.size(), QSize(3, 2));
    QCOMPARE(QColor(tint.pixel(0, 1)).rgb(), dminColour(0.0).rgb());
    QCOMPARE(QColor(tint.pixel(2, 1)).rgb(), dminColour(200.0).rgb());
    QCOMPARE(QColor(tint.pixel(1, 0)).rgb(), dminColour(400.0).rgb());
    QCOMPARE(qAlpha(tint.pixel(1, 1)), 0);  // (1, 0) is not filled
    QCOMPARE(qAlpha(tint.pixel(0, 0)), 0);  // (0, 1)
    QVERIFY(qAlpha(tint.pixel(0, 1)) > 0);
  }

  void panelEqualsScore_data() {
    QTest::addColumn<QString>("model");
    QTest::addColumn<QString>("rule");
    QTest::addColumn<double>("cell");
    QTest::newRow("himm x himm, 10 cm") << "himm"
                                        << "himm" << 0.1;
    QTest::newRow("hpf x addition, 5 cm") << "hpf"
                                          << "addition" << 0.05;
  }

  void panelEqualsScore() {
    QFETCH(QString, model);
    QFETCH(QString, rule);
    QFETCH(double, cell);
    const MapperSettings settings = settingsOf(model.toStdString(), rule.toStdString());
    app::MainWindow window(GridView::Backend::Raster);
    QVERIFY(openRoom(window, settings, cell, true));
    const MetricsResult* shown = window.findChild<MetricsPanel*>()->result();
    QVERIFY(shown->score);

    const Dataset data = readSglog(kRoomLog);
    const OccupancyMap map = cliMap(data, settings, cell);
    const ReferenceScore expected = scoreAgainstReference(map, readReferenceJson(kRoomReference));
    QCOMPARE(shown->spec, map.spec);
    for (Metric m : allMetrics()) {
      const std::optional<double> a = shown->score->value(m), b = expected.value(m);
      QVERIFY2(a.has_value() == b.has_value(), metricName(m));
      if (a) QCOMPARE(*a, *b);  // the same core call on the same map: the same bits
    }
    QCOMPARE(shown->score->cellsEvaluated, expected.cellsEvaluated);
    QVERIFY(*expected.value(Metric::Iop) > 0.0);

    // The table shows IOP with its unit and a tooltip naming paper 000 and eq 9.
    auto* table = window.findChild<QTableWidget*>(QStringLiteral("metricsTable"));
    QVERIFY(table);
    bool found = false;
    for (int r = 0; r < table->rowCount(); ++r) {
      if (!table->item(r, 1) || table->item(r, 1)->data(Qt::UserRole).toString() != "iop_mm")
        continue;
      found = true;
      QCOMPARE(table->item(r, 0)->text(), QStringLiteral("IOP"));
      QCOMPARE(table->item(r, 1)->text(), QString::number(*expected.value(Metric::Iop), 'f', 1));
      QCOMPARE(table->item(r, 2)->text(), QStringLiteral("mm"));
      QVERIFY(table->item(r, 1)->toolTip().contains("Paper 000"));
      QVERIFY(table->item(r, 1)->toolTip().contains("eq 9"));
    }
    QVERIFY(found);
    // Every number carries a tooltip naming a paper.
    for (int r = 0; r < table->rowCount(); ++r)
      if (table->item(r, 1))
        QVERIFY2(table->item(r, 1)->toolTip().contains("Paper 00"),
                 qPrintable(table->item(r, 0)->text()));

    // The D_min tint of that map reaches the grid view, on the map's grid.
    const GridScene& scene = window.gridView()->scene();
    QVERIFY(scene.dminTint && !scene.dminTint->isNull());
    QCOMPARE(scene.dminSpec, map.spec);
    QCOMPARE(scene.dminTint->size(), QSize(map.spec.width, map.spec.height));
  }

  void referenceEditRescores() {
    app::MainWindow window(GridView::Backend::Raster);
    QVERIFY(openRoom(window, settingsOf("himm", "himm"), 0.1, true));
    auto* panel = window.findChild<MetricsPanel*>();
    const double before = *panel->result()->value("iop_mm");
    // The reference moved 0.5 m along x: the map's evidence is farther from it.
    ReferenceMap moved = *window.document()->reference();
    for (ReferenceObject& o : moved.objects)
      for (auto& corner : o.corners) corner.x() += 0.5 / moved.metresPerUnit();
    window.document()->setReference(moved, QString());
    QVERIFY(panel->waitForResult(120000));
    const Dataset data = readSglog(kRoomLog);
    const ReferenceScore expected =
        scoreAgainstReference(cliMap(data, settingsOf("himm", "himm"), 0.1), moved);
    QCOMPARE(*panel->result()->value("iop_mm"), *expected.value(Metric::Iop));
    QVERIFY(*expected.value(Metric::Iop) != before);
  }

  void goodnessWithoutReference() {
    const MapperSettings settings = settingsOf("himm", "himm");
    app::MainWindow window(GridView::Backend::Raster);
    QVERIFY(openRoom(window, settings, 0.1, false));
    const MetricsResult* shown = window.findChild<MetricsPanel*>()->result();
    QVERIFY(!shown->score);
    QVERIFY(shown->goodness);
    // `sonargrid-cli goodness`: the log mapped on its fitting grid with a VSDNS observer, the
    // derivative noise of that map.
    const Dataset data = readSglog(kRoomLog);
    Mapper mapper(data.ring, data.fittingGrid(settings.pose, 0.1), settings);
    VsdnsAccumulator vsdns;
    mapper.setObserver(&vsdns);
    mapper.mapDataset(data);
    const DerivativeNoise noise = derivativeNoise(mapper.snapshot());
    QCOMPARE(*shown->value("vsdns"), *vsdns.result().vsdns);
    QCOMPARE(*shown->value("derivative_noise"), noise.sum);
    QCOMPARE(*shown->value("derivative_noise_mean"), *noise.mean);
    QVERIFY(!shown->value("two_run_positive"));  // no second run
  }

  void draggedSliderScoresOnlyTheMapItStopsAt() {
    // A dragged slider: each step starts a re-map (awaitMap) and delivers its map (setMap). The
    // panel scores a delivered map only once MetricsPanel::kSettleMs pass without another re-map,
    // so the steps it passes through are never scored: one computation (generation + 1) for the
    // map of the last step. Maps A and B differ in their grids, which the result names.
    GridSpec a, b;
    a.cellSize = b.cellSize = 0.1;
    a.width = 3;
    a.height = 2;
    b.width = 4;
    b.height = 5;
    MetricsPanel panel;
    panel.setMap(std::make_shared<const OccupancyMap>(OccupancyMap::unobserved(a)));
    QVERIFY(panel.waitForResult(10000));
    QCOMPARE(panel.result()->spec, a);
    const quint64 before = panel.generation();

    panel.awaitMap();  // step 1 re-maps
    QVERIFY(panel.busy());
    panel.setMap(std::make_shared<const OccupancyMap>(OccupancyMap::unobserved(b)));
    QCoreApplication::processEvents();  // a zero-delay start would run here; the settle waits
    QCOMPARE(panel.generation(), before);
    QVERIFY(panel.busy());
    panel.awaitMap();  // step 2 re-maps before the settle: step 1's map B is never scored
    panel.setMap(std::make_shared<const OccupancyMap>(OccupancyMap::unobserved(a)));
    QVERIFY(panel.waitForResult(10000));
    QCOMPARE(panel.generation(), before + 1);
    QCOMPARE(panel.result()->spec, a);

    // A re-map that brings no map (failed): resume() scores the map the panel has.
    panel.awaitMap();
    QVERIFY(panel.busy());
    panel.resume();
    QVERIFY(panel.waitForResult(10000));
    QCOMPARE(panel.generation(), before + 2);
    QCOMPARE(panel.result()->spec, a);
    // Any other input still scores at once, as before.
    panel.setMap(std::make_shared<const OccupancyMap>(OccupancyMap::unobserved(b)));
    QCoreApplication::processEvents();
    QCOMPARE(panel.generation(), before + 3);
    QVERIFY(panel.waitForResult(10000));
    QCOMPARE(panel.result()->spec, b);

    // The slider let go while its map waits for the settle: scored at once, not kSettleMs later.
    panel.awaitMap();
    panel.setMap(std::make_shared<const OccupancyMap>(OccupancyMap::unobserved(a)));
    QVERIFY(panel.settling());
    QCOMPARE(panel.generation(), before + 3);
    panel.endSettle();
    QVERIFY(!panel.settling());
    QCOMPARE(panel.generation(), before + 4);  // started in endSettle() itself
    QVERIFY(panel.waitForResult(10000));
    QCOMPARE(panel.result()->spec, a);

    // A single change (a key, the wheel, the spin box): its map is scored as soon as it arrives.
    panel.awaitMap();
    panel.scoreAtOnce();
    panel.setMap(std::make_shared<const OccupancyMap>(OccupancyMap::unobserved(b)));
    QVERIFY(!panel.settling());
    QCoreApplication::processEvents();  // the zero-delay start
    QCOMPARE(panel.generation(), before + 5);
    QVERIFY(panel.waitForResult(10000));
    QCOMPARE(panel.result()->spec, b);
    // ... and only that change: the next re-map's map (a timeline tick) waits for the settle.
    panel.awaitMap();
    panel.setMap(std::make_shared<const OccupancyMap>(OccupancyMap::unobserved(a)));
    QVERIFY(panel.settling());
    QVERIFY(panel.waitForResult(10000));
    QCOMPARE(panel.generation(), before + 6);
    QCOMPARE(panel.result()->spec, a);
  }

  void windowWaitsForTheNewMapBeforeScoring() {
    // The window's wiring: a settings change starts a re-map (RemapController::started), the panel
    // awaits its map and then shows that map's numbers, never the old map's.
    app::MainWindow window(GridView::Backend::Raster);
    QVERIFY(openRoom(window, settingsOf("himm", "himm"), 0.1, true));
    auto* panel = window.findChild<MetricsPanel*>();
    QSignalSpy started(window.remapController(), &RemapController::started);
    window.setMapperSettings(settingsOf("hpf", "addition"));
    QCOMPARE(started.count(), 1);
    QCOMPARE(started.at(0).at(0).value<quint64>(), window.remapController()->latestGeneration());
    QVERIFY(panel->busy());
    QVERIFY(window.waitForMap(120000));
    QVERIFY(panel->waitForResult(120000));
    const Dataset data = readSglog(kRoomLog);
    const ReferenceMap reference = *window.document()->reference();
    const ReferenceScore expected =
        scoreAgainstReference(cliMap(data, settingsOf("hpf", "addition"), 0.1), reference);
    QCOMPARE(*panel->result()->value("iop_mm"), *expected.value(Metric::Iop));
  }

  void windowScoresASingleChangeAtOnce() {
    // The window's wiring of the settle: a parameter changed by a key on its slider (not held) is
    // scored as soon as its map arrives; a change from elsewhere (setMapperSettings, as a menu or
    // the timeline makes one) waits for the settle; a slider held down waits too, until let go.
    app::MainWindow window(GridView::Backend::Raster);
    QVERIFY(openRoom(window, settingsOf("himm", "himm"), 0.1, true));
    auto* panel = window.findChild<MetricsPanel*>();
    QVERIFY(panel->waitForResult(120000));
    QSlider* slider = window.parameterPanel()->sliderFor("p_hit");
    QVERIFY(slider);
    // Each change below re-maps (a new generation), so each waitForMap() waits for a map.
    auto step = [&](QAbstractSlider::SliderAction action) {
      const quint64 before = window.remapController()->latestGeneration();
      slider->triggerAction(action);  // what a key or the wheel does to the slider
      return window.remapController()->latestGeneration() == before + 1;
    };
    QVERIFY(step(QAbstractSlider::SliderSingleStepAdd));
    QVERIFY(window.waitForMap(120000));  // returns right after the panel was given the map
    QVERIFY(!panel->settling());
    QVERIFY(panel->waitForResult(120000));

    MapperSettings other = window.mapperSettings();
    other.parameters.set("p_miss", 0.3);
    const quint64 before = window.remapController()->latestGeneration();
    window.setMapperSettings(other);
    QCOMPARE(window.remapController()->latestGeneration(), before + 1);
    QVERIFY(window.waitForMap(120000));
    QVERIFY(panel->settling());
    QVERIFY(panel->waitForResult(120000));

    emit slider->sliderPressed();  // held: its steps wait
    QVERIFY(step(QAbstractSlider::SliderSingleStepAdd));
    QVERIFY(window.waitForMap(120000));
    QVERIFY(panel->settling());
    emit slider->sliderReleased();  // let go: scored now
    QVERIFY(!panel->settling());
    QVERIFY(panel->waitForResult(120000));
  }

  void closingMidComputationIsSafe() {
    // The window goes while the panel (and a pinned row) are still computing.
    auto* window = new app::MainWindow(GridView::Backend::Raster);
    window->openReference(kRoomReference, true);
    QVERIFY(window->openLog(kRoomLog, true));
    window->waitForMap(120000);
    window->document()->pinRow({"a", window->mapperSettings(), window->document()->cellSize()});
    QCoreApplication::processEvents();
    delete window;
    QVERIFY(true);  // reaching here without a crash or a hang is the test
  }

  void comparisonRowsExportAndCommonCells() {
    app::MainWindow window(GridView::Backend::Raster);
    QVERIFY(openRoom(window, settingsOf("himm", "himm"), 0.1, true));
    auto* table = window.findChild<ComparisonTable*>();
    QVERIFY(table);
    app::Document* doc = window.document();
    emit table->pinRequested();  // himm x himm at 10 cm
    window.setMapperSettings(settingsOf("hpf", "addition"));
    QVERIFY(window.waitForMap(120000));
    emit table->pinRequested();  // hpf x addition at 10 cm
    QCOMPARE(doc->pinnedRows().size(), std::size_t{2});
    QVERIFY(table->waitForResult(240000));
    QVERIFY(table->result(0, CellSet::Common) && table->result(1, CellSet::Common));

    // Each map on its own cells: the score of the CLI's map of the row's configuration.
    const Dataset data = readSglog(kRoomLog);
    const ReferenceMap ref = readReferenceJson(kRoomReference);
    std::vector<OccupancyMap> maps;
    for (const char* pair : {"himm", "hpf"}) {
      const MapperSettings s =
          pair == std::string("himm") ? settingsOf("himm", "himm") : settingsOf("hpf", "addition");
      maps.push_back(cliMap(data, s, 0.1));
    }
    for (std::size_t r = 0; r < 2; ++r) {
      const ReferenceScore own = scoreAgainstReference(maps[r], ref);
      QCOMPARE(*table->result(r, CellSet::EachMap)->value("iop_mm"), *own.value(Metric::Iop));
      QCOMPARE(table->result(r, CellSet::EachMap)->score->cellsEvaluated, own.cellsEvaluated);
    }
    // The common cells: the same count for every row, no more than either map's own, and the
    // score with the cell mask both maps observed (both are on one grid here).
    const std::size_t common0 = table->result(0, CellSet::Common)->score->cellsEvaluated;
    const std::size_t common1 = table->result(1, CellSet::Common)->score->cellsEvaluated;
    QCOMPARE(common0, common1);
    QVERIFY(common0 > 0);
    QVERIFY(common0 <= table->result(0, CellSet::EachMap)->score->cellsEvaluated);
    QVERIFY(common0 <= table->result(1, CellSet::EachMap)->score->cellsEvaluated);
    QCOMPARE(maps[0].spec, maps[1].spec);
    ScoreOptions masked;
    for (std::size_t i = 0; i < maps[0].spec.cellCount(); ++i)
      masked.cellMask.push_back(maps[0].observed[i] && maps[1].observed[i] ? 1 : 0);
    QCOMPARE(*table->result(1, CellSet::Common)->value("iop_mm"),
             *scoreAgainstReference(maps[1], ref, masked).value(Metric::Iop));

    // The CSV: a header of the score --json keys and one line per row with those numbers.
    table->setCellSet(CellSet::Common);
    QTemporaryDir dir;
    const QString csvPath = dir.filePath("comparison.csv");
    QCOMPARE(table->exportTo(csvPath), QString());
    QFile csv(csvPath);
    QVERIFY(csv.open(QIODevice::ReadOnly));
    const QStringList lines = QString::fromUtf8(csv.readAll()).split('\n', Qt::SkipEmptyParts);
    QCOMPARE(lines.size(), 3);
    const QStringList header = lines[0].split(',');
    const int iop = static_cast<int>(header.indexOf("iop_mm"));
    const int cells = static_cast<int>(header.indexOf("cells_evaluated"));
    QVERIFY(iop > 0 && cells > 0);
    for (int r = 0; r < 2; ++r) {
      const QStringList f = lines[r + 1].split(',');
      QCOMPARE(f.size(), header.size());
      QCOMPARE(f[iop].toDouble(), *table->result(std::size_t(r))->value("iop_mm"));
      QCOMPARE(f[cells].toULongLong(), qulonglong(common0));
    }
    QVERIFY(lines[1].startsWith(doc->pinnedRows()[0].label));
    const QString mdPath = dir.filePath("comparison.md");
    QCOMPARE(table->exportTo(mdPath), QString());
    QFile md(mdPath);
    QVERIFY(md.open(QIODevice::ReadOnly));
    const QString markdown = QString::fromUtf8(md.readAll());
    QVERIFY(markdown.startsWith("| row | model × rule | pose | cell (m) | IOP (mm) |"));
    QCOMPARE(markdown.count("\n| R"), 2);

    // Clicking row 0 restores himm x himm: one undo step, which undo takes back.
    QUndoStack* stack = doc->undoStack();
    const int steps = stack->count();
    emit table->rowActivated(0);
    QCOMPARE(doc->mapperSettings().model, std::string("himm"));
    QCOMPARE(stack->count(), steps + 1);
    stack->undo();
    QCOMPARE(doc->mapperSettings().model, std::string("hpf"));
    // Unpinning is undoable too.
    emit table->removeRequested(0);
    QCOMPARE(doc->pinnedRows().size(), std::size_t{1});
    stack->undo();
    QCOMPARE(doc->pinnedRows().size(), std::size_t{2});
  }

  void commonMaskAcrossGrids() {
    // Two maps of the same ground on different cells: a 10 cm map's cell counts when the 20 cm
    // map observed the cell holding its centre. 2 x 1 cells of 20 cm, (0) observed; 4 x 2 cells
    // of 10 cm, all observed: the common cells of the fine map are those over x < 0.2 m.
    GridSpec coarse;
    coarse.cellSize = 0.2;
    coarse.width = 2;
    coarse.height = 1;
    GridSpec fine;
    fine.cellSize = 0.1;
    fine.width = 4;
    fine.height = 2;
    OccupancyMap a = OccupancyMap::unobserved(coarse), b = OccupancyMap::unobserved(fine);
    a.observed = {1, 0};
    b.observed.assign(8, 1);
    const std::vector<const OccupancyMap*> maps{&a, &b};
    QCOMPARE(commonObservedCells(maps, 1), (std::vector<std::uint8_t>{1, 1, 0, 0, 1, 1, 0, 0}));
    QCOMPARE(commonObservedCells(maps, 0), (std::vector<std::uint8_t>{1, 0}));
  }
};

QTEST_MAIN(TestMetricsPanel)
#include "tst_metrics_panel.moc"
