// SPDX-License-Identifier: GPL-3.0-or-later
// The grid view under the offscreen platform (raster surface): hover read-out, keys, wheel, fit.

#include <QSignalSpy>
#include <QtTest>

#include "grid_view.h"

using namespace sg;
using namespace sg::ui;

Q_DECLARE_METATYPE(sg::ui::CellReadout)

namespace {

// 20 x 10 cells of 0.5 m from (-2, -1): the world box [-2, 8] x [-1, 4]. Cell (4, 6) is marked.
std::shared_ptr<OccupancyMap> markedMap() {
  GridSpec spec;
  spec.origin = {-2.0, -1.0};
  spec.cellSize = 0.5;
  spec.width = 20;
  spec.height = 10;
  auto map = std::make_shared<OccupancyMap>(OccupancyMap::unobserved(spec));
  const std::size_t i = spec.linear({4, 6});
  map->level[i] = 13;
  map->probability[i] = 0.9;
  map->native[i] = 42.0;
  map->observed[i] = 1;
  return map;
}

}  // namespace

class TestGridView : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() { qRegisterMetaType<sg::ui::CellReadout>(); }

  void offscreenUsesRaster() {
    QCOMPARE(GridView::automaticBackend(), GridView::Backend::Raster);
    GridView view;
    QCOMPARE(view.backend(), GridView::Backend::Raster);
  }

  void fitsTheFirstMap() {
    GridView view;
    view.resize(400, 300);
    view.show();
    QVERIFY(QTest::qWaitForWindowExposed(&view));
    view.setMap(markedMap());
    // 10 m x 5 m in (400 - 24) x (300 - 24) px: min(37.6, 55.2) = 37.6 px/m, centre (3, 1.5).
    QCOMPARE(view.view().pixelsPerMetre, 37.6);
    QCOMPARE(view.view().centre, Position(3.0, 1.5));
  }

  void hoverShowsTheRightCell() {
    GridView view;
    view.resize(400, 300);
    view.show();
    QVERIFY(QTest::qWaitForWindowExposed(&view));
    view.setMap(markedMap());
    view.setNativeName("HIMM CV");
    QSignalSpy spy(&view, &GridView::hovered);
    QSignalSpy text(&view, &GridView::hoverText);
    // Pixel (98, 124): x = 3 + (98 - 200) / 37.6 = 0.287 m, y = 1.5 - (124 - 150) / 37.6 = 2.191 m,
    // so cell ((0.287 + 2) / 0.5, (2.191 + 1) / 0.5) = (4.57, 6.38) -> (4, 6), the marked cell.
    QTest::mouseMove(&view, QPoint(98, 124));
    QTRY_VERIFY(spy.count() >= 1);
    const auto r = spy.last().at(0).value<CellReadout>();
    QVERIFY(r.inside);
    QCOMPARE(r.cell, CellIndex(4, 6));
    QCOMPARE(r.level, 13);
    QCOMPARE(r.probability, 0.9);
    QCOMPARE(r.native, 42.0);
    QVERIFY(std::abs(r.world.x() - (3.0 + (98 - 200) / 37.6)) < 1e-9);
    QVERIFY(std::abs(r.world.y() - (1.5 - (124 - 150) / 37.6)) < 1e-9);
    const QString shown = text.last().at(0).toString();
    QVERIFY2(shown.contains("cell (4, 6)") && shown.contains("CV 13") &&
                 shown.contains("p(occ) 0.900") && shown.contains("HIMM CV 42"),
             qPrintable(shown));
    // The pixel under the pointer has the marked cell's colour.
    const Rgb c = defaultLevelPalette()[13];
    QCOMPARE(view.renderImage().pixel(98, 124), qRgb(c.r, c.g, c.b));
    QCOMPARE(view.grabSurface().pixel(98, 124), qRgb(c.r, c.g, c.b));
    // One pixel left of the grid: off the grid. The grid's left edge x = -2 lies at
    // 200 + (-2 - 3) * 37.6 = 12 px.
    QTest::mouseMove(&view, QPoint(10, 124));
    QTRY_VERIFY(!spy.last().at(0).value<CellReadout>().inside);
  }

  void keysZoomPanAndFit() {
    GridView view;
    view.resize(400, 300);
    view.show();
    QVERIFY(QTest::qWaitForWindowExposed(&view));
    view.setMap(markedMap());
    const ViewTransform fitted = view.view();
    QTest::keyClick(&view, Qt::Key_Plus);
    QVERIFY(std::abs(view.view().pixelsPerMetre - 37.6 * 1.25) < 1e-9);
    QVERIFY((view.view().centre - fitted.centre).norm() < 1e-12);  // zoom about the centre
    QTest::keyClick(&view, Qt::Key_Left);
    // Left pans the picture 40 px right: the centre moves 40 / 47 m towards -x.
    QVERIFY(std::abs(view.view().centre.x() - (3.0 - 40.0 / 47.0)) < 1e-9);
    QTest::keyClick(&view, Qt::Key_F);
    QCOMPARE(view.view(), fitted);
  }

  void wheelZoomsAboutThePointer() {
    GridView view;
    view.resize(400, 300);
    view.show();
    QVERIFY(QTest::qWaitForWindowExposed(&view));
    view.setMap(markedMap());
    const QPointF at(98, 124);
    const Position before = view.view().toWorld(at, view.size());
    QWheelEvent wheel(at, view.mapToGlobal(at), QPoint(), QPoint(0, 120), Qt::NoButton,
                      Qt::NoModifier, Qt::NoScrollPhase, false);
    QApplication::sendEvent(&view, &wheel);
    // One notch is 15 degrees: 1.0025^15 = 1.0382.
    QVERIFY(std::abs(view.view().pixelsPerMetre - 37.6 * std::pow(1.0025, 15.0)) < 1e-9);
    QVERIFY((view.view().toWorld(at, view.size()) - before).norm() < 1e-9);
  }

  void keepsTheViewForTheSameGround() {
    GridView view;
    view.resize(400, 300);
    view.show();
    QVERIFY(QTest::qWaitForWindowExposed(&view));
    view.setMap(markedMap());
    view.zoomAt(2.0, QPointF(100, 100));
    const ViewTransform zoomed = view.view();
    view.setMap(markedMap());  // a re-map: same geometry, new levels
    QCOMPARE(view.view(), zoomed);

    // A preview on cells twice as large covers the same ground ([-2, 8] x [-1, 4] as 10 x 5 cells
    // of 1 m), and one a cell off still counts (within two of the larger cells): the user's view
    // stays. Another log's grid, 10 m away, is fitted.
    GridSpec coarse = markedMap()->spec;
    coarse.cellSize = 1.0;
    coarse.width = 10;
    coarse.height = 5;
    view.setMap(std::make_shared<OccupancyMap>(OccupancyMap::unobserved(coarse)));
    QCOMPARE(view.view(), zoomed);
    coarse.width = 11;
    coarse.origin = {-3.0, -1.0};
    view.setMap(std::make_shared<OccupancyMap>(OccupancyMap::unobserved(coarse)));
    QCOMPARE(view.view(), zoomed);
    view.setMap(markedMap());
    QCOMPARE(view.view(), zoomed);
    GridSpec elsewhere = markedMap()->spec;
    elsewhere.origin = {8.0, -1.0};
    view.setMap(std::make_shared<OccupancyMap>(OccupancyMap::unobserved(elsewhere)));
    QCOMPARE(view.view(), ViewTransform::fitting(elsewhere, view.size()));
  }

  void keepsAMovedViewWhenTheMapGrows() {
    // A live map's grid grows by whole cells around the old one (Mapper::append): a view the user
    // zoomed stays; a view still fitted fits the grown grid.
    GridSpec grown = markedMap()->spec;  // [-2, 8] x [-1, 4] grown to [-12, 18] x [-6, 9]
    grown.origin = {-12.0, -6.0};
    grown.width = 60;
    grown.height = 30;
    GridView view;
    view.resize(400, 300);
    view.show();
    QVERIFY(QTest::qWaitForWindowExposed(&view));
    view.setMap(markedMap());
    view.setMap(std::make_shared<OccupancyMap>(OccupancyMap::unobserved(grown)));
    QCOMPARE(view.view(), ViewTransform::fitting(grown, view.size()));
    view.setMap(markedMap());
    view.zoomAt(2.0, QPointF(100, 100));
    const ViewTransform zoomed = view.view();
    view.setMap(std::make_shared<OccupancyMap>(OccupancyMap::unobserved(grown)));
    QCOMPARE(view.view(), zoomed);
  }

  void followsTheRobotUntilPannedAway() {
    // A live map at its live edge (RobotSession): zoomed in, the view brings a robot that nears
    // its edge back to the centre; after a pan it stays where the user put it; fitting the map
    // (or turning the follow on again) follows again.
    Dataset d;
    d.ring = SonarRing::pioneer3dx();
    for (const double x : {3.0, 7.5, 7.6, -1.5}) {
      Scan s;
      s.odometry = Pose2D(x, 1.5, 0.0);
      d.scans.push_back(s);
    }
    GridView view;
    view.resize(400, 300);
    view.show();
    QVERIFY(QTest::qWaitForWindowExposed(&view));
    view.setMap(markedMap());  // fitted: centre (3, 1.5), 37.6 px/m
    view.setFollowRobot(true);
    QVERIFY(view.followsRobot());
    view.setRobotAt(&d, PoseSource::Odometry, 1);
    QCOMPARE(view.view().centre, Position(3.0, 1.5));  // fitted to the map: the robot is in it
    view.zoomAt(4.0, QPointF(200, 150));  // 150.4 px/m about the centre: x in [1.67, 4.33]
    QCOMPARE(view.view().centre, Position(3.0, 1.5));
    view.setRobotAt(&d, PoseSource::Odometry, 0);  // x = 3: in the middle, nothing moves
    QCOMPARE(view.view().centre, Position(3.0, 1.5));
    view.setRobotAt(&d, PoseSource::Odometry, 1);  // x = 7.5: outside, recentred on it
    QCOMPARE(view.view().centre, Position(7.5, 1.5));
    QCOMPARE(view.view().pixelsPerMetre, 150.4);
    // 0.1 m further is 15 px from the centre, well inside: the view stays.
    view.setRobotAt(&d, PoseSource::Odometry, 2);
    QCOMPARE(view.view().centre, Position(7.5, 1.5));
    view.panBy(QPointF(40, 0));  // the user looks elsewhere
    QVERIFY(!view.followsRobot());
    const ViewTransform panned = view.view();
    view.setRobotAt(&d, PoseSource::Odometry, 3);  // x = -1.5: far outside, but not followed
    QCOMPARE(view.view(), panned);
    view.setFollowRobot(true);  // still on: the pan is remembered
    QVERIFY(!view.followsRobot());
    view.setFollowRobot(false);  // behind the live edge, then back to it: followed again
    view.setFollowRobot(true);
    QVERIFY(view.followsRobot());
    view.setRobotAt(&d, PoseSource::Odometry, 3);
    QCOMPARE(view.view().centre, Position(-1.5, 1.5));
    view.panBy(QPointF(-40, 0));
    view.fitToMap();  // fitting forgets the pan as well
    QVERIFY(view.followsRobot());
  }

  void overlayToggles() {
    GridView view;
    view.setOverlays({});
    view.setOverlay(Overlay::Beams, true);
    QCOMPARE(view.overlays(), Overlays(Overlay::Beams));
    view.setOverlay(Overlay::Beams, false);
    QCOMPARE(view.overlays(), Overlays());
  }
};

QTEST_MAIN(TestGridView)
#include "tst_grid_view.moc"
