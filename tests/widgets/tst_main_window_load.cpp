// SPDX-License-Identifier: GPL-3.0-or-later
// Loading a large log in the main window offscreen: the load runs on a worker thread and reports
// progress; cancelling it, replacing it with another file, a malformed file or a log no grid can
// hold leaves the previous document and its map as they were (nothing half-loaded is shown).

#include <QPushButton>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QStatusBar>
#include <QTemporaryDir>
#include <QtTest>
#include <algorithm>
#include <fstream>
#include <sstream>

#include "bag_import_dialog.h"
#include "csv_import_dialog.h"
#include "document.h"
#include "main_window.h"
#include "project_file.h"
#include "remap_controller.h"
#include "sonargrid/engine/mapper.h"
#include "sonargrid/io/csv_log.h"
#include "sonargrid/io/log_reader.h"
#include "sonargrid/io/sglog.h"

using namespace sg;

namespace {

const QString kRoom = QStringLiteral(SONARGRID_DATASETS "/room/room.sglog");

// 17 laps of the room log one after the other: 17 x 743 scans of 16 readings = 202,096 readings.
Dataset largeLog() {
  const Dataset room = readSglog(kRoom.toStdString());
  Dataset out;
  out.name = "room x 17";
  out.ring = room.ring;
  const double lap = room.scans.back().time + 1.0;
  for (int i = 0; i < 17; ++i) {
    for (Scan s : room.scans) {
      s.time += i * lap;
      for (Reading& r : s.readings) r.time += i * lap;
      out.scans.push_back(std::move(s));
    }
  }
  return out;
}

}  // namespace

class TestMainWindowLoad : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  QString large_;
  QString bad_;
  std::size_t badLine_ = 0;

  // A window showing the room log and its map.
  static bool openRoom(app::MainWindow& window) {
    return window.openLog(kRoom, true) && window.waitForMap(60000);
  }

 private slots:
  void initTestCase() {
    QStandardPaths::setTestModeEnabled(true);
    QCoreApplication::setOrganizationName("SonarGridTest");
    QCoreApplication::setApplicationName("tst_main_window_load");
    QSettings().clear();
    QVERIFY(dir_.isValid());
    const Dataset data = largeLog();
    QCOMPARE(data.readingCount(), std::size_t(202096));
    large_ = dir_.filePath("large.sglog");
    writeSglog(data, large_.toStdString());

    // The same log with a bad range on a reading line 90 % of the way through.
    std::ostringstream text;
    writeSglog(data, text);
    std::string s = text.str();
    std::size_t at = s.find("\nr ", s.size() * 9 / 10) + 1;
    badLine_ = std::size_t(std::count(s.begin(), s.begin() + std::ptrdiff_t(at), '\n')) + 1;
    s.insert(at, "r 0 far 0\n");
    bad_ = dir_.filePath("bad.sglog");
    std::ofstream(bad_.toStdString(), std::ios::binary) << s;
  }

  void largeLogLoadsWithProgress() {
    app::MainWindow window;
    window.show();
    QSignalSpy progress(&window, &app::MainWindow::loadProgress);
    QSignalSpy loaded(&window, &app::MainWindow::loaded);
    window.loadLog(large_, LogOptions{});
    // loadLog returned at once: the load runs on a worker while the GUI thread goes on.
    QVERIFY(window.loading());
    QVERIFY(window.waitForLoad(120000));
    QCOMPARE(loaded.count(), 1);
    QCOMPARE(window.dataset()->readingCount(), std::size_t(202096));
    QCOMPARE(window.logPath(), large_);
    // The file is several MB, read in 256 KiB blocks (text_lines.h): many percent steps, rising,
    // ending at 100.
    QVERIFY2(progress.count() >= 5, qPrintable(QString::number(progress.count())));
    for (int i = 1; i < progress.count(); ++i)
      QVERIFY(progress[i][0].toInt() > progress[i - 1][0].toInt());
    QCOMPARE(progress.last()[0].toInt(), 100);
    QVERIFY(window.waitForMap(120000));
  }

  void cancelKeepsThePreviousDocument() {
    app::MainWindow window;
    window.show();
    QVERIFY(openRoom(window));
    const auto data = window.dataset();
    const auto map = window.gridView()->map();
    const QString title = window.windowTitle();
    QSignalSpy cancelled(&window, &app::MainWindow::loadCancelled);
    QSignalSpy loaded(&window, &app::MainWindow::loaded);

    window.loadLog(large_, LogOptions{});
    auto* cancel = window.findChild<QPushButton*>(QStringLiteral("cancelLoading"));
    QVERIFY(cancel && cancel->isVisible());
    QTest::mouseClick(cancel, Qt::LeftButton);
    QCOMPARE(cancelled.count(), 1);
    QCOMPARE(cancelled[0][0].toString(), large_);
    QVERIFY(!window.loading());
    QVERIFY(!cancel->isVisible());
    QTest::qWait(300);  // let the worker notice and end; its outcome must not arrive

    // Esc does the same.
    window.loadLog(large_, LogOptions{});
    window.activateWindow();
    QVERIFY(QTest::qWaitForWindowActive(&window));
    QTest::keyClick(&window, Qt::Key_Escape);
    QCOMPARE(cancelled.count(), 2);
    QTest::qWait(300);

    QCOMPARE(loaded.count(), 0);
    QCOMPARE(window.dataset(), data);
    QCOMPARE(window.logPath(), kRoom);
    QCOMPARE(window.gridView()->map(), map);
    QCOMPARE(window.windowTitle(), title);
    QCOMPARE(window.remapController()->dataset(), data);
  }

  void openingAnotherFileCancelsTheFirst() {
    app::MainWindow window;
    window.show();
    QSignalSpy cancelled(&window, &app::MainWindow::loadCancelled);
    QSignalSpy loaded(&window, &app::MainWindow::loaded);
    window.loadLog(large_, LogOptions{});
    window.loadLog(kRoom, LogOptions{});
    QCOMPARE(cancelled.count(), 1);
    QCOMPARE(cancelled[0][0].toString(), large_);
    QVERIFY(window.waitForLoad(60000));
    QTest::qWait(300);  // a late outcome of the first load must not replace the second
    QCOMPARE(loaded.count(), 1);
    QCOMPARE(loaded[0][0].toString(), kRoom);
    QCOMPARE(window.dataset()->scans.size(), std::size_t(743));
  }

  void aBagOpensAndMapsAsItsSglog() {
    // datasets/room/room.sglog written as MCAP by npm's @mcap/core
    // (tests/data/bags/room/README.md): File > Open reads it with the topics it picks, and the
    // window's map is the .sglog's, bit for bit in every layer.
    app::MainWindow window;
    QVERIFY(openRoom(window));
    const std::shared_ptr<const OccupancyMap> sglog = window.remapController()->lastMap();
    QVERIFY(sglog != nullptr);
    const QString bag = QStringLiteral(SONARGRID_TEST_DATA "/bags/room/room-zstd.mcap");
    QVERIFY(window.openLog(bag, true) && window.waitForMap(60000));
    QCOMPARE(window.logPath(), bag);
    const std::shared_ptr<const OccupancyMap> map = window.remapController()->lastMap();
    QVERIFY(map != nullptr && map != sglog);
    QCOMPARE(window.dataset()->readingCount(), std::size_t(11888));
    QVERIFY(map->spec == sglog->spec && map->level == sglog->level &&
            map->observed == sglog->observed && map->probability.identical(sglog->probability) &&
            map->native.identical(sglog->native) && map->evidence.identical(sglog->evidence));
  }

  void aBagOpensTheTopicDialogAndItsProjectKeepsThePick() {
    // tests/data/bags/room/rosaria-room.bag (python3-rosbag): File > Open shows the topics, the
    // user chooses the Pioneer's ring for its point clouds and no true pose; the log loads as
    // `sonargrid-cli --robot p3dx` reads it, and a project saved then reopens it the same way
    // without asking again.
    const QString bag = QStringLiteral(SONARGRID_TEST_DATA "/bags/room/rosaria-room.bag");
    LogOptions cli;
    cli.ring = SonarRing::pioneer3dx();
    const Dataset expected = readLog(bag.toStdString(), cli);
    QTemporaryDir dir;
    const QString project = dir.filePath(QStringLiteral("rosaria.sgproj"));
    {
      app::MainWindow window;
      window.show();
      bool asked = false;
      QTimer::singleShot(0, &window, [&] {
        auto* d = window.findChild<ui::BagImportDialog*>();
        if (!d) return;
        asked = true;
        d->setRobotPreset(QStringLiteral("p3dx"));
        d->accept();
      });
      QVERIFY(window.openLog(bag));
      QVERIFY(asked);
      QVERIFY(window.waitForLoad(30000));
      QVERIFY(*window.dataset() == expected);
      const app::LogReading& reading = window.document()->logReading();
      QCOMPARE(reading.format, LogFormat::Bag);
      QCOMPARE(reading.topics.sonar, std::vector<std::string>{"/RosAria/sonar"});
      QCOMPARE(reading.topics.odometry, std::string("/RosAria/pose"));
      QVERIFY(reading.ring == SonarRing::pioneer3dx());
      QVERIFY(window.saveProjectAs(project, true));
    }
    const app::ProjectState stored = app::readProject(project);
    QCOMPARE(stored.logReading.topics.sonar, std::vector<std::string>{"/RosAria/sonar"});
    app::MainWindow window;
    QVERIFY(window.openProject(project, true));
    QVERIFY(window.findChild<ui::BagImportDialog*>() == nullptr);
    QCOMPARE(window.logPath(), bag);
    QVERIFY(*window.dataset() == expected);
  }

  void scansWithoutTruthAreLeftOutAndSaid() {
    // room.sglog with its first scan's true pose removed (a simulator's first SIP before its first
    // SIMSTAT): mapped from the true pose, the window keeps that pose source, leaves the scan out
    // (the map is that of the other 742 scans) and says so in the status bar.
    Dataset partial = readLog(kRoom.toStdString());
    partial.scans.front().truth.reset();
    Dataset without = partial;
    without.scans.erase(without.scans.begin());
    const QString path = dir_.filePath("first_scan_without_truth.sglog");
    writeSglog(partial, path.toStdString());
    app::MainWindow window;
    window.show();
    MapperSettings s = window.document()->mapperSettings();
    s.pose = PoseSource::Truth;
    window.setMapperSettings(s);
    QVERIFY(window.openLog(path, true) && window.waitForMap(60000));
    QCOMPARE(window.document()->mapperSettings().pose, PoseSource::Truth);
    QVERIFY2(window.statusBar()->currentMessage().startsWith(
                 QStringLiteral("1 of 743 scans have no true pose and are left out of the map")),
             qPrintable(window.statusBar()->currentMessage()));
    const std::shared_ptr<const OccupancyMap> map = window.remapController()->lastMap();
    QVERIFY(map != nullptr);
    Mapper expected(without.ring, map->spec, s);
    QVERIFY(expected.mapDataset(without));
    QVERIFY(map->level == expected.snapshot().level);
  }

  void csvFileOpensTheImportDialog() {
    const QString csv = QStringLiteral(SONARGRID_TEST_DATA "/logs/mm_ddeg.csv");
    const QString geometry = QStringLiteral(SONARGRID_TEST_DATA "/logs/ring4_mm.geom");
    app::MainWindow window;
    window.show();
    bool asked = false;
    // The dialog is modal: choose the rest of the fixture's mapping from inside its event loop
    // (its first guess, a header row over time, x, y, θ and the sonars, fits this file).
    QTimer::singleShot(0, &window, [&] {
      auto* d = window.findChild<ui::CsvImportDialog*>();
      if (!d) return;
      asked = true;
      d->setLengthUnit(LengthUnit::Millimetre);
      d->setAngleUnit(AngleUnit::TenthDegree);
      d->setNoEcho(QStringLiteral("5110"));
      d->setGeometryFile(geometry);
      d->accept();
    });
    QVERIFY(window.openLog(csv));
    QVERIFY(asked);
    QVERIFY(window.waitForLoad(30000));
    // The same Dataset as the CLI's documented spec (docs/formats.md, "CSV and text columns").
    LogOptions cli;
    cli.csv = parseCsvLayout(
        "header=1,time=1,x=2,y=3,theta=4,sonars=5-8,length=mm,angle=ddeg,"
        "noecho=5110");
    cli.ring = readSonarGeometry(geometry.toStdString());
    QVERIFY(*window.dataset() == readLog(csv.toStdString(), cli));
  }

  void malformedLogShowsNothingHalfLoaded() {
    app::MainWindow window;
    window.show();
    QVERIFY(openRoom(window));
    const auto data = window.dataset();
    const auto map = window.gridView()->map();
    QSignalSpy progress(&window, &app::MainWindow::loadProgress);
    QSignalSpy failed(&window, &app::MainWindow::loadFailed);
    window.loadLog(bad_, LogOptions{});
    QVERIFY(!window.waitForLoad(120000));
    QCOMPARE(failed.count(), 1);
    // The error names the file and the line of the inserted bad reading.
    const QString message = failed[0][1].toString();
    QVERIFY2(message.contains(QStringLiteral("bad.sglog:%1:").arg(badLine_)), qPrintable(message));
    // Most of the file had been read when the error stopped the load...
    QVERIFY(!progress.isEmpty());
    QVERIFY(progress.last()[0].toInt() >= 80);
    // ...yet none of it is shown.
    QCOMPARE(window.dataset(), data);
    QCOMPARE(window.logPath(), kRoom);
    QCOMPARE(window.gridView()->map(), map);
    QCOMPARE(window.remapController()->dataset(), data);
  }

  void logNoGridCanHoldKeepsThePreviousDocument() {
    // One pose 1e12 m from the others (tests/data/sglog/far_pose.sglog): the core refuses the
    // grid (sg::kMaxGridCells), and the window shows that error instead of a blank map.
    const QString far = QStringLiteral(SONARGRID_TEST_DATA "/sglog/far_pose.sglog");
    app::MainWindow window;
    window.show();
    QVERIFY(openRoom(window));
    const auto data = window.dataset();
    const auto map = window.gridView()->map();
    const QString title = window.windowTitle();
    QSignalSpy failed(&window, &app::MainWindow::loadFailed);
    QSignalSpy loaded(&window, &app::MainWindow::loaded);
    window.loadLog(far, LogOptions{});
    QVERIFY(!window.waitForLoad(30000));
    QCOMPARE(failed.count(), 1);
    QCOMPARE(failed[0][0].toString(), far);
    // The file, the scan (index 2, t = 1 s, at x = 1e12) and the limit.
    const QString message = failed[0][1].toString();
    QVERIFY2(message.startsWith(far + ": scan 2 (t = 1 s) reaches (1e+12, 0) m: "),
             qPrintable(message));
    QVERIFY2(message.endsWith("more than the grid limit of 200000000 cells"), qPrintable(message));
    QCOMPARE(loaded.count(), 0);
    QCOMPARE(window.dataset(), data);
    QCOMPARE(window.logPath(), kRoom);
    QCOMPARE(window.gridView()->map(), map);
    QCOMPARE(window.windowTitle(), title);
    QCOMPARE(window.remapController()->dataset(), data);
  }
};

QTEST_MAIN(TestMainWindowLoad)
#include "tst_main_window_load.moc"
