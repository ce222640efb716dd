// SPDX-License-Identifier: GPL-3.0-or-later
// The main window offscreen: the timeline at t shows the map `sonargrid-cli map --until t` builds
// (both call Mapper::mapDataset(log, t) on the log's fitting grid), a bad file leaves the open
// document alone, recent files are remembered.

#include <QSignalSpy>
#include <QStandardPaths>
#include <QtTest>

#include "main_window.h"
#include "remap_controller.h"
#include "sonargrid/io/sglog.h"
#include "timeline.h"

using namespace sg;

namespace {

const QString kRoom = QStringLiteral(SONARGRID_DATASETS "/room/room.sglog");

MapperSettings himm() {
  MapperSettings s;
  s.model = "himm";
  s.rule = "himm";
  s.parameters = defaultParameters(s.model, s.rule);
  s.pose = PoseSource::Truth;
  return s;
}

// What `sonargrid-cli map --log room.sglog --pose truth --model himm --rule himm --until t` maps.
OccupancyMap cliMap(const Dataset& data, double until) {
  Mapper m(data.ring, data.fittingGrid(PoseSource::Truth, 0.05), himm());
  m.mapDataset(data, until);
  return m.snapshot();
}

}  // namespace

class TestMainWindow : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() {
    QStandardPaths::setTestModeEnabled(true);  // QSettings go to a scratch location
    QCoreApplication::setOrganizationName("SonarGridTest");
    QCoreApplication::setApplicationName("tst_main_window");
    QSettings().clear();
  }

  void timelineAtTShowsTheMapUntilT() {
    app::MainWindow window;
    window.setCellSize(0.05);
    window.setMapperSettings(himm());
    window.show();
    QVERIFY(window.openLog(kRoom, true));
    QVERIFY(window.waitForMap(30000));
    const Dataset data = readSglog(kRoom.toStdString());
    QVERIFY(window.gridView()->map()->level == cliMap(data, 1e300).level);

    // Scrub to t = 30 s (scan 300 of the 10 Hz log).
    window.timeline()->setTime(30.0);
    QCOMPARE(window.timeline()->currentScan(), std::size_t(300));
    QVERIFY(window.waitForMap(30000));
    const auto at30 = window.gridView()->map();
    QVERIFY(at30->level == cliMap(data, 30.0).level);
    QVERIFY(at30->native == cliMap(data, 30.0).native);
    QVERIFY(at30->level != cliMap(data, 1e300).level);  // a real difference to detect
    // The robot drawn is the robot of that scan.
    QVERIFY(window.gridView()->scene().robot.has_value());
    QCOMPARE(window.gridView()->scene().robot->position, data.scans[300].truth->position);
    QCOMPARE(window.gridView()->scene().beams.size(), data.scans[300].readings.size());

    // One scan forward: the map up to scan 301's time.
    window.timeline()->stepForward();
    QCOMPARE(window.timeline()->time(), data.scans[301].time);
    QVERIFY(window.waitForMap(30000));
    QVERIFY(window.gridView()->map()->level == cliMap(data, data.scans[301].time).level);
  }

  void badLogKeepsTheOpenDocument() {
    app::MainWindow window;
    window.setMapperSettings(himm());
    QVERIFY(window.openLog(kRoom, true));
    QVERIFY(window.waitForMap(30000));
    const auto before = window.gridView()->map();
    const QString title = window.windowTitle();
    QVERIFY(!window.openLog(QStringLiteral(SONARGRID_TEST_DATA "/sglog/bad_range.sglog"), true));
    QVERIFY(!window.openLog(QStringLiteral(SONARGRID_TEST_DATA "/no/such.sglog"), true));
    QCOMPARE(window.windowTitle(), title);
    QCOMPARE(window.gridView()->map(), before);
    QVERIFY(window.remapController()->dataset());
    QCOMPARE(window.remapController()->dataset()->scans.size(), std::size_t(743));
  }

  void remembersRecentFilesAndChoices() {
    {
      app::MainWindow window;
      MapperSettings s = himm();
      s.model = "hpf";
      s.rule = "bayes";
      s.parameters = defaultParameters(s.model, s.rule);
      window.setMapperSettings(s);
      QVERIFY(window.openLog(kRoom, true));
      QCOMPARE(window.recentFiles().front(), QFileInfo(kRoom).absoluteFilePath());
      QVERIFY(window.waitForMap(30000));
    }
    app::MainWindow again;
    QCOMPARE(again.recentFiles().front(), QFileInfo(kRoom).absoluteFilePath());
    QCOMPARE(app::MainWindow::lastSettings().model, std::string("hpf"));
    QCOMPARE(app::MainWindow::lastSettings().rule, std::string("bayes"));
  }
};

QTEST_MAIN(TestMainWindow)
#include "tst_main_window.moc"
