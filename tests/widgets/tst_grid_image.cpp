// SPDX-License-Identifier: GPL-3.0-or-later
// The picture of a grid, pixel by pixel: renderGridCells/renderGridImage are pure functions, so
// every expected colour below is worked out by hand from the view geometry.

#include <QPainter>
#include <QSet>
#include <QtTest>

#include "grid_image.h"

using namespace sg;
using namespace sg::ui;

namespace {

QRgb rgbOf(int level) {
  const Rgb& c = defaultLevelPalette()[static_cast<std::size_t>(level)];
  return qRgb(c.r, c.g, c.b);
}

// 3 x 2 cells of 1 m, origin (0, 0). Row iy = 0 is the bottom row (GridSpec convention).
//   iy = 1:  8  3 12
//   iy = 0:  0  5 15
std::shared_ptr<OccupancyMap> smallMap() {
  GridSpec spec;
  spec.origin = {0.0, 0.0};
  spec.cellSize = 1.0;
  spec.width = 3;
  spec.height = 2;
  auto map = std::make_shared<OccupancyMap>(OccupancyMap::unobserved(spec));
  map->level = {0, 5, 15, 8, 3, 12};
  map->probability = {0.0, 1.0 / 3.0, 1.0, 0.5, 0.2, 0.8};
  map->native = {-7.0, -2.0, 9.0, 0.0, -4.0, 5.0};
  map->observed = {1, 1, 1, 0, 1, 1};
  return map;
}

// Centre (1.5, 1.0) at 10 px/m in a 40 x 30 picture: the grid's left edge x = 0 falls at
// 20 + (0 - 1.5) * 10 = 5 px, its top edge y = 2 at 15 - (2 - 1) * 10 = 5 px; each cell is 10 px.
ViewTransform smallView() {
  ViewTransform t;
  t.centre = {1.5, 1.0};
  t.pixelsPerMetre = 10.0;
  return t;
}

}  // namespace

class TestGridImage : public QObject {
  Q_OBJECT

 private slots:
  void paletteHasSixteenDistinctLevels() {
    // Paper 000 §4.3: 16 display levels; each must be told apart on screen.
    QSet<QRgb> colours;
    for (int k = 0; k < kLevels; ++k) colours.insert(rgbOf(k));
    QCOMPARE(colours.size(), 16);
    QVERIFY(!colours.contains(backgroundColour().rgb()));
  }

  void legendShowsEveryLevel() {
    GridScene scene;
    const QSize size(400, 300);
    const QImage image =
        renderGridImage(scene, defaultLevelPalette(), Overlay::Legend, ViewTransform{}, size);
    QSet<QRgb> seen;
    for (int k = 0; k < kLevels; ++k) {
      const QRect swatch = legendSwatch(k, size);
      QVERIFY(QRect(QPoint(0, 0), size).contains(swatch));
      // Every pixel of the swatch is the level's colour.
      for (int y = swatch.top(); y <= swatch.bottom(); ++y)
        for (int x = swatch.left(); x <= swatch.right(); ++x) QCOMPARE(image.pixel(x, y), rgbOf(k));
      seen.insert(image.pixel(swatch.center()));
    }
    QCOMPARE(seen.size(), 16);
    // Without the legend flag the same pixels are background.
    const QImage bare = renderGridImage(scene, defaultLevelPalette(), {}, ViewTransform{}, size);
    QCOMPARE(bare.pixel(legendSwatch(3, size).center()), backgroundColour().rgb());
  }

  void cellsPixelByPixel() {
    const auto map = smallMap();
    const QImage image = renderGridCells(map.get(), defaultLevelPalette(), smallView(), {40, 30});
    QCOMPARE(image.size(), QSize(40, 30));
    const int levels[2][3] = {{0, 5, 15}, {8, 3, 12}};  // [iy][ix]
    for (int py = 0; py < 30; ++py) {
      for (int px = 0; px < 40; ++px) {
        QRgb expected = backgroundColour().rgb();
        if (px >= 5 && px < 35 && py >= 5 && py < 25) {
          const int ix = (px - 5) / 10;
          const int iy = 1 - (py - 5) / 10;  // picture rows grow downwards, world y upwards
          // Cell (0, 1) was never observed: unknown, whatever its level.
          expected = ix == 0 && iy == 1 ? unknownColour().rgb() : rgbOf(levels[iy][ix]);
        }
        if (image.pixel(px, py) != expected)
          QFAIL(qPrintable(QStringLiteral("pixel (%1, %2)").arg(px).arg(py)));
      }
    }
  }

  void greyPaletteIsUsedWhenGiven() {
    // Level k of the grey palette is 255 - 17k (palette.cpp): cell (2, 0) holds 15 -> black.
    const auto map = smallMap();
    const QImage image = renderGridCells(map.get(), greyLevelPalette(), smallView(), {40, 30});
    QCOMPARE(image.pixel(30, 20), qRgb(0, 0, 0));
    QCOMPARE(image.pixel(10, 20), qRgb(255, 255, 255));  // cell (0, 0), level 0
    QCOMPARE(image.pixel(20, 10), qRgb(204, 204, 204));  // cell (1, 1), level 3: 255 - 51
    // Cell (0, 1), never observed: the unknown colour in every palette.
    QCOMPARE(image.pixel(10, 10), unknownColour().rgb());
  }

  void overlaysDrawOnlyWhenToggled() {
    GridScene scene;
    scene.map = smallMap();
    scene.robot = Pose2D(1.5, 1.0, 0.0);  // at the centre pixel (20, 15)
    scene.robotRadius = 0.5;
    scene.referenceLines = {{{0.0, 0.0}, {3.0, 0.0}}};  // the grid's bottom edge: pixel row 25
    const QSize size(40, 30);
    const QImage none = renderGridImage(scene, defaultLevelPalette(), {}, smallView(), size);
    QCOMPARE(none, renderGridCells(scene.map.get(), defaultLevelPalette(), smallView(), size));

    const QImage robot =
        renderGridImage(scene, defaultLevelPalette(), Overlay::Robot, smallView(), size);
    // The robot's disc (white at 150/255 over level 5's blue) lightens the cell under it.
    QVERIFY(robot.pixel(22, 17) != none.pixel(22, 17));
    QCOMPARE(robot.pixel(2, 2), none.pixel(2, 2));  // far away: untouched

    const QImage reference =
        renderGridImage(scene, defaultLevelPalette(), Overlay::Reference, smallView(), size);
    const QColor line = reference.pixelColor(20, 25);
    QVERIFY2(line.green() > 120 && line.green() > line.red() + 60,
             qPrintable(line.name()));  // the reference green (0, 190, 90)
    QCOMPARE(reference.pixel(20, 10), none.pixel(20, 10));
  }

  void beamConesFollowTheScan() {
    // One sonar at (0.5, 1.0) facing +x, 25 degree cone, 2 m echo: the cone covers (1.5, 1.0)
    // (pixel (20, 15)) but not (1.5, 1.9), which is 42 degrees off the axis.
    GridScene scene;
    scene.map = smallMap();
    scene.beams.push_back({Pose2D(0.5, 1.0, 0.0), degToRad(12.5), 2.0, true});
    const QSize size(40, 30);
    const QImage none = renderGridImage(scene, defaultLevelPalette(), {}, smallView(), size);
    const QImage beams =
        renderGridImage(scene, defaultLevelPalette(), Overlay::Beams, smallView(), size);
    QVERIFY(beams.pixel(20, 15) != none.pixel(20, 15));
    QCOMPARE(beams.pixel(20, 6), none.pixel(20, 6));
  }

  void placeRobotBuildsRingAndBeams() {
    Dataset data;
    data.ring = SonarRing::circular(4, 0.2);
    Scan s0;
    s0.time = 0.0;
    s0.odometry = Pose2D(1.0, 2.0, 0.0);
    Scan s1 = s0;
    s1.time = 0.1;
    s1.odometry = Pose2D(1.5, 2.0, std::numbers::pi / 2);
    s1.readings = {{0, 1.25, 0.1}, {2, Reading::kNoEcho, 0.1}};
    data.scans = {s0, s1};
    GridScene scene;
    placeRobot(scene, data, PoseSource::Odometry, 1);
    QCOMPARE(scene.path.size(), std::size_t(2));
    QVERIFY(scene.robot.has_value());
    QCOMPARE(scene.sonars.size(), std::size_t(4));
    // Sonar 0 sits 0.2 m ahead of the robot; heading pi/2 puts it at (1.5, 2.2), facing +y.
    QVERIFY(std::abs(scene.sonars[0].x() - 1.5) < 1e-12);
    QVERIFY(std::abs(scene.sonars[0].y() - 2.2) < 1e-12);
    QCOMPARE(scene.beams.size(), std::size_t(2));
    QCOMPARE(scene.beams[0].range, 1.25);
    QVERIFY(!scene.beams[1].echo);
    QCOMPARE(scene.beams[1].range, data.ring.maxRange);  // no echo: drawn to the maximum range
  }

  void readCellGivesEveryLayer() {
    const auto map = smallMap();
    const CellReadout r = readCell(*map, {2.5, 0.5});  // cell (2, 0)
    QVERIFY(r.inside);
    QCOMPARE(r.cell, CellIndex(2, 0));
    QCOMPARE(r.level, 15);
    QCOMPARE(r.probability, 1.0);
    QCOMPARE(r.native, 9.0);
    QVERIFY(r.observed);
    QVERIFY(!readCell(*map, {3.01, 0.5}).inside);
    QVERIFY(!readCell(*map, {0.5, -0.01}).inside);
    QVERIFY(!readCell(*map, {0.5, 1.5}).observed);  // cell (0, 1)
    QVERIFY(describeReadout(readCell(*map, {0.5, 1.5}), "CV").contains("never observed"));
  }

  void transformRoundTripAndFit() {
    const ViewTransform t = smallView();
    const QSize size(40, 30);
    QCOMPARE(t.toPixel({0.0, 2.0}, size), QPointF(5.0, 5.0));
    const Position w = t.toWorld(QPointF(35.0, 25.0), size);
    QVERIFY((w - Position(3.0, 0.0)).norm() < 1e-12);
    // 3 m x 2 m in 40 x 30 px without margin: min(40 / 3, 30 / 2) = 13.33 px/m, centred.
    const ViewTransform fit = ViewTransform::fitting(smallMap()->spec, size, 0);
    QVERIFY(std::abs(fit.pixelsPerMetre - 40.0 / 3.0) < 1e-12);
    QVERIFY((fit.centre - Position(1.5, 1.0)).norm() < 1e-12);
  }

  void unobservedIsNotFree_data() {
    QTest::addColumn<int>("level");
    QTest::addColumn<bool>("observed");
    QTest::addColumn<bool>("unknown");
    // HIMM leaves a never-observed cell at CV 0, the level of "certainly free" (paper 000 §2.2):
    // it must be drawn unknown, and an observed CV 0 free.
    QTest::newRow("HIMM CV 0, never observed") << 0 << false << true;
    QTest::newRow("HIMM CV 0, observed free") << 0 << true << false;
    // The probability rules leave it at p 0.5, level 8 (round(15 · 0.5) = 8 in
    // levelOfProbability): still unknown; hpf × addition fills cells that stay at level ≤ 8, and
    // an observed cell is never drawn unknown.
    QTest::newRow("p 0.5, never observed") << 8 << false << true;
    QTest::newRow("filled at level 8") << 8 << true << false;
    QTest::newRow("filled at level 6") << 6 << true << false;
    QTest::newRow("occupied") << 15 << true << false;
  }

  void unobservedIsNotFree() {
    QFETCH(int, level);
    QFETCH(bool, observed);
    QFETCH(bool, unknown);
    GridSpec spec;
    spec.cellSize = 1.0;
    spec.width = 1;
    spec.height = 1;
    auto map = std::make_shared<OccupancyMap>(OccupancyMap::unobserved(spec));
    map->level = {static_cast<std::uint8_t>(level)};
    map->observed = {static_cast<std::uint8_t>(observed ? 1 : 0)};
    map->filled = {static_cast<std::uint8_t>(observed && level <= 8 ? 1 : 0)};
    ViewTransform view;
    view.centre = {0.5, 0.5};
    view.pixelsPerMetre = 10.0;
    for (const LevelPalette* palette : {&defaultLevelPalette(), &greyLevelPalette()}) {
      const QRgb expected =
          unknown ? unknownColour().rgb()
                  : qRgb((*palette)[std::size_t(level)].r, (*palette)[std::size_t(level)].g,
                         (*palette)[std::size_t(level)].b);
      // The 1 m cell covers pixels 5..14 of a 20 × 20 picture centred on it.
      QCOMPARE(renderGridCells(map.get(), *palette, view, {20, 20}).pixel(10, 10), expected);
      GridScene scene;
      scene.map = map;
      QImage vector(20, 20, QImage::Format_RGB32);
      QPainter painter(&vector);
      paintGridVector(painter, scene, *palette, {}, view, {20, 20});
      painter.end();
      QCOMPARE(vector.pixel(10, 10), expected);
    }
    CellReadout r = readCell(*map, {0.5, 0.5});
    QCOMPARE(describeReadout(r, "CV").contains("unknown"), unknown);
  }

  void unknownColourIsNoLevelAndInTheLegend() {
    for (const LevelPalette* palette : {&defaultLevelPalette(), &greyLevelPalette()})
      for (const Rgb& c : *palette) QVERIFY(unknownColour() != QColor(c.r, c.g, c.b));
    QVERIFY(unknownColour() != backgroundColour());
    const QSize size(500, 300);
    const QImage image =
        renderGridImage(GridScene{}, defaultLevelPalette(), Overlay::Legend, ViewTransform{}, size);
    const QRect swatch = legendSwatch(kLevels, size);
    QVERIFY(QRect(QPoint(0, 0), size).contains(swatch));
    QVERIFY(swatch.left() > legendSwatch(kLevels - 1, size).right());  // set apart after 15
    for (int y = swatch.top(); y <= swatch.bottom(); ++y)
      for (int x = swatch.left(); x <= swatch.right(); ++x)
        QCOMPARE(image.pixel(x, y), unknownColour().rgb());
  }

  void readoutHasOneClearProbability_data() {
    QTest::addColumn<double>("probability");
    QTest::addColumn<double>("native");
    QTest::addColumn<QString>("expected");
    QTest::addColumn<QString>("absent");
    // Bayes: the native value is the probability itself; shown once, in two significant digits
    // when below 0.001 (was "p(occ) 0.000 | p(occupied) 2.301e-86").
    QTest::newRow("tiny") << 2.301e-86 << 2.301e-86 << "p(occ) 2.3e-86"
                          << "p(occupied)";
    QTest::newRow("near 1") << 1.0 - 4.1e-7 << 1.0 - 4.1e-7 << "p(occ) 1 − 4.1e-07"
                            << "p(occ) 1.000";
    QTest::newRow("middle") << 0.25 << 0.25 << "p(occ) 0.250"
                            << "p(occupied)";
    // Log-odds: a different quantity, kept. log(0.25 / 0.75) = −1.0986.
    QTest::newRow("log-odds") << 0.25 << -1.0986 << "p(occupied) -1.099"
                              << "p(occ) 0.000";
  }

  void readoutHasOneClearProbability() {
    QFETCH(double, probability);
    QFETCH(double, native);
    QFETCH(QString, expected);
    QFETCH(QString, absent);
    CellReadout r;
    r.inside = true;
    r.observed = true;
    r.level = levelOfProbability(probability);
    r.probability = probability;
    r.native = native;
    const QString text = describeReadout(r, "p(occupied)");
    QVERIFY2(text.contains(expected), qPrintable(text));
    QVERIFY2(!text.contains(absent), qPrintable(text));
  }

  void firstViewFitsThePathAndTheReference() {
    // A 4 m × 2 m box in 100 × 60 px without margin: min(100 / 4, 60 / 2) = 25 px/m, centred at
    // (2, 1).
    const ViewTransform t = ViewTransform::fittingBox({0.0, 0.0}, {4.0, 2.0}, {100, 60}, 0);
    QCOMPARE(t.pixelsPerMetre, 25.0);
    QVERIFY((t.centre - Position(2.0, 1.0)).norm() < 1e-12);
    // The reference's corners (a 6 × 4 room and a pole at (9, 1)) bound the focus exactly.
    ReferenceMap reference;
    ReferenceObject walls;
    walls.closed = true;
    walls.corners = {{0.0, 0.0}, {6.0, 0.0}, {6.0, 4.0}, {0.0, 4.0}};
    ReferenceObject pole;
    pole.corners = {{9.0, 1.0}};
    reference.objects = {walls, pole};
    const FocusArea a = focusArea(nullptr, PoseSource::Truth, &reference);
    QVERIFY(!a.empty());
    QVERIFY((a.low - Position(0.0, 0.0)).norm() < 1e-12);
    QVERIFY((a.high - Position(9.0, 4.0)).norm() < 1e-12);
    QVERIFY(focusArea(nullptr, PoseSource::Truth, nullptr).empty());
  }

  void vectorPictureMatchesRaster() {
    // The SVG export draws the cells as one image scaled by the view: rendered into a raster
    // device with whole-pixel cell edges, it gives the raster picture exactly.
    GridScene scene;
    scene.map = smallMap();
    QImage vector(40, 30, QImage::Format_RGB32);
    QPainter painter(&vector);
    paintGridVector(painter, scene, defaultLevelPalette(), {}, smallView(), {40, 30});
    painter.end();
    QCOMPARE(vector,
             renderGridCells(scene.map.get(), defaultLevelPalette(), smallView(), {40, 30}));
  }
};

QTEST_MAIN(TestGridImage)
#include "tst_grid_image.moc"
