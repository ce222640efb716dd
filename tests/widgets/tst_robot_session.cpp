// SPDX-License-Identifier: GPL-3.0-or-later
// The app's live map against the virtual robot over loopback (issue 13 item 6; docs/live-robot.md,
// "In the app"): the window's Robot dock starts the in-process virtual robot (its clock five times
// real time, so a few simulated seconds pass quickly; nothing here asserts a duration) and its
// session maps what arrives. The live map holds exactly the readings the link counted, equals in
// every layer the batch map of the same scans on the live grid's limits, and a re-map mid-stream
// or a disconnect and reconnect keeps every scan. A recording is a complete log of what came in
// while it ran, and teleoperation drives the robot with the arrow keys without panning the view.
//
// Set SONARGRID_ROBOT_SCREENSHOT=FILE.png to save the window during the live session.

#include <QFileInfo>
#include <QMenu>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QUndoStack>
#include <QtTest>
#include <cstring>

#include "document.h"
#include "grid_view.h"
#include "main_window.h"
#include "remap_controller.h"
#include "robot/robot_dock.h"
#include "robot/robot_session.h"
#include "robot/teleop_keys.h"
#include "sonargrid/io/sglog.h"
#include "timeline.h"

using namespace sg;

namespace {

constexpr int kWaitMs = 120000;  // a bound against hangs, never a measured time

MapperSettings settingsFor(const std::string& model, const std::string& rule) {
  MapperSettings s;
  s.model = model;
  s.rule = rule;
  s.parameters = defaultParameters(model, rule);
  return s;
}

bool sameLayers(const OccupancyMap& a, const OccupancyMap& b) {
  return a.spec == b.spec && a.level == b.level && a.filled == b.filled &&
         a.observed == b.observed && a.probability.identical(b.probability) &&
         a.native.identical(b.native) && a.evidence.identical(b.evidence);
}

app::VirtualRobotHost::Options virtualRobot(std::optional<RouteKind> route = RouteKind::InMotion) {
  app::VirtualRobotHost::Options o;
  o.world = QStringLiteral(SONARGRID_DATASETS "/raschke-single/world.json");
  o.robot = "p3dx";
  o.route = route;
  o.timeScale = 5.0;
  o.seed = 7;
  return o;
}

// Waits for the maps asked for so far; the last one delivered.
std::shared_ptr<const OccupancyMap> settledMap(app::MainWindow& window) {
  ui::RemapController* remap = window.remapController();
  QElapsedTimer clock;
  clock.start();
  while (remap->busy() && clock.elapsed() < kWaitMs) QTest::qWait(20);
  // The window takes the map from the last mapped() signal, queued after busy() turned false.
  QCoreApplication::processEvents();
  return remap->busy() ? nullptr : window.gridView()->map();
}

std::size_t readingCount(const Dataset& d) {
  std::size_t n = 0;
  for (const Scan& s : d.scans) n += s.readings.size();
  return n;
}

}  // namespace

class TestRobotSession : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() {
    QStandardPaths::setTestModeEnabled(true);  // QSettings go to a scratch location
    QCoreApplication::setOrganizationName("SonarGridTest");
    QCoreApplication::setApplicationName("tst_robot_session");
    QSettings().clear();
  }

  void liveMapEqualsTheBatchMapOfTheReceivedScans() {
    app::MainWindow window(ui::GridView::Backend::Raster);
    window.resize(1280, 800);
    window.show();
    window.setMapperSettings(settingsFor("himm", "himm"));
    auto* dock = window.findChild<app::RobotDock*>();
    QVERIFY(dock);
    app::RobotSession* session = dock->session();
    QSignalSpy merged(session, &app::RobotSession::scansMerged);
    // Through the dock, as Robot ▸ Start Virtual Robot does, but five times as fast: the world
    // becomes the window's reference map.
    QVERIFY(!window.hasReference());
    dock->setWorld(virtualRobot().world);
    app::VirtualRobotHost::Options options = dock->virtualRobotOptions();
    QCOMPARE(options.world, virtualRobot().world);
    options.timeScale = virtualRobot().timeScale;
    options.seed = virtualRobot().seed;
    QVERIFY(dock->startVirtualRobot(options));
    QVERIFY(window.hasReference());
    QTRY_COMPARE_WITH_TIMEOUT(session->state(), app::RobotSession::State::Connected, kWaitMs);

    // A change of model and rule while the scans stream in re-maps what has come and goes on.
    QTRY_VERIFY_WITH_TIMEOUT(session->scansReceived() >= 30, kWaitMs);
    window.setMapperSettings(settingsFor("hpf", "bayes"));
    QTRY_VERIFY_WITH_TIMEOUT(session->scansReceived() >= 80, kWaitMs);
    if (const QByteArray shot = qgetenv("SONARGRID_ROBOT_SCREENSHOT"); !shot.isEmpty()) {
      // A picture for the docs: a lap and more of the room.
      window.resize(1280, 960);  // the dock's status in view
      QTRY_VERIFY_WITH_TIMEOUT(session->scansReceived() >= 500, kWaitMs);
      settledMap(window);
      QTest::qWait(300);
      QVERIFY(window.grab().save(QString::fromLocal8Bit(shot)));
    }
    session->disconnectLink();
    QCOMPARE(session->state(), app::RobotSession::State::Idle);
    const auto map = settledMap(window);
    QVERIFY(map);

    // Merged on the timer, in batches: fewer merges than scans.
    const auto source = session->source();
    const arcos::LinkCounters& c = session->link()->counters();
    QVERIFY(merged.count() > 1);
    QVERIFY(static_cast<std::uint64_t>(merged.count()) < c.sips);
    // Every scan the link decoded is in the source, and every reading it counted.
    QCOMPARE(static_cast<std::uint64_t>(source->size()), c.sips);
    const Dataset received = source->dataset(source->size());
    QCOMPARE(static_cast<std::uint64_t>(readingCount(received)), c.readings);
    QCOMPARE(static_cast<std::uint64_t>(session->readingsReceived()), c.readings);
    QCOMPARE(c.errors(), std::uint64_t{0});
    // The timeline ends at the last scan and stands there.
    QCOMPARE(window.timeline()->currentScan(), source->size() - 1);

    // The window's live map is the batch map of those scans with the settings of the re-map, on
    // the live grid's limits.
    QCOMPARE(map->rule, std::string("bayes"));
    const MapperSettings settings = window.remapController()->settings();
    Mapper batch(received.ring, map->spec, settings);
    batch.mapDataset(received);
    const OccupancyMap expected = batch.snapshot();
    QVERIFY(map->filledCount() > 0);
    QCOMPARE(map->filledCount(), expected.filledCount());
    QVERIFY(sameLayers(*map, expected));
    qInfo("live map: %zu scans, %zu readings, %d merges, %zu filled cells (%d x %d)",
          source->size(), readingCount(received), static_cast<int>(merged.count()),
          map->filledCount(), map->spec.width, map->spec.height);
    session->stopVirtualRobot();
  }

  void theRobotsWorldBecomesTheReference() {
    // Issue 49 item 10: with the room's reference open, the virtual robot in raschke-single's
    // world was scored against the room's walls. Its world becomes the reference (one undo step),
    // and its default route (the world's route.txt) starts without a clearance error.
    app::MainWindow window(ui::GridView::Backend::Raster);
    QVERIFY(window.openReference(SONARGRID_DATASETS "/room/room.json", true));
    auto* dock = window.findChild<app::RobotDock*>();
    QVERIFY(dock);
    dock->setWorld(virtualRobot().world);
    app::VirtualRobotHost::Options options = dock->virtualRobotOptions();
    options.timeScale = virtualRobot().timeScale;
    options.seed = virtualRobot().seed;
    const int steps = window.document()->undoStack()->count();
    QVERIFY(dock->startVirtualRobot(options));
    QCOMPARE(QFileInfo(window.document()->referencePath()).canonicalFilePath(),
             QFileInfo(virtualRobot().world).canonicalFilePath());
    QCOMPARE(window.document()->undoStack()->count(), steps + 1);
    // Started again in the same world: the reference is left as it is.
    dock->session()->stopVirtualRobot();
    QVERIFY(dock->startVirtualRobot(options));
    QCOMPARE(window.document()->undoStack()->count(), steps + 1);
    dock->session()->stopVirtualRobot();
  }

  void disconnectAndReconnectKeepTheMap() {
    app::MainWindow window(ui::GridView::Backend::Raster);
    window.setMapperSettings(settingsFor("himm", "himm"));
    app::RobotSession* session = window.findChild<app::RobotDock*>()->session();
    QString error;
    QVERIFY2(session->startVirtualRobot(virtualRobot(), &error), qPrintable(error));
    QTRY_VERIFY_WITH_TIMEOUT(session->scansReceived() >= 30, kWaitMs);
    session->disconnectLink();
    const auto first = settledMap(window);
    const auto source = session->source();
    const Dataset before = source->dataset(source->size());
    QVERIFY(before.scans.size() >= 30);

    const live::LinkAddress address = session->link()->address();
    session->connectTo(address);
    QTRY_VERIFY_WITH_TIMEOUT(session->scansReceived() >= before.scans.size() + 30, kWaitMs);
    session->disconnectLink();
    const auto map = settledMap(window);

    // The same source goes on: the first connection's scans are still its first scans.
    QCOMPARE(session->source(), source);
    const Dataset all = source->dataset(source->size());
    for (std::size_t i = 0; i < before.scans.size(); ++i) {
      QCOMPARE(all.scans[i].time, before.scans[i].time);
      QCOMPARE(all.scans[i].readings.size(), before.scans[i].readings.size());
    }
    const arcos::LinkCounters& c = session->link()->counters();
    QCOMPARE(c.handshakes, std::uint64_t{2});
    QCOMPARE(c.reconnects, std::uint64_t{1});
    QCOMPARE(static_cast<std::uint64_t>(all.scans.size()), c.sips);
    QCOMPARE(static_cast<std::uint64_t>(readingCount(all)), c.readings);
    // Times only grow across the gap.
    for (std::size_t i = 1; i < all.scans.size(); ++i)
      QVERIFY(all.scans[i].time >= all.scans[i - 1].time);

    // The map holds both connections' scans: the batch map of all of them, and it covers at least
    // what the first connection's did.
    Mapper batch(all.ring, map->spec, window.remapController()->settings());
    batch.mapDataset(all);
    QVERIFY(sameLayers(*map, batch.snapshot()));
    QVERIFY(map->filledCount() >= first->filledCount());
    qInfo("reconnect: %zu scans before, %zu after, %zu filled cells before, %zu after",
          before.scans.size(), all.scans.size(), first->filledCount(), map->filledCount());
    session->stopVirtualRobot();
  }

  void recordingIsACompleteLog() {
    QTemporaryDir dir;
    const QString path = dir.filePath("live.sglog");
    app::MainWindow window(ui::GridView::Backend::Raster);
    app::RobotDock* dock = window.findChild<app::RobotDock*>();
    app::RobotSession* session = dock->session();
    QString error;
    QVERIFY2(session->startVirtualRobot(virtualRobot(), &error), qPrintable(error));
    QTRY_VERIFY_WITH_TIMEOUT(session->scansReceived() >= 10, kWaitMs);
    const std::size_t from = session->scansReceived();
    QVERIFY(dock->recordTo(path));
    QTRY_VERIFY_WITH_TIMEOUT(session->scansReceived() >= from + 30, kWaitMs);
    session->stopRecording();
    const std::size_t to = session->scansReceived();
    QVERIFY(!session->recording());
    session->stopVirtualRobot();
    session->mergeNow();

    // Exactly the scans received while recording, as the source holds them.
    const Dataset log = readSglog(path.toStdString());
    const auto source = session->source();
    QCOMPARE(log.scans.size(), to - from);
    QCOMPARE(log.ring.robot, source->ring().robot);
    const Dataset all = source->dataset(source->size());
    for (std::size_t i = 0; i < log.scans.size(); ++i) {
      const Scan& a = log.scans[i];
      const Scan& b = all.scans[from + i];
      QCOMPARE(a.readings.size(), b.readings.size());
      QVERIFY(std::abs(a.time - b.time) < 1e-6);  // .sglog keeps microseconds
    }
  }

  void aLogOpenedWhileLiveTakesTheMapUntilNewMap() {
    app::MainWindow window(ui::GridView::Backend::Raster);
    window.setMapperSettings(settingsFor("himm", "himm"));
    app::RobotDock* dock = window.findChild<app::RobotDock*>();
    app::RobotSession* session = dock->session();
    QString error;
    QVERIFY2(session->startVirtualRobot(virtualRobot(), &error), qPrintable(error));
    QTRY_VERIFY_WITH_TIMEOUT(session->scansReceived() >= 10, kWaitMs);
    const auto live = session->source();
    QCOMPARE(window.remapController()->source(), live);

    // The log takes the window: its map and timeline stay while the robot's scans go on arriving.
    QVERIFY(window.openLog(QStringLiteral(SONARGRID_DATASETS "/room/room.sglog"), true));
    QVERIFY(window.dataset());
    const double logEnd = window.timeline()->endTime();
    const std::size_t at = session->scansReceived();
    QTRY_VERIFY_WITH_TIMEOUT(session->scansReceived() >= at + 10, kWaitMs);
    session->mergeNow();
    QVERIFY(!session->mapping());
    QCOMPARE(window.remapController()->dataset(), window.dataset());
    QCOMPARE(window.timeline()->endTime(), logEnd);
    QCOMPARE(window.timeline()->currentScan(), window.dataset()->scans.size() - 1);

    // New Map gives the window back to the robot: the log closes, a new source maps the scans
    // that come, and the timeline is theirs.
    for (QAction* a : dock->menu()->actions())
      if (a->text() == QStringLiteral("&New Map")) a->trigger();
    QVERIFY(!window.dataset());
    QTRY_VERIFY_WITH_TIMEOUT(session->source() && session->source()->size() >= 5, kWaitMs);
    QVERIFY(session->source() != live);
    QVERIFY(session->mapping());
    QCOMPARE(window.remapController()->source(), session->source());
    session->disconnectLink();
    settledMap(window);
    QCOMPARE(window.timeline()->currentScan(), session->source()->size() - 1);
    QVERIFY(window.timeline()->endTime() < logEnd);
    session->stopVirtualRobot();
  }

  void arrowKeysDriveTheRobotAndNotTheView() {
    app::MainWindow window(ui::GridView::Backend::Raster);
    window.resize(1000, 700);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    app::RobotDock* dock = window.findChild<app::RobotDock*>();
    app::RobotSession* session = dock->session();
    QString error;
    // Without a route: the robot stands until a client drives it.
    QVERIFY2(session->startVirtualRobot(virtualRobot(std::nullopt), &error), qPrintable(error));
    QTRY_VERIFY_WITH_TIMEOUT(session->scansReceived() >= 10, kWaitMs);
    session->mergeNow();
    const Pose2D standing =
        session->source()->dataset(session->source()->size()).scans.back().odometry;

    ui::GridView* view = window.gridView();
    dock->teleopAction()->setChecked(true);
    QVERIFY(dock->teleop()->isEnabled());
    QTest::keyPress(view, Qt::Key_Up);
    const std::size_t pressedAt = session->scansReceived();
    QTRY_VERIFY_WITH_TIMEOUT(session->scansReceived() >= pressedAt + 10, kWaitMs);
    QTest::keyRelease(view, Qt::Key_Up);
    const std::size_t releasedAt = session->scansReceived();
    QTRY_VERIFY_WITH_TIMEOUT(session->scansReceived() >= releasedAt + 10, kWaitMs);
    session->disconnectLink();
    settledMap(window);
    const Dataset d = session->source()->dataset(session->source()->size());
    const Pose2D after = d.scans.back().odometry;
    // It drove forward along its heading, and then stood again.
    const Position moved = after.position - standing.position;
    QVERIFY(moved.norm() > 0.05);
    QVERIFY(moved.dot(Position(std::cos(standing.heading), std::sin(standing.heading))) > 0.0);
    QVERIFY((after.position - d.scans[d.scans.size() - 5].odometry.position).norm() == 0.0);

    // The map no longer changes: the view does not pan with the keys while they drive...
    const ui::ViewTransform viewBefore = view->view();
    QTest::keyClick(view, Qt::Key_Left);
    QTest::keyClick(view, Qt::Key_Down);
    QCOMPARE(view->view().centre, viewBefore.centre);
    // ...and does once teleoperation is off.
    dock->teleopAction()->setChecked(false);
    QTest::keyClick(view, Qt::Key_Left);
    QVERIFY(view->view().centre != viewBefore.centre);
    session->stopVirtualRobot();
  }
};

QTEST_MAIN(TestRobotSession)
#include "tst_robot_session.moc"
