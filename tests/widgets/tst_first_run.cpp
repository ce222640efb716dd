// SPDX-License-Identifier: GPL-3.0-or-later
// What a new user meets in the first ten minutes, offscreen: a new log replaces a reference drawn
// for another room with its own dataset's (dataset.json manifests), File ▸ Open Example lists the
// bundled datasets, the Export items wait for a map, the default window keeps half its width for
// the grid and every slider usable, and the Help tour changes the window's model as it steps.

#include <QAction>
#include <QDir>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QListWidget>
#include <QSettings>
#include <QSlider>
#include <QStandardPaths>
#include <QStyleOptionSlider>
#include <QTemporaryDir>
#include <QUndoStack>
#include <QtTest>

#include "dataset_manifest.h"
#include "document.h"
#include "example_chooser.h"
#include "grid_view.h"
#include "main_window.h"
#include "parameter_panel.h"
#include "sonargrid/metrics/reference_score.h"
#include "sonargrid/params/presets.h"
#include "tour_dialog.h"

using namespace sg;
using namespace sg::app;

namespace {

const QString kDatasets = QStringLiteral(SONARGRID_DATASETS);

QString dataset(const QString& relative) {
  return QDir(kDatasets).filePath(relative);
}

bool anyLabelSays(const QWidget& w, const QString& text) {
  for (const QLabel* l : w.findChildren<QLabel*>())
    if (l->text().contains(text)) return true;
  return false;
}

QAction* actionNamed(const QWidget& w, const QString& text) {
  for (QAction* a : w.findChildren<QAction*>())
    if (a->text() == text) return a;
  return nullptr;
}

// One undoable edit of the document's settings, whatever the window chose (it remembers the last
// settings): HPF × addition with an ε other than its own.
void editSettings(MainWindow& w) {
  MapperSettings s = w.document()->mapperSettings();
  const bool was023 = s.model == "hpf" && s.parameters.get("epsilon") == 0.23;
  s.model = "hpf";
  s.rule = "addition";
  s.parameters = defaultParameters("hpf", "addition");
  s.parameters.set("epsilon", was023 ? 0.31 : 0.23);
  w.document()->setMapperSettings(s);
}

}  // namespace

class TestFirstRun : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() {
    QStandardPaths::setTestModeEnabled(true);  // QSettings go to a scratch location
    QCoreApplication::setOrganizationName("SonarGridTest");
    QCoreApplication::setApplicationName("tst_first_run");
    QSettings().clear();
  }

  void everyBundledDatasetDeclaresItsReference_data() {
    QTest::addColumn<QString>("folder");
    QTest::addColumn<QString>("reference");
    QTest::addColumn<QString>("example");
    // datasets/README.md: each folder's reference map and its first run.
    QTest::newRow("arafat-room") << "arafat-room"
                                 << "world.json"
                                 << "run-1.sglog";
    QTest::newRow("office") << "office"
                            << "world.json"
                            << "office.sglog";
    QTest::newRow("raschke-multi") << "raschke-multi"
                                   << "world.json"
                                   << "in-motion-01.sglog";
    QTest::newRow("raschke-single") << "raschke-single"
                                    << "world.json"
                                    << "in-motion-01.sglog";
    QTest::newRow("room") << "room"
                          << "room.json"
                          << "room.sglog";
  }

  void everyBundledDatasetDeclaresItsReference() {
    QFETCH(QString, folder);
    QFETCH(QString, reference);
    QFETCH(QString, example);
    const std::optional<DatasetManifest> m = readDatasetManifest(dataset(folder));
    QVERIFY(m.has_value());
    QCOMPARE(m->name, folder);
    QCOMPARE(QFileInfo(m->reference).fileName(), reference);
    QCOMPARE(QFileInfo(m->example).fileName(), example);
    QVERIFY(!m->title.isEmpty());
    QVERIFY(!m->description.isEmpty() && !m->description.contains('\n'));
    // Any log of the folder finds the same manifest.
    QCOMPARE(manifestForLog(m->example)->reference, m->reference);
  }

  void badManifestsAreNamed_data() {
    QTest::addColumn<QByteArray>("json");
    QTest::addColumn<QString>("says");
    const QByteArray head = R"("format": "sonargrid-dataset", "version": 1, )";
    QTest::newRow("not JSON") << QByteArray("{ nope") << "not valid JSON";
    QTest::newRow("wrong format") << QByteArray(R"({"format": "x", "version": 1})") << "\"format\"";
    QTest::newRow("no title") << "{" + head + R"("description": "d", "example": "a.sglog"})"
                              << "\"title\" is missing";
    QTest::newRow("missing example")
        << "{" + head + R"("title": "t", "description": "d", "example": "b.sglog"})"
        << "\"example\": ";
    QTest::newRow("reference outside")
        << "{" + head +
               R"("title": "t", "description": "d", "example": "a.sglog", "reference": "../x.json"})"
        << "must name a file in the dataset's folder";
    QTest::newRow("two-line description")
        << "{" + head + R"("title": "t", "description": "one\ntwo", "example": "a.sglog"})"
        << "one line";
  }

  void badManifestsAreNamed() {
    QFETCH(QByteArray, json);
    QFETCH(QString, says);
    QTemporaryDir dir;
    QFile log(dir.filePath("a.sglog"));
    QVERIFY(log.open(QIODevice::WriteOnly));
    log.close();
    QFile f(dir.filePath(kManifestName));
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write(json);
    f.close();
    try {
      readDatasetManifest(dir.path());
      QFAIL("no error");
    } catch (const ManifestError& e) {
      const QString message = QString::fromUtf8(e.what());
      QVERIFY2(message.contains(says), qPrintable(message));
      QVERIFY2(message.contains(kManifestName), qPrintable(message));
    }
    QString error;
    QVERIFY(!manifestForLog(dir.filePath("a.sglog"), &error).has_value());
    QVERIFY(error.contains(says));
  }

  void newLogReplacesAStaleReference() {
    MainWindow w(ui::GridView::Backend::Raster);
    QVERIFY(w.openLog(dataset("room/room.sglog"), true));
    QCOMPARE(QFileInfo(w.document()->referencePath()).fileName(), QString("room.json"));
    QVERIFY(anyLabelSays(w, "room.json"));
    // Another room's log: the room's walls go, raschke-multi's own reference comes (its manifest).
    QVERIFY(w.openLog(dataset("raschke-multi/in-motion-02.sglog"), true));
    QCOMPARE(QDir::cleanPath(w.document()->referencePath()),
             QDir::cleanPath(dataset("raschke-multi/world.json")));
    QVERIFY(w.document()->reference().has_value());
    QVERIFY(!anyLabelSays(w, "room.json"));
    QVERIFY(anyLabelSays(w, "world.json"));
    // A new log is a new document with a history of its own (issue 49): no undo puts the room's
    // walls back over raschke-multi's log.
    QVERIFY(!w.document()->undoStack()->canUndo());
    // Another run of the same dataset keeps its reference: nothing closed, no undo step.
    QVERIFY(w.openLog(dataset("raschke-multi/in-motion-03.sglog"), true));
    QVERIFY(!w.document()->undoStack()->canUndo());
    QCOMPARE(QDir::cleanPath(w.document()->referencePath()),
             QDir::cleanPath(dataset("raschke-multi/world.json")));
  }

  void undoStaysInItsDocument() {
    // Issue 49 item 4: an edit of the room's document, then another log opened: Undo has nothing
    // to undo (it put the room's reference over raschke-multi's log, IOP 696 mm), and the edit
    // made before stays as it was.
    MainWindow w(ui::GridView::Backend::Raster);
    QVERIFY(w.openLog(dataset("room/room.sglog"), true));
    editSettings(w);
    QVERIFY(w.document()->undoStack()->canUndo());
    QVERIFY(w.openLog(dataset("raschke-multi/in-motion-02.sglog"), true));
    QVERIFY(!w.document()->undoStack()->canUndo());
    QCOMPARE(QDir::cleanPath(w.document()->referencePath()),
             QDir::cleanPath(dataset("raschke-multi/world.json")));
  }

  void openingAsksBeforeReplacingAModifiedDocument() {
    // Issue 49 item 3: the tour and a recent log replaced a modified document (`*` in the title)
    // without asking. Answered "cancel" (SONARGRID_UNSAVED_CHANGES answers the question for
    // tests), each leaves the document as it was.
    struct Cancel {
      Cancel() { qputenv("SONARGRID_UNSAVED_CHANGES", "cancel"); }
      ~Cancel() { qunsetenv("SONARGRID_UNSAVED_CHANGES"); }
    } cancel;
    MainWindow w(ui::GridView::Backend::Raster);
    QVERIFY(w.openLog(dataset("raschke-multi/in-motion-02.sglog"), true));
    QVERIFY(w.openLog(dataset("room/room.sglog"), true));
    editSettings(w);
    QVERIFY(w.document()->isModified());
    QAction* tour = w.findChild<QAction*>(QStringLiteral("tourAction"));
    QVERIFY(tour);
    tour->trigger();
    QVERIFY(!w.findChild<TourDialog*>());
    QAction* recent = nullptr;
    for (QAction* a : w.findChildren<QAction*>())
      if (a->text().endsWith(QStringLiteral("in-motion-02.sglog"))) recent = a;
    QVERIFY(recent);
    recent->trigger();
    QTest::qWait(300);  // a load that had started would be under way by now
    QCOMPARE(QFileInfo(w.document()->logPath()).fileName(), QString("room.sglog"));
    QVERIFY(w.document()->isModified());
    QCOMPARE(w.document()->mapperSettings().model, std::string("hpf"));
  }

  void exampleChooserListsTheBundledDatasets() {
    const std::vector<DatasetManifest> all = datasetManifests(kDatasets);
    QCOMPARE(all.size(), std::size_t{5});  // the five folders of datasets/README.md
    ExampleChooser chooser(all);
    QCOMPARE(chooser.list()->count(), 5);
    for (int i = 0; i < 5; ++i) {
      const QListWidgetItem* item = chooser.list()->item(i);
      QVERIFY(item->text().contains(all[std::size_t(i)].title));
      QVERIFY(item->text().contains(all[std::size_t(i)].description));
      QVERIFY(!item->icon().isNull());
      // The thumbnail draws the reference: dark ink on white.
      const QImage thumb = ExampleChooser::thumbnail(all[std::size_t(i)], {120, 80});
      int ink = 0;
      for (int y = 0; y < thumb.height(); ++y)
        for (int x = 0; x < thumb.width(); ++x) ink += qGray(thumb.pixel(x, y)) < 128;
      QVERIFY2(ink > 100, qPrintable(all[std::size_t(i)].name));
    }
    if (const QString dir = qEnvironmentVariable("SONARGRID_SNAPSHOT_DIR"); !dir.isEmpty()) {
      chooser.resize(640, 560);
      chooser.grab().save(dir + "/open-example.png");
    }
    QVERIFY(chooser.choose("raschke-multi"));
    QCOMPARE(QFileInfo(chooser.chosenLog()).fileName(), QString("in-motion-01.sglog"));
    QVERIFY(!chooser.choose("no-such-dataset"));
  }

  void exportsWaitForAMap() {
    MainWindow w(ui::GridView::Backend::Raster);
    const QStringList exports{"Export View as &PNG…", "Export View as &SVG…", "Export &Map as PNG…",
                              "Export Map as &ROS map_server…"};
    for (const QString& text : exports) {
      QAction* a = actionNamed(w, text);
      QVERIFY2(a, qPrintable(text));
      QVERIFY2(!a->isEnabled(), qPrintable(text));
    }
    QVERIFY(w.openLog(dataset("room/room.sglog"), true));
    QVERIFY(w.waitForMap(120000));
    QCoreApplication::processEvents();
    for (const QString& text : exports)
      QVERIFY2(actionNamed(w, text)->isEnabled(), qPrintable(text));
  }

  void defaultWindowKeepsTheGridAndTheSliders_data() {
    QTest::addColumn<QString>("preset");
    // Konolige's rows had the longest labels; P1–P5 the most rows of the paper presets.
    QTest::newRow("O'Sullivan multiple-target") << "paper001-mt-log";
    QTest::newRow("Arafat parameterized") << "paper002-fig6-parameterized";
    QTest::newRow("Raschke HIMM") << "paper000-himm";
  }

  void defaultWindowKeepsTheGridAndTheSliders() {
    QFETCH(QString, preset);
    QSettings().remove("window");
    MainWindow w(ui::GridView::Backend::Raster);
    w.resize(1280, 800);
    w.setMapperSettings(applyPreset(*findPreset(preset.toStdString())));
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    QCoreApplication::processEvents();
    // The grid keeps at least 60 % of the window's width (issue 49 item 9: 768 of 1280 px).
    QVERIFY2(w.gridView()->width() >= 768, qPrintable(QString::number(w.gridView()->width())));
    // Every slider's groove is at least 80 px.
    const QList<QSlider*> sliders = w.parameterPanel()->findChildren<QSlider*>();
    QVERIFY(!sliders.isEmpty());
    for (QSlider* slider : sliders) {
      QStyleOptionSlider option;
      option.initFrom(slider);
      option.orientation = slider->orientation();
      const QRect groove = slider->style()->subControlRect(QStyle::CC_Slider, &option,
                                                           QStyle::SC_SliderGroove, slider);
      QVERIFY2(
          groove.width() >= 80,
          qPrintable(QStringLiteral("%1: %2 px").arg(slider->objectName()).arg(groove.width())));
    }
  }

  void tourStepsChangeTheModel() {
    MainWindow w(ui::GridView::Backend::Raster);
    TourDialog tour(&w);
    QCOMPARE(tour.step(), 0);
    QVERIFY(tour.stepCount() >= 5);
    // Step 1 opens raschke-multi run 1 with its reference, mapped with HIMM × HIMM.
    QVERIFY(w.waitForLoad(120000));
    QCOMPARE(QFileInfo(w.logPath()).fileName(), QString("in-motion-01.sglog"));
    QCOMPARE(QFileInfo(w.document()->referencePath()).fileName(), QString("world.json"));
    QCOMPARE(w.mapperSettings().model, std::string("himm"));
    tour.next();
    QCOMPARE(w.mapperSettings().model, std::string("himm"));
    QCOMPARE(w.mapperSettings().rule, std::string("himm"));
    tour.next();  // HPF with probability addition (paper 000 §2.1)
    QCOMPARE(w.mapperSettings().model, std::string("hpf"));
    QCOMPARE(w.mapperSettings().rule, std::string("addition"));
    tour.back();  // and back to HIMM
    QCOMPARE(w.mapperSettings().model, std::string("himm"));
    tour.next();
    tour.next();  // the beam view's regions: parameterized, paper 002 Fig. 6 (P5 = 15°)
    QCOMPARE(w.mapperSettings().model, std::string("parameterized"));
    QCOMPARE(w.mapperSettings().parameters.get("p5"), 15.0);
    if (const QString dir = qEnvironmentVariable("SONARGRID_SNAPSHOT_DIR"); !dir.isEmpty()) {
      tour.show();
      QVERIFY(QTest::qWaitForWindowExposed(&tour));
      tour.grab().save(dir + "/tour-regions.png");
    }
    tour.next();  // one slider: P5 = 6° (paper 002 Table 1 col. 6)
    QCOMPARE(w.mapperSettings().parameters.get("p5"), 6.0);
    QCOMPARE(w.parameterPanel()->spinBoxFor("p5")->value(), 6.0);
    tour.next();
    QCOMPARE(tour.step(), tour.stepCount() - 1);
    tour.next();  // past the end: stays
    QCOMPARE(tour.step(), tour.stepCount() - 1);
    QVERIFY(w.waitForMap(120000));
  }

  void tourClaimsHold() {
    // Issue 49 item 5: every step's claim is checked with a metric of the map it shows, scored
    // against the reference the window has (raschke-multi's world.json), with the core's IOP
    // (paper 000 eq 9) and its filled cells. The tour's steps 4-6 showed Figure 6's set, whose
    // P3 = 1.0 as metres fills the room (IOP 947 mm, 37 485 of 57 250 cells filled) while the
    // text said the walls sharpen; step 1 said "green" while the reference showed blue, in edit
    // mode.
    MainWindow w(ui::GridView::Backend::Raster);
    TourDialog tour(&w);
    QVERIFY(w.waitForLoad(120000));
    // Step 1: the reference is drawn (its overlay, green) and not in the editor's edit mode.
    QVERIFY(w.document()->overlays().testFlag(ui::Overlay::Reference));
    QVERIFY(!w.gridView()->tool());
    QVERIFY(tour.findChild<QLabel*>("tourText")->text().contains("green"));
    struct Shown {
      double iop;
      std::size_t filled;
    };
    auto shown = [&w]() -> Shown {
      if (!w.waitForMap(120000)) return {-1.0, 0};
      const auto map = w.gridView()->map();
      const ReferenceScore score = scoreAgainstReference(*map, *w.document()->reference());
      return {score.value(Metric::Iop).value_or(-1.0), map->filledCount()};
    };
    tour.next();  // step 2: HIMM, "walls come out thin and sharp"
    const Shown himm = shown();
    tour.next();  // step 3: HPF, "walls are thicker and blurred"
    const Shown hpf = shown();
    QVERIFY2(hpf.iop > himm.iop && hpf.filled > himm.filled,
             qPrintable(QStringLiteral("HIMM %1 mm, %2 cells; HPF %3 mm, %4 cells")
                            .arg(himm.iop)
                            .arg(himm.filled)
                            .arg(hpf.iop)
                            .arg(hpf.filled)));
    tour.next();  // step 4: the parameterized model with P5 = 15°
    QCOMPARE(w.mapperSettings().parameters.get("p5"), 15.0);
    const Shown wide = shown();
    tour.next();  // step 5: P5 = 6°, "the occupied arcs thin and the walls sharpen (IOP falls)"
    const Shown narrow = shown();
    QVERIFY2(narrow.iop < wide.iop && narrow.filled < wide.filled,
             qPrintable(QStringLiteral("P5 15: %1 mm, %2 cells; P5 6: %3 mm, %4 cells")
                            .arg(wide.iop)
                            .arg(wide.filled)
                            .arg(narrow.iop)
                            .arg(narrow.filled)));
    // Neither map is the room filled: under half the grid's cells (Figure 6's set filled 65 %).
    const std::size_t cells = w.gridView()->map()->spec.cellCount();
    QVERIFY2(wide.filled < cells / 2, qPrintable(QString::number(wide.filled)));
    tour.next();  // step 6: "every change of model or parameter can be undone"
    QVERIFY(w.document()->undoStack()->canUndo());
    w.document()->undoStack()->undo();
    QCOMPARE(w.mapperSettings().parameters.get("p5"), 15.0);
  }
};

QTEST_MAIN(TestFirstRun)
#include "tst_first_run.moc"
