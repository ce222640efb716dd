// SPDX-License-Identifier: GPL-3.0-or-later
// The OpenGL surface against the raster picture: the same map, view and overlays must give the
// same pixels within a tolerance (the shader computes cell indices in single precision, so a pixel
// centre within ~1e-5 cells of a cell edge may fall on the other side; overlays blended as an
// image round differently from overlays painted onto the cells by a level or two).

#include <QSignalSpy>
#include <QtTest>
#include <random>

#include "grid_view.h"

using namespace sg;
using namespace sg::ui;

namespace {

std::shared_ptr<OccupancyMap> randomMap(int width, int height, unsigned seed) {
  GridSpec spec;
  spec.origin = {-1.3, 0.7};
  spec.cellSize = 0.05;
  spec.width = width;
  spec.height = height;
  auto map = std::make_shared<OccupancyMap>(OccupancyMap::unobserved(spec));
  std::mt19937 random(seed);
  for (auto& level : map->level) level = static_cast<std::uint8_t>(random() % 16);
  return map;
}

struct Difference {
  int pixels = 0;  // pixels whose channels differ by more than `tolerance`
  int maxDelta = 0;
};

Difference compare(const QImage& a, const QImage& b, int tolerance) {
  Difference d;
  const QImage x = a.convertToFormat(QImage::Format_RGB32);
  const QImage y = b.convertToFormat(QImage::Format_RGB32);
  for (int py = 0; py < x.height(); ++py)
    for (int px = 0; px < x.width(); ++px) {
      const QRgb p = x.pixel(px, py), q = y.pixel(px, py);
      const int delta = std::max({std::abs(qRed(p) - qRed(q)), std::abs(qGreen(p) - qGreen(q)),
                                  std::abs(qBlue(p) - qBlue(q))});
      d.maxDelta = std::max(d.maxDelta, delta);
      if (delta > tolerance) ++d.pixels;
    }
  return d;
}

}  // namespace

class TestGlView : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() {
    if (QGuiApplication::platformName() != QLatin1String("xcb"))
      QSKIP("needs the xcb platform (run under xvfb-run, ctest label gl)");
  }

  void cellsMatchTheRasterPath_data() {
    QTest::addColumn<double>("pixelsPerMetre");
    QTest::addColumn<double>("centreX");
    QTest::addColumn<double>("centreY");
    // Fitted, magnified (cells of 7.3 px) and minified (several cells per pixel) views, none
    // aligned to whole pixels.
    QTest::newRow("fit") << 0.0 << 0.0 << 0.0;
    QTest::newRow("zoomed") << 146.0 << 0.113 << 1.871;
    QTest::newRow("minified") << 9.7 << 2.0 << 3.0;
  }

  void cellsMatchTheRasterPath() {
    QFETCH(double, pixelsPerMetre);
    QFETCH(double, centreX);
    QFETCH(double, centreY);
    GridView view(GridView::Backend::OpenGL);
    QCOMPARE(view.backend(), GridView::Backend::OpenGL);
    view.resize(320, 240);
    view.setOverlays({});
    view.show();
    QVERIFY(QTest::qWaitForWindowExposed(&view));
    view.setMap(randomMap(83, 61, 7));
    if (pixelsPerMetre > 0.0) view.setView({{centreX, centreY}, pixelsPerMetre});
    const QImage gl = view.grabSurface();
    QVERIFY(!gl.isNull());
    QCOMPARE(gl.size(), QSize(320, 240));
    const QImage raster = view.renderImage();
    const Difference d = compare(gl, raster, 2);
    // Colours come from the same 16-entry table: a matching pixel matches exactly. At most 0.1 %
    // of the 76 800 pixels may sit on the other side of a cell edge.
    QVERIFY2(d.pixels <= 77, qPrintable(QStringLiteral("%1 pixels differ").arg(d.pixels)));
  }

  void overlaysMatchTheRasterPath() {
    GridView view(GridView::Backend::OpenGL);
    view.resize(320, 240);
    view.show();
    QVERIFY(QTest::qWaitForWindowExposed(&view));
    view.setMap(randomMap(83, 61, 11));
    view.setReferenceLines({{{-1.2, 0.8}, {2.8, 0.8}, {2.8, 3.6}, {-1.2, 3.6}, {-1.2, 0.8}}});
    Dataset data;
    data.ring = SonarRing::pioneer3dx();
    Scan scan;
    scan.odometry = Pose2D(0.7, 2.2, 0.4);
    for (std::uint16_t k = 0; k < 16; ++k)
      scan.readings.push_back({k, k % 4 == 0 ? Reading::kNoEcho : 0.5 + 0.1 * k, 0.0});
    data.scans = {scan};
    view.setRobotAt(&data, PoseSource::Odometry, 0);
    view.setOverlays(kAllOverlays);
    const QImage gl = view.grabSurface();
    const QImage raster = view.renderImage();
    const Difference d = compare(gl, raster, 4);
    // The overlays are composited as a premultiplied image in GL and painted straight onto the
    // cells by the raster path: the two roundings of the same blend differ by a level or two.
    QVERIFY2(d.pixels <= 77, qPrintable(QStringLiteral("%1 pixels differ by more than 4 "
                                                       "(largest difference %2)")
                                            .arg(d.pixels)
                                            .arg(d.maxDelta)));
    // ...and they were drawn at all: the picture differs from the bare cells.
    view.setOverlays({});
    const Difference bare = compare(gl, view.grabSurface(), 24);
    QVERIFY(bare.pixels > 1000);
  }
};

QTEST_MAIN(TestGlView)
#include "tst_gl_view.moc"
