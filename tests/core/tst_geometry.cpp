// SPDX-License-Identifier: BSD-3-Clause
// The geometry of the core: poses, the sonar ring presets, grid geometry, parameter sets, the beam
// lookup tables and the cone rasteriser. Every expected number is worked out by hand in the comment
// next to it; the rasteriser is also checked against a brute force over every cell of a grid.

#include <QtTest>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "sonargrid/data/dataset.h"
#include "sonargrid/data/pose.h"
#include "sonargrid/data/sonar_ring.h"
#include "sonargrid/engine/beam_tables.h"
#include "sonargrid/engine/grid_spec.h"
#include "sonargrid/models/cone_raster.h"
#include "sonargrid/params/parameters.h"

Q_DECLARE_METATYPE(sg::Dataset)

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

double deg(double d) {
  return sg::degToRad(d);
}

bool near(double a, double b, double tolerance) {
  return std::abs(a - b) <= tolerance;
}

QByteArray describe(double a, double b) {
  return QByteArray::number(a, 'g', 17) + " vs expected " + QByteArray::number(b, 'g', 17);
}

// what() of the ParameterError `fn` throws, or what happened instead.
template <class Fn>
QByteArray parameterError(Fn&& fn) {
  try {
    fn();
  } catch (const sg::ParameterError& e) {
    return QByteArray(e.what());
  } catch (const std::exception& e) {
    return QByteArray("unexpected exception: ") + e.what();
  }
  return "no error";
}

sg::ParameterSpec spec(const std::string& name, const std::string& unit, double min, double max,
                       double defaultValue, bool integer = false) {
  sg::ParameterSpec s;
  s.name = name;
  s.unit = unit;
  s.min = min;
  s.max = max;
  s.defaultValue = defaultValue;
  s.integer = integer;
  return s;
}

// epsilon in [0, 1] m (default 0.2), n a whole number in [0, 10] (default 3), k in [-5, 5] (0).
sg::ParameterSet threeParameters() {
  return sg::ParameterSet({spec("epsilon", "m", 0.0, 1.0, 0.2), spec("n", "", 0.0, 10.0, 3.0, true),
                           spec("k", "", -5.0, 5.0, 0.0)});
}

// A uniform double from the top 53 bits of the generator, so that the sequence is the same with
// every standard library (std::uniform_real_distribution is not specified bit for bit).
class Random {
 public:
  explicit Random(std::uint64_t seed) : bits_(seed) {}
  double uniform(double lo, double hi) {
    return lo + (hi - lo) * (static_cast<double>(bits_() >> 11U) * 0x1.0p-53);
  }
  int below(int n) { return static_cast<int>(bits_() % static_cast<std::uint64_t>(n)); }

 private:
  std::mt19937_64 bits_;
};

struct Visit {
  std::uint32_t cell;
  double delta;
  double theta;
};

// What forEachConeCell did: the cells with their delta and theta, and its reserve() calls.
struct Raster {
  std::vector<Visit> visits;
  int reserveCalls = 0;
  std::size_t bound = 0;
  bool reservedFirst = true;  // reserve() came before the first cell
};

Raster rasterise(const sg::Pose2D& sensor, double reach, double halfAngle, const sg::GridSpec& grid,
                 const sg::BeamTables& tables) {
  Raster out;
  sg::forEachConeCell(
      sensor, reach, halfAngle, grid, tables,
      [&out](std::size_t bound) {
        ++out.reserveCalls;
        out.bound = bound;
      },
      [&out](std::uint32_t cell, double delta, double theta) {
        if (out.reserveCalls == 0) out.reservedFirst = false;
        out.visits.push_back({cell, delta, theta});
      });
  return out;
}

// The cells of the cone by brute force: every cell of the grid goes through the acceptance test of
// cone_raster.h (table entry of the sensor's quantised sub-cell apex, distance <= (float)reach,
// bearing within halfAngle of the heading after one wrap), in row-major order.
std::vector<Visit> bruteForceCone(const sg::Pose2D& sensor, double reach, double halfAngle,
                                  const sg::GridSpec& grid, const sg::BeamTables& tables) {
  const double c = grid.cellSize;
  const double u = (sensor.x() - grid.origin.x()) / c;
  const double v = (sensor.y() - grid.origin.y()) / c;
  const int q = tables.subdivisions();
  const int qx = std::min(q - 1, static_cast<int>((u - std::floor(u)) * q));
  const int qy = std::min(q - 1, static_cast<int>((v - std::floor(v)) * q));
  const int iu = static_cast<int>(std::floor(u));
  const int iv = static_cast<int>(std::floor(v));
  const int r = tables.radius();
  const float reachF = static_cast<float>(reach);
  std::vector<Visit> out;
  for (int iy = 0; iy < grid.height; ++iy) {
    for (int ix = 0; ix < grid.width; ++ix) {
      const int dx = ix - iu;
      const int dy = iy - iv;
      // Beyond the table every cell centre is more than radius - 1 cells away, out of reach.
      if (std::abs(dx) > r || std::abs(dy) > r) continue;
      const sg::BeamTables::Entry e = tables.entry(qx, qy, dx, dy);
      if (!(e.distance <= reachF)) continue;
      double theta = static_cast<double>(e.bearing) - sensor.heading;
      if (theta > kPi) {
        theta -= 2.0 * kPi;
      } else if (theta < -kPi) {
        theta += 2.0 * kPi;
      }
      if (!(std::abs(theta) <= halfAngle)) continue;
      out.push_back({static_cast<std::uint32_t>(grid.linear(sg::CellIndex(ix, iy))),
                     static_cast<double>(e.distance), theta});
    }
  }
  return out;
}

QByteArray beamText(const sg::Pose2D& s, double reach, double halfAngle) {
  return "sensor (" + QByteArray::number(s.x(), 'g', 17) + ", " +
         QByteArray::number(s.y(), 'g', 17) + ", " + QByteArray::number(s.heading, 'g', 17) +
         ") reach " + QByteArray::number(reach, 'g', 17) + " halfAngle " +
         QByteArray::number(halfAngle, 'g', 17);
}

}  // namespace

class TstGeometry : public QObject {
  Q_OBJECT

 private slots:
  void compose_data();
  void compose();
  void transform_data();
  void transform();
  void wrapAngle_data();
  void wrapAngle();

  void pioneer3dx_data();
  void pioneer3dx();
  void amigobot_data();
  void amigobot();
  void k2a_data();
  void k2a();
  void presetByName_data();
  void presetByName();

  void worldToCell_data();
  void worldToCell();
  void cellRoundTrips();
  void covering_data();
  void covering();
  void coveringRefused_data();
  void coveringRefused();
  void fittingGrid_data();
  void fittingGrid();
  void fittingGridRefused_data();
  void fittingGridRefused();
  void gridLimitErrorInFile();

  void parameterSetGet();
  void parameterErrors_data();
  void parameterErrors();
  void parameterAppend();

  void beamTableEntries_data();
  void beamTableEntries();
  void beamTablesShared();
  void beamTablesFilledByEveryCore();
  void beamTablesMirrorIsExact();

  void coneTiny_data();
  void coneTiny();
  void coneMatchesBruteForce();
};

// ---------------------------------------------------------------------------------------------
// Pose2D

void TstGeometry::compose_data() {
  QTest::addColumn<double>("x");
  QTest::addColumn<double>("y");
  QTest::addColumn<double>("headingDeg");
  QTest::addColumn<double>("lx");
  QTest::addColumn<double>("ly");
  QTest::addColumn<double>("lheadingDeg");
  QTest::addColumn<double>("ex");
  QTest::addColumn<double>("ey");
  QTest::addColumn<double>("eheading");  // radians

  // Rotating (0.1, 0) by 90° gives (0, 0.1); added to (1, 2): (1, 2.1). Headings add: 90° + 0°.
  QTest::addRow("robot at 90 deg, sonar ahead")
      << 1.0 << 2.0 << 90.0 << 0.1 << 0.0 << 0.0 << 1.0 << 2.1 << kPi / 2;
  // The identity pose leaves the local pose as it is (heading 30° = pi/6).
  QTest::addRow("identity") << 0.0 << 0.0 << 0.0 << 0.3 << -0.4 << 30.0 << 0.3 << -0.4 << kPi / 6;
  // Rotating by -90° maps (x, y) to (y, -x): (0.3, 0.4) -> (0.4, -0.3); plus (2, -1) gives
  // (2.4, -1.3). Heading -90° + 30° = -60° = -pi/3.
  QTest::addRow("robot at -90 deg")
      << 2.0 << -1.0 << -90.0 << 0.3 << 0.4 << 30.0 << 2.4 << -1.3 << -kPi / 3;
  // Rotating by 180° negates: (0.2, 0.1) -> (-0.2, -0.1); plus (1, 1) gives (0.8, 0.9). The heading
  // 180° + 0° = pi wraps to -pi (the range is [-pi, pi)).
  QTest::addRow("180 deg wraps to -pi")
      << 1.0 << 1.0 << 180.0 << 0.2 << 0.1 << 0.0 << 0.8 << 0.9 << -kPi;
  // 170° + 20° = 190° wraps to 190 - 360 = -170° = -17pi/18. Position: no offset.
  QTest::addRow("heading sum wraps")
      << 0.0 << 0.0 << 170.0 << 0.0 << 0.0 << 20.0 << 0.0 << 0.0 << -17 * kPi / 18;
  // p3dx sonar 1 (0.114, 0.119, 50°) on a robot at (0, 0, 45°): rotating by 45° maps (x, y) to
  // ((x - y)/sqrt2, (x + y)/sqrt2) = (-0.005/sqrt2, 0.233/sqrt2) = (-0.0035355339, 0.1647558800);
  // heading 95° = 19pi/36.
  QTest::addRow("p3dx sonar 1 at 45 deg") << 0.0 << 0.0 << 45.0 << 0.114 << 0.119 << 50.0
                                          << -0.0035355339 << 0.1647558800 << 19 * kPi / 36;
}

void TstGeometry::compose() {
  QFETCH(double, x);
  QFETCH(double, y);
  QFETCH(double, headingDeg);
  QFETCH(double, lx);
  QFETCH(double, ly);
  QFETCH(double, lheadingDeg);
  QFETCH(double, ex);
  QFETCH(double, ey);
  QFETCH(double, eheading);
  const sg::Pose2D p =
      sg::Pose2D(x, y, deg(headingDeg)).compose(sg::Pose2D(lx, ly, deg(lheadingDeg)));
  // 1e-9: the hand values above are given to 10 decimals.
  QVERIFY2(near(p.x(), ex, 1e-9), describe(p.x(), ex));
  QVERIFY2(near(p.y(), ey, 1e-9), describe(p.y(), ey));
  QVERIFY2(near(p.heading, eheading, 1e-12), describe(p.heading, eheading));
  QVERIFY(p.heading >= -kPi && p.heading < kPi);
}

void TstGeometry::transform_data() {
  QTest::addColumn<double>("x");
  QTest::addColumn<double>("y");
  QTest::addColumn<double>("headingDeg");
  QTest::addColumn<double>("px");
  QTest::addColumn<double>("py");
  QTest::addColumn<double>("ex");
  QTest::addColumn<double>("ey");

  // (1, 0) turned by 90° is (0, 1); plus (1, 2): (1, 3).
  QTest::addRow("90 deg") << 1.0 << 2.0 << 90.0 << 1.0 << 0.0 << 1.0 << 3.0;
  // (1, 2) turned by 180° is (-1, -2); plus (3, 4): (2, 2).
  QTest::addRow("180 deg") << 3.0 << 4.0 << 180.0 << 1.0 << 2.0 << 2.0 << 2.0;
  // (2, 0) turned by 30° is (2 cos 30°, 2 sin 30°) = (sqrt3, 1) = (1.7320508076, 1); plus (-1, 0).
  QTest::addRow("30 deg") << -1.0 << 0.0 << 30.0 << 2.0 << 0.0 << 0.7320508076 << 1.0;
  // The origin of the local frame is the pose's position.
  QTest::addRow("local origin") << 5.0 << -6.0 << 123.0 << 0.0 << 0.0 << 5.0 << -6.0;
}

void TstGeometry::transform() {
  QFETCH(double, x);
  QFETCH(double, y);
  QFETCH(double, headingDeg);
  QFETCH(double, px);
  QFETCH(double, py);
  QFETCH(double, ex);
  QFETCH(double, ey);
  const sg::Position p = sg::Pose2D(x, y, deg(headingDeg)).transform(sg::Position(px, py));
  QVERIFY2(near(p.x(), ex, 1e-9), describe(p.x(), ex));
  QVERIFY2(near(p.y(), ey, 1e-9), describe(p.y(), ey));
  // compose() moves the position the same way.
  const sg::Pose2D c = sg::Pose2D(x, y, deg(headingDeg)).compose(sg::Pose2D(px, py, 0.0));
  QVERIFY(near(c.x(), p.x(), 1e-15) && near(c.y(), p.y(), 1e-15));
}

void TstGeometry::wrapAngle_data() {
  QTest::addColumn<double>("angle");
  QTest::addColumn<double>("expected");
  QTest::addColumn<double>("tolerance");

  // The range is [-pi, pi): pi itself maps to -pi, exactly (pi + pi = 2pi, fmod gives 0, 0 - pi).
  QTest::addRow("zero") << 0.0 << 0.0 << 0.0;
  QTest::addRow("pi") << kPi << -kPi << 0.0;
  QTest::addRow("-pi") << -kPi << -kPi << 0.0;
  QTest::addRow("pi/2") << kPi / 2 << kPi / 2 << 0.0;
  QTest::addRow("-pi/2") << -kPi / 2 << -kPi / 2 << 0.0;
  // Whole turns: 2pi -> 0, 3pi -> pi -> -pi, -3pi -> -pi.
  QTest::addRow("2pi") << 2 * kPi << 0.0 << 1e-15;
  QTest::addRow("-2pi") << -2 * kPi << 0.0 << 1e-15;
  QTest::addRow("3pi") << 3 * kPi << -kPi << 1e-15;
  QTest::addRow("-3pi") << -3 * kPi << -kPi << 1e-15;
  // 7pi/2 = 2pi + 3pi/2 -> 3pi/2 - 2pi = -pi/2; -7pi/2 -> pi/2.
  QTest::addRow("7pi/2") << 3.5 * kPi << -kPi / 2 << 1e-15;
  QTest::addRow("-7pi/2") << -3.5 * kPi << kPi / 2 << 1e-15;
  // 190° -> -170°; -190° -> 170°.
  QTest::addRow("190 deg") << deg(190) << deg(-170) << 1e-15;
  QTest::addRow("-190 deg") << deg(-190) << deg(170) << 1e-15;
  // 1000 rad: 1000 / 2pi = 159.15..., so 1000 - 159 * 2pi = 1000 - 999.0264638415542 =
  // 0.9735361584458 (already in range).
  QTest::addRow("1000 rad") << 1000.0 << 0.9735361584458 << 1e-12;
  // Angles already in range come back to within rounding of pi (a + pi - pi): 0.1 stays 0.1.
  QTest::addRow("0.1") << 0.1 << 0.1 << 1e-15;
  QTest::addRow("-3") << -3.0 << -3.0 << 1e-15;
}

void TstGeometry::wrapAngle() {
  QFETCH(double, angle);
  QFETCH(double, expected);
  QFETCH(double, tolerance);
  const double w = sg::wrapAngle(angle);
  QVERIFY2(near(w, expected, tolerance), describe(w, expected));
  QVERIFY2(w >= -kPi && w < kPi, describe(w, expected));
}

// ---------------------------------------------------------------------------------------------
// Sonar rings (the published ring geometry, docs/formats.md: x mm, y mm, heading deg)

namespace {

void addMountColumns() {
  QTest::addColumn<int>("index");
  QTest::addColumn<double>("x");
  QTest::addColumn<double>("y");
  QTest::addColumn<double>("heading");
}

// Positions are mm / 1000, a correctly rounded division, so they equal the decimal literals
// exactly. Headings are deg * pi / 180, compared with the fraction of pi to 1e-15.
void checkMount(const sg::SonarRing& ring) {
  QFETCH(int, index);
  QFETCH(double, x);
  QFETCH(double, y);
  QFETCH(double, heading);
  QVERIFY(index >= 0 && static_cast<std::size_t>(index) < ring.size());
  const sg::Pose2D& p = ring.sonars[static_cast<std::size_t>(index)].pose;
  QVERIFY2(p.x() == x, describe(p.x(), x));
  QVERIFY2(p.y() == y, describe(p.y(), y));
  QVERIFY2(near(p.heading, heading, 1e-15), describe(p.heading, heading));
}

}  // namespace

void TstGeometry::pioneer3dx_data() {
  addMountColumns();
  QTest::addRow("0 left") << 0 << 0.069 << 0.136 << kPi / 2;             // 69 136 90
  QTest::addRow("1") << 1 << 0.114 << 0.119 << 5 * kPi / 18;             // 114 119 50
  QTest::addRow("2") << 2 << 0.148 << 0.078 << kPi / 6;                  // 148 78 30
  QTest::addRow("3 front") << 3 << 0.166 << 0.027 << kPi / 18;           // 166 27 10
  QTest::addRow("4 front") << 4 << 0.166 << -0.027 << -kPi / 18;         // 166 -27 -10
  QTest::addRow("7 right") << 7 << 0.069 << -0.136 << -kPi / 2;          // 69 -136 -90
  QTest::addRow("8 rear right") << 8 << -0.157 << -0.136 << -kPi / 2;    // -157 -136 -90
  QTest::addRow("9") << 9 << -0.203 << -0.119 << -13 * kPi / 18;         // -203 -119 -130
  QTest::addRow("11 back") << 11 << -0.255 << -0.027 << -17 * kPi / 18;  // -255 -27 -170
  QTest::addRow("12 back") << 12 << -0.255 << 0.027 << 17 * kPi / 18;    // -255 27 170
  QTest::addRow("15 rear left") << 15 << -0.157 << 0.136 << kPi / 2;     // -157 136 90
}

void TstGeometry::pioneer3dx() {
  const sg::SonarRing ring = sg::SonarRing::pioneer3dx();
  QCOMPARE(ring.size(), std::size_t{16});
  QCOMPARE(ring.robot, std::string("p3dx"));
  // The ring's defaults: 25° cone, 0.15 m to 5 m.
  QCOMPARE(ring.apertureRad, 25 * kPi / 180);
  QCOMPARE(ring.minRange, 0.15);
  QCOMPARE(ring.maxRange, 5.0);
  checkMount(ring);
}

void TstGeometry::amigobot_data() {
  addMountColumns();
  QTest::addRow("0 left") << 0 << 0.076 << 0.1 << kPi / 2;            // 76 100 90
  QTest::addRow("1") << 1 << 0.125 << 0.075 << 41 * kPi / 180;        // 125 75 41
  QTest::addRow("2 front") << 2 << 0.15 << 0.03 << kPi / 12;          // 150 30 15
  QTest::addRow("3 front") << 3 << 0.15 << -0.03 << -kPi / 12;        // 150 -30 -15
  QTest::addRow("5 right") << 5 << 0.076 << -0.1 << -kPi / 2;         // 76 -100 -90
  QTest::addRow("6 rear") << 6 << -0.14 << -0.058 << -29 * kPi / 36;  // -140 -58 -145
  QTest::addRow("7 rear") << 7 << -0.14 << 0.058 << 29 * kPi / 36;    // -140 58 145
}

void TstGeometry::amigobot() {
  const sg::SonarRing ring = sg::SonarRing::amigobot();
  QCOMPARE(ring.size(), std::size_t{8});
  QCOMPARE(ring.robot, std::string("amigobot"));
  checkMount(ring);
}

void TstGeometry::k2a_data() {
  QTest::addColumn<int>("index");
  QTest::addColumn<double>("x");
  QTest::addColumn<double>("y");
  QTest::addColumn<double>("heading");

  // Sonar i faces i * 15° (wrapped to [-180°, 180°)) and sits 0.3 m out along that direction.
  QTest::addRow("0 forward") << 0 << 0.3 << 0.0 << 0.0;
  // 15°: (0.3 cos 15°, 0.3 sin 15°) = (0.3 * 0.9659258263, 0.3 * 0.2588190451).
  QTest::addRow("1") << 1 << 0.2897777479 << 0.0776457135 << kPi / 12;
  QTest::addRow("6 left") << 6 << 0.0 << 0.3 << kPi / 2;  // 90°
  // 180° wraps to -180° = -pi exactly; the position is (-0.3, 0).
  QTest::addRow("12 back") << 12 << -0.3 << 0.0 << -kPi;
  // 195° wraps to -165°: (0.3 cos 195°, 0.3 sin 195°) = (-0.2897777479, -0.0776457135).
  QTest::addRow("13") << 13 << -0.2897777479 << -0.0776457135 << -11 * kPi / 12;
  QTest::addRow("18 right") << 18 << 0.0 << -0.3 << -kPi / 2;               // 270° -> -90°
  QTest::addRow("23") << 23 << 0.2897777479 << -0.0776457135 << -kPi / 12;  // 345° -> -15°
}

void TstGeometry::k2a() {
  QFETCH(int, index);
  QFETCH(double, x);
  QFETCH(double, y);
  QFETCH(double, heading);
  const sg::SonarRing ring = sg::SonarRing::k2a();
  QCOMPARE(ring.size(), std::size_t{24});
  QCOMPARE(ring.robot, std::string("k2a"));
  const sg::Pose2D& p = ring.sonars[static_cast<std::size_t>(index)].pose;
  QVERIFY2(near(p.x(), x, 1e-10), describe(p.x(), x));
  QVERIFY2(near(p.y(), y, 1e-10), describe(p.y(), y));
  // 2pi * i / 24 goes through fmod in wrapAngle: a few ulps of 2pi (1e-14) for i past 12.
  QVERIFY2(near(p.heading, heading, 1e-14), describe(p.heading, heading));

  // Every neighbour is 15° further round, and every sonar 0.3 m out (another radius on request).
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const sg::Pose2D& a = ring.sonars[i].pose;
    const sg::Pose2D& b = ring.sonars[(i + 1) % ring.size()].pose;
    QVERIFY2(near(sg::wrapAngle(b.heading - a.heading), kPi / 12, 1e-12), QByteArray::number(i));
    QVERIFY2(near(a.position.norm(), 0.3, 1e-15), QByteArray::number(i));
  }
  QVERIFY(near(sg::SonarRing::k2a(0.5).sonars[12].pose.x(), -0.5, 1e-15));
}

void TstGeometry::presetByName_data() {
  QTest::addColumn<QString>("name");
  QTest::addColumn<bool>("known");
  QTest::addColumn<int>("size");

  QTest::addRow("p3dx") << "p3dx" << true << 16;
  QTest::addRow("amigobot") << "amigobot" << true << 8;
  QTest::addRow("k2a") << "k2a" << true << 24;
  // Names are matched exactly: no case folding, no aliases.
  QTest::addRow("capitals") << "P3DX" << false << 0;
  QTest::addRow("alias") << "pioneer" << false << 0;
  QTest::addRow("custom") << "custom" << false << 0;
  QTest::addRow("empty") << "" << false << 0;
}

void TstGeometry::presetByName() {
  QFETCH(QString, name);
  QFETCH(bool, known);
  QFETCH(int, size);
  // An unknown name leaves `out` alone; a known one replaces it whole.
  sg::SonarRing out = sg::SonarRing::circular(3, 1.0);
  const sg::SonarRing before = out;
  QCOMPARE(sg::SonarRing::preset(name.toStdString(), out), known);
  if (!known) {
    QVERIFY(out == before);
    return;
  }
  QCOMPARE(out.size(), static_cast<std::size_t>(size));
  QCOMPARE(out.robot, name.toStdString());
  const std::vector<std::string> names = sg::SonarRing::presetNames();
  QVERIFY(std::find(names.begin(), names.end(), name.toStdString()) != names.end());
  QCOMPARE(names, (std::vector<std::string>{"p3dx", "amigobot", "k2a"}));
}

// ---------------------------------------------------------------------------------------------
// GridSpec

void TstGeometry::worldToCell_data() {
  QTest::addColumn<double>("ox");
  QTest::addColumn<double>("oy");
  QTest::addColumn<double>("cell");
  QTest::addColumn<double>("px");
  QTest::addColumn<double>("py");
  QTest::addColumn<int>("ix");
  QTest::addColumn<int>("iy");

  // (x - ox) / cell, rounded down.
  QTest::addRow("inside") << 0.0 << 0.0 << 0.25 << 0.6 << 1.1 << 2 << 4;  // 2.4 -> 2, 4.4 -> 4
  QTest::addRow("origin") << 0.0 << 0.0 << 0.25 << 0.0 << 0.0 << 0 << 0;
  // A cell is closed at its lower edge: x = 0.5 is the first point of cell 2 (0.5 / 0.25 = 2).
  QTest::addRow("lower edge") << 0.0 << 0.0 << 0.25 << 0.5 << 0.25 << 2 << 1;
  // Negative: -0.4 -> -1 and -1.2 -> -2 (floor); truncation would give 0 and -1.
  QTest::addRow("negative") << 0.0 << 0.0 << 0.25 << -0.1 << -0.3 << -1 << -2;
  QTest::addRow("just below origin") << 0.0 << 0.0 << 0.25 << -1e-12 << -1e-12 << -1 << -1;
  // Offset origin (-1, -2), 0.5 m cells: (0.2 + 1) / 0.5 = 2.4 -> 2; (-0.7 + 2) / 0.5 = 2.6 -> 2.
  QTest::addRow("offset origin") << -1.0 << -2.0 << 0.5 << 0.2 << -0.7 << 2 << 2;
  // Left of an offset origin: (-1.3 + 1) / 0.5 = -0.6 -> -1; (-2.75 + 2) / 0.5 = -1.5 -> -2.
  QTest::addRow("left of offset origin") << -1.0 << -2.0 << 0.5 << -1.3 << -2.75 << -1 << -2;
  // Far and non-finite points give +-2^28 = 268435456 on that axis (grid_spec.h): outside every
  // grid, never an int overflow. 1e12 / 0.25 = 4e12 cells; 2^28 - 1 cells is still exact.
  constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
  constexpr double kInf = std::numeric_limits<double>::infinity();
  QTest::addRow("1e12") << 0.0 << 0.0 << 0.25 << 1e12 << 0.6 << 268435456 << 2;
  QTest::addRow("-1e12") << 0.0 << 0.0 << 0.25 << 0.6 << -1e12 << 2 << -268435456;
  QTest::addRow("NaN") << 0.0 << 0.0 << 0.25 << kNan << kNan << -268435456 << -268435456;
  QTest::addRow("inf, -inf") << 0.0 << 0.0 << 0.25 << kInf << -kInf << 268435456 << -268435456;
  QTest::addRow("2^28 - 1 cells") << 0.0 << 0.0 << 1.0 << 268435455.5 << -268435455.5 << 268435455
                                  << -268435456;
}

void TstGeometry::worldToCell() {
  QFETCH(double, ox);
  QFETCH(double, oy);
  QFETCH(double, cell);
  QFETCH(double, px);
  QFETCH(double, py);
  QFETCH(int, ix);
  QFETCH(int, iy);
  sg::GridSpec g;
  g.origin = sg::Position(ox, oy);
  g.cellSize = cell;
  g.width = 10;
  g.height = 10;
  const sg::CellIndex c = g.worldToCell(sg::Position(px, py));
  QCOMPARE(c.x(), ix);
  QCOMPARE(c.y(), iy);
  QCOMPARE(g.contains(c), ix >= 0 && iy >= 0 && ix < 10 && iy < 10);
}

void TstGeometry::cellRoundTrips() {
  sg::GridSpec g;
  g.origin = sg::Position(-1.3, 0.45);
  g.cellSize = 0.05;
  g.width = 7;
  g.height = 5;
  QCOMPARE(g.cellCount(), std::size_t{35});
  QVERIFY(near(g.widthMetres(), 0.35, 1e-15));   // 7 * 0.05
  QVERIFY(near(g.heightMetres(), 0.25, 1e-15));  // 5 * 0.05

  // Cell (3, 2): centre (-1.3 + 3.5 * 0.05, 0.45 + 2.5 * 0.05) = (-1.125, 0.575); linear 2 * 7 + 3.
  const sg::Position centre = g.cellCentre(sg::CellIndex(3, 2));
  QVERIFY2(near(centre.x(), -1.125, 1e-12), describe(centre.x(), -1.125));
  QVERIFY2(near(centre.y(), 0.575, 1e-12), describe(centre.y(), 0.575));
  QCOMPARE(g.linear(sg::CellIndex(3, 2)), std::size_t{17});
  QCOMPARE(g.fromLinear(17), sg::CellIndex(3, 2));
  QCOMPARE(g.fromLinear(34), sg::CellIndex(6, 4));  // the last cell: 4 * 7 + 6
  QCOMPARE(g.fromLinear(7), sg::CellIndex(0, 1));   // first of the second row

  QVERIFY(!g.contains(sg::CellIndex(-1, 0)));
  QVERIFY(!g.contains(sg::CellIndex(7, 0)));
  QVERIFY(!g.contains(sg::CellIndex(0, 5)));
  QVERIFY(g.contains(sg::CellIndex(6, 4)));

  // Every cell: linear <-> cell, centre -> the same cell, and the corners of the cell -> it too.
  for (std::size_t i = 0; i < g.cellCount(); ++i) {
    const sg::CellIndex c = g.fromLinear(i);
    QVERIFY(g.contains(c));
    QCOMPARE(g.linear(c), i);
    QCOMPARE(g.worldToCell(g.cellCentre(c)), c);
    const sg::Position p = g.cellCentre(c);
    const double h = 0.49 * g.cellSize;
    for (const sg::Position& corner :
         {sg::Position(p.x() - h, p.y() - h), sg::Position(p.x() + h, p.y() + h)}) {
      QCOMPARE(g.worldToCell(corner), c);
    }
  }
}

void TstGeometry::covering_data() {
  QTest::addColumn<double>("lox");
  QTest::addColumn<double>("loy");
  QTest::addColumn<double>("hix");
  QTest::addColumn<double>("hiy");
  QTest::addColumn<double>("cell");
  QTest::addColumn<double>("margin");
  QTest::addColumn<double>("ox");
  QTest::addColumn<double>("oy");
  QTest::addColumn<int>("width");
  QTest::addColumn<int>("height");

  // origin = floor((lo - margin) / cell) * cell; size = ceil((hi + margin - origin) / cell).
  // A point, 0.05 m cells, 0.5 m margin: -0.5 / 0.05 = -10 -> origin -0.5; 1.0 / 0.05 = 20 cells.
  QTest::addRow("point") << 0.0 << 0.0 << 0.0 << 0.0 << 0.05 << 0.5 << -0.5 << -0.5 << 20 << 20;
  // Snapped: x (0.3 - 0.5) / 0.25 = -0.8 -> -1 -> -0.25; y (-0.6 - 0.5) / 0.25 = -4.4 -> -5 ->
  // -1.25. Width (1.1 + 0.5 + 0.25) / 0.25 = 7.4 -> 8; height (0.7 + 0.5 + 1.25) / 0.25 = 9.8
  // -> 10.
  QTest::addRow("snapped") << 0.3 << -0.6 << 1.1 << 0.7 << 0.25 << 0.5 << -0.25 << -1.25 << 8 << 10;
  // Already on the lattice, no margin: origin (-2, -3), 1 m / 0.5 = 2 cells each way.
  QTest::addRow("aligned, negative")
      << -2.0 << -3.0 << -1.0 << -2.0 << 0.5 << 0.0 << -2.0 << -3.0 << 2 << 2;
  // Negative box off the lattice: (-2.3 - 0.1) / 0.5 = -4.8 -> -5 -> -2.5; (-0.2 - 0.1) / 0.5 =
  // -0.6 -> -1 -> -0.5. Width (-1.05 + 0.1 + 2.5) / 0.5 = 3.1 -> 4; height (0.3 + 0.1 + 0.5) / 0.5
  // = 1.8 -> 2.
  QTest::addRow("negative, off lattice")
      << -2.3 << -0.2 << -1.05 << 0.3 << 0.5 << 0.1 << -2.5 << -0.5 << 4 << 2;
  // An empty box on a lattice point still gets one cell: origin (1, 1), ceil(0) = 0 -> 1.
  QTest::addRow("empty box") << 1.0 << 1.0 << 1.0 << 1.0 << 1.0 << 0.0 << 1.0 << 1.0 << 1 << 1;
  // The cap itself (sg::kMaxGridCells = 2e8) is allowed: 1 m cells, ceil(19999.5) = 20000 columns,
  // ceil(9999.5) = 10000 rows.
  QTest::addRow("at the limit") << 0.0 << 0.0 << 19999.5 << 9999.5 << 1.0 << 0.0 << 0.0 << 0.0
                                << 20000 << 10000;
  // Far from the origin but small: a log at 1e12 m is fine as long as it stays together.
  // floor((1e12 - 0.5) / 0.5) = 1999999999999 cells -> 999999999999.5; (1e12 + 1.5 -
  // 999999999999.5) / 0.5 = 4 columns; y floor(-0.5 / 0.5) = -1 -> -0.5, (0.5 + 0.5) / 0.5 = 2
  // rows.
  QTest::addRow("far but small") << 1e12 << 0.0 << 1e12 + 1.0 << 0.0 << 0.5 << 0.5 << 999999999999.5
                                 << -0.5 << 4 << 2;
}

void TstGeometry::coveringRefused_data() {
  QTest::addColumn<double>("lox");
  QTest::addColumn<double>("loy");
  QTest::addColumn<double>("hix");
  QTest::addColumn<double>("hiy");
  QTest::addColumn<double>("cell");
  QTest::addColumn<double>("margin");
  QTest::addColumn<QString>("message");

  constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const QString limit = QStringLiteral(", more than the grid limit of 200000000 cells");
  // 1e12 / 0.05 = 2e13 columns (an int would overflow; the old code made 1 of them).
  QTest::addRow("x = 1e12") << 0.0 << 0.0 << 1e12 << 0.0 << 0.05 << 0.0
                            << "x 0 to 1e+12 m, y 0 to 0 m make a grid of 20000000000000 x 1 "
                               "cells of 0.05 m" +
                                   limit;
  // Origin floor(-1e12 / 0.05) = -2e13 cells, the same 2e13 columns.
  QTest::addRow("x = -1e12") << -1e12 << 0.0 << 0.0 << 0.0 << 0.05 << 0.0
                             << "x -1e+12 to 0 m, y 0 to 0 m make a grid of 20000000000000 x 1 "
                                "cells of 0.05 m" +
                                    limit;
  // The cap at 1 m cells: 20000 x 10000 = 2e8 is allowed (covering_data, "at the limit"); one row
  // more, 20000 x 10001 = 200,020,000, is not.
  QTest::addRow("just over the limit")
      << 0.0 << 0.0 << 19999.5 << 10000.5 << 1.0 << 0.0
      << "x 0 to 19999.5 m, y 0 to 10000.5 m make a grid of 20000 x 10001 cells of 1 m" + limit;
  // One side alone beyond the cap: 200,000,001 columns of one row.
  QTest::addRow("one side over the limit")
      << 0.0 << 0.0 << 200000000.5 << 0.0 << 1.0 << 0.0
      << "x 0 to 2e+08 m, y 0 to 0 m make a grid of 200000001 x 1 cells of 1 m" + limit;
  // 2e300 / 1e-3 = 2e303 cells a side: the product is inf, each side is checked first.
  QTest::addRow("sides beyond any integer")
      << -1e300 << -1e300 << 1e300 << 1e300 << 0.001 << 0.0
      << "x -1e+300 to 1e+300 m, y -1e+300 to 1e+300 m make a grid of 2e+303 x 2e+303 cells of "
         "0.001 m" +
             limit;
  // The margin counts: 0.5 m either side of a point at 0.05 m is 20 cells, at 1e-5 m it is
  // 100000 x 100000 = 1e10 cells.
  QTest::addRow("margin makes it too large")
      << 0.0 << 0.0 << 0.0 << 0.0 << 1e-5 << 0.5
      << "x 0 to 0 m, y 0 to 0 m grown by 0.5 m make a grid of 100000 x 100000 cells of 1e-05 m" +
             limit;
  QTest::addRow("NaN") << kNan << 0.0 << 1.0 << 1.0 << 0.05 << 0.5
                       << "the extent is not finite: x nan to 1 m, y 0 to 1 m";
  QTest::addRow("inf") << 0.0 << 0.0 << kInf << 1.0 << 0.05 << 0.5
                       << "the extent is not finite: x 0 to inf m, y 0 to 1 m";
  QTest::addRow("-inf") << 0.0 << -kInf << 1.0 << 1.0 << 0.05 << 0.5
                        << "the extent is not finite: x 0 to 1 m, y -inf to 1 m";
  QTest::addRow("cell 0") << 0.0 << 0.0 << 1.0 << 1.0 << 0.0 << 0.5
                          << "the cell size is 0 m; it must be a positive, finite number of metres";
  QTest::addRow("cell NaN") << 0.0 << 0.0 << 1.0 << 1.0 << kNan << 0.5
                            << "the cell size is nan m; it must be a positive, finite number of "
                               "metres";
  QTest::addRow("cell negative")
      << 0.0 << 0.0 << 1.0 << 1.0 << -0.05 << 0.5
      << "the cell size is -0.05 m; it must be a positive, finite number of metres";
  QTest::addRow("margin inf") << 0.0 << 0.0 << 1.0 << 1.0 << 0.05 << kInf
                              << "the margin inf m is not finite";
}

void TstGeometry::coveringRefused() {
  QFETCH(double, lox);
  QFETCH(double, loy);
  QFETCH(double, hix);
  QFETCH(double, hiy);
  QFETCH(double, cell);
  QFETCH(double, margin);
  QFETCH(QString, message);
  try {
    const sg::GridSpec g =
        sg::GridSpec::covering(sg::Position(lox, loy), sg::Position(hix, hiy), cell, margin);
    QFAIL(qPrintable(QStringLiteral("made a grid of %1 x %2 cells").arg(g.width).arg(g.height)));
  } catch (const sg::GridLimitError& e) {
    QCOMPARE(QString::fromStdString(e.what()), message);
    QCOMPARE(QString::fromStdString(e.message()), message);
    QVERIFY(e.file().empty());
  }
}

void TstGeometry::covering() {
  QFETCH(double, lox);
  QFETCH(double, loy);
  QFETCH(double, hix);
  QFETCH(double, hiy);
  QFETCH(double, cell);
  QFETCH(double, margin);
  QFETCH(double, ox);
  QFETCH(double, oy);
  QFETCH(int, width);
  QFETCH(int, height);
  const sg::GridSpec g =
      sg::GridSpec::covering(sg::Position(lox, loy), sg::Position(hix, hiy), cell, margin);
  QCOMPARE(g.cellSize, cell);
  QVERIFY2(near(g.origin.x(), ox, 1e-12), describe(g.origin.x(), ox));
  QVERIFY2(near(g.origin.y(), oy, 1e-12), describe(g.origin.y(), oy));
  QCOMPARE(g.width, width);
  QCOMPARE(g.height, height);

  // The origin is a whole number of cells from (0, 0), and the grid holds the grown box.
  QVERIFY(near(g.origin.x() / cell, std::round(g.origin.x() / cell), 1e-9));
  QVERIFY(near(g.origin.y() / cell, std::round(g.origin.y() / cell), 1e-9));
  QVERIFY(g.origin.x() <= lox - margin + 1e-12 && g.origin.y() <= loy - margin + 1e-12);
  QVERIFY(g.origin.x() + g.widthMetres() >= hix + margin - 1e-12);
  QVERIFY(g.origin.y() + g.heightMetres() >= hiy + margin - 1e-12);
}

namespace {

// Two sonars 0.5 m ahead and behind, facing out; 2 m maximum range. The robot is always halfway
// between its sonars, so sonar positions and echoes decide every bound below. A zero aperture puts
// both cone edges on the axis; the "cone edges" row gives it a width.
sg::Dataset twoSonarDataset() {
  sg::Dataset d;
  d.ring.robot = "custom";
  d.ring.maxRange = 2.0;
  d.ring.apertureRad = 0.0;
  d.ring.sonars = {sg::SonarMount{sg::Pose2D(0.5, 0.0, 0.0)},
                   sg::SonarMount{sg::Pose2D(-0.5, 0.0, kPi)}};
  return d;
}

sg::Scan scanAt(const sg::Pose2D& odometry, double range0, double range1) {
  sg::Scan s;
  s.odometry = odometry;
  s.readings = {sg::Reading{0, range0, 0.0}, sg::Reading{1, range1, 0.0}};
  return s;
}

}  // namespace

void TstGeometry::fittingGrid_data() {
  QTest::addColumn<sg::Dataset>("dataset");
  QTest::addColumn<bool>("truth");
  QTest::addColumn<double>("margin");  // < 0: the default, 0.5 m
  QTest::addColumn<double>("ox");
  QTest::addColumn<double>("oy");
  QTest::addColumn<int>("width");
  QTest::addColumn<int>("height");

  // dataset.h: the box of every sonar position and every echo point, grown by the margin; without
  // a single echo, the sonar positions grown by max range + margin. 0.25 m cells throughout, then
  // GridSpec::covering (origin floor((lo - m) / 0.25) * 0.25, size ceil((hi + m - origin) / 0.25)).
  const double none = sg::Reading::kNoEcho;
  sg::Dataset d = twoSonarDataset();
  // Robot (1, 2, 0°): sonars at (1.5, 2) and (0.5, 2); sonar 0's echo at 1 m: (2.5, 2).
  // Robot (3, -1, 90°): sonars at (3, -0.5) facing +y and (3, -1.5) facing -y; echoes at 0.75 m
  // (3, 0.25) and 0.25 m (3, -1.75).
  d.scans = {scanAt(sg::Pose2D(1, 2, 0), 1.0, none),
             scanAt(sg::Pose2D(3, -1, kPi / 2), 0.75, 0.25)};
  // Box (0.5, -1.75) to (3, 2), margin 0.4: x floor(0.1 / 0.25 = 0.4) = 0 -> 0; y floor(-2.15 /
  // 0.25 = -8.6) = -9 -> -2.25; width ceil(3.4 / 0.25 = 13.6) = 14; height ceil((2.4 + 2.25) /
  // 0.25 = 18.6) = 19.
  QTest::addRow("echoes") << d << false << 0.4 << 0.0 << -2.25 << 14 << 19;

  d.scans = {scanAt(sg::Pose2D(1, 2, 0), none, none)};
  // No echo: sonars (0.5, 2) to (1.5, 2) grown by 2 + 0.4 = 2.4: x floor(-1.9 / 0.25 = -7.6) = -8
  // -> -2; y floor(-0.4 / 0.25 = -1.6) = -2 -> -0.5; width ceil((3.9 + 2) / 0.25 = 23.6) = 24;
  // height ceil((4.4 + 0.5) / 0.25 = 19.6) = 20.
  QTest::addRow("no echo") << d << false << 0.4 << -2.0 << -0.5 << 24 << 20;
  // A finite range at max range (possible in memory) is no echo either: the same grid.
  d.scans = {scanAt(sg::Pose2D(1, 2, 0), 2.0, none)};
  QTest::addRow("range at max range") << d << false << 0.4 << -2.0 << -0.5 << 24 << 20;

  // One echo at 1 m from (1, 2, 0°): box (0.5, 2) to (2.5, 2), default margin 0.5: x 0 / 0.25 = 0
  // -> 0; y 1.5 / 0.25 = 6 -> 1.5; width (3 - 0) / 0.25 = 12; height (2.5 - 1.5) / 0.25 = 4.
  d.scans = {scanAt(sg::Pose2D(1, 2, 0), 1.0, none)};
  QTest::addRow("default margin") << d << false << -1.0 << 0.0 << 1.5 << 12 << 4;
  {
    // A 90° cone: the echo's edge points are 1 m from sonar 0 at ±45°, (1.5 + 0.7071, 2 ± 0.7071).
    // Box (0.5, 1.2929) to (2.5, 2.7071), margin 0.4: x 0; y floor(0.8929 / 0.25 = 3.57) = 3 ->
    // 0.75; width ceil(2.9 / 0.25 = 11.6) = 12; height ceil((3.1071 - 0.75) / 0.25 = 9.43) = 10.
    sg::Dataset wide = d;
    wide.ring.apertureRad = kPi / 2;
    QTest::addRow("cone edges") << wide << false << 0.4 << 0.0 << 0.75 << 12 << 10;
  }
  // Margin 0.4: x floor(0.1 / 0.25) = 0; y floor(1.6 / 0.25 = 6.4) = 6 -> 1.5; width ceil(2.9 /
  // 0.25 = 11.6) = 12; height ceil((2.4 - 1.5) / 0.25 = 3.6) = 4.
  QTest::addRow("odometry") << d << false << 0.4 << 0.0 << 1.5 << 12 << 4;
  // The same scan with a true pose (5, 5, 0°): sonars (4.5, 5), (5.5, 5), echo (6.5, 5). Truth:
  // x floor(4.1 / 0.25 = 16.4) = 16 -> 4; y floor(4.6 / 0.25 = 18.4) = 18 -> 4.5; width
  // ceil((6.9 - 4) / 0.25 = 11.6) = 12; height ceil((5.4 - 4.5) / 0.25 = 3.6) = 4.
  d.scans[0].truth = sg::Pose2D(5, 5, 0);
  QTest::addRow("truth") << d << true << 0.4 << 4.0 << 4.5 << 12 << 4;
  QTest::addRow("odometry, truth present") << d << false << 0.4 << 0.0 << 1.5 << 12 << 4;

  // No scans: the point (0, 0) grown by the margin: floor(-0.4 / 0.25 = -1.6) = -2 -> -0.5,
  // ceil(0.9 / 0.25 = 3.6) = 4 cells.
  d.scans.clear();
  QTest::addRow("no scans") << d << false << 0.4 << -0.5 << -0.5 << 4 << 4;
}

void TstGeometry::fittingGridRefused_data() {
  QTest::addColumn<sg::Dataset>("dataset");
  QTest::addColumn<QString>("message");

  constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const double none = sg::Reading::kNoEcho;
  const QString limit = QStringLiteral(", more than the grid limit of 200000000 cells");
  sg::Dataset d = twoSonarDataset();
  // The two scans of the "echoes" row (box (0.5, -1.75) to (3, 2)), at t = 0 and 1 s, then a
  // third at t = 2 s whose pose is 1e12 m away: its sonars sit at x = 1e12 +- 0.5. The robot's
  // median position is (3, 0), so scan 2 is the one named, at its front sonar (1e12 + 0.5, 0).
  // 0.25 m cells, 0.5 m margin: origin x 0, y floor(-2.25 / 0.25) = -9 -> -2.25; columns
  // (1e12 + 1) / 0.25 = 4000000000004; rows (2.5 + 2.25) / 0.25 = 19.
  d.scans = {scanAt(sg::Pose2D(1, 2, 0), 1.0, none), scanAt(sg::Pose2D(3, -1, kPi / 2), 0.75, 0.25),
             scanAt(sg::Pose2D(1e12, 0, 0), none, none)};
  for (std::size_t i = 0; i < d.scans.size(); ++i) d.scans[i].time = double(i);
  QTest::addRow("a pose at x = 1e12")
      << d
      << "scan 2 (t = 2 s) reaches (1e+12, 0) m: x 0.5 to 1e+12 m, y -1.75 to 2 m grown by 0.5 m "
         "make a grid of 4000000000004 x 19 cells of 0.25 m" +
             limit;
  // The same pose at -1e12: its back sonar (-1e12 - 0.5, 0) is the farthest point. Origin x
  // floor((-1e12 - 1) / 0.25) = -4000000000004 cells -> -1000000000001; columns
  // (3.5 + 1000000000001) / 0.25 = 4000000000018.
  d.scans[2].odometry = sg::Pose2D(-1e12, 0, 0);
  QTest::addRow("a pose at x = -1e12")
      << d
      << "scan 2 (t = 2 s) reaches (-1e+12, 0) m: x -1e+12 to 3 m, y -1.75 to 2 m grown by 0.5 m "
         "make a grid of 4000000000018 x 19 cells of 0.25 m" +
             limit;
  // The far scan first: the median still names it (robots x 1e12, 1, 3 -> median 3).
  sg::Dataset first = d;
  first.scans = {scanAt(sg::Pose2D(1e12, 0, 0), none, none), d.scans[0], d.scans[1]};
  first.scans[0].time = 0.5;
  QTest::addRow("the first scan far")
      << first
      << "scan 0 (t = 0.5 s) reaches (1e+12, 0) m: x 0.5 to 1e+12 m, y -1.75 to 2 m grown by "
         "0.5 m make a grid of 4000000000004 x 19 cells of 0.25 m" +
             limit;
  // Not finite (possible in memory; the readers refuse it): the first point that is not, in scan
  // order, sonar 0 before the robot. Robot (NaN, -1) heading 90°: sonar 0 at (NaN, -0.5).
  d.scans[2].odometry = sg::Pose2D(3, -1, kPi / 2);
  d.scans[1].odometry = sg::Pose2D(kNan, -1, kPi / 2);
  QTest::addRow("NaN pose") << d
                            << "scan 1 (t = 1 s) has a position that is not finite: (nan, -0.5) m";
  d.scans[1].odometry = sg::Pose2D(3, -1, kPi / 2);
  d.scans[2].odometry = sg::Pose2D(kInf, 0, 0);
  QTest::addRow("infinite pose")
      << d << "scan 2 (t = 2 s) has a position that is not finite: (inf, 0) m";
  // No echo at all and a 1e9 m maximum range: the positions fit, the margin max_range + 0.5 does
  // not. Sonars (0.5, 2) and (1.5, 2); origin x floor((0.5 - 1e9 - 0.5) / 0.25) -> -1e9, y
  // floor((2 - 1e9 - 0.5) / 0.25) = -3999999994 -> -999999998.5; columns (1.5 + 1e9 + 0.5 + 1e9)
  // / 0.25 = 8000000008, rows (2 + 1e9 + 0.5 + 999999998.5) / 0.25 = 8000000004.
  sg::Dataset noEcho = twoSonarDataset();
  noEcho.ring.maxRange = 1e9;
  noEcho.scans = {scanAt(sg::Pose2D(1, 2, 0), none, none)};
  QTest::addRow("no echo, huge max_range")
      << noEcho
      << "no reading has an echo, so the grid reaches max_range 1e+09 m beyond every sonar: x 0.5 "
         "to 1.5 m, y 2 to 2 m grown by 1e+09 m make a grid of 8000000008 x 8000000004 cells of "
         "0.25 m" +
             limit;
}

void TstGeometry::fittingGridRefused() {
  QFETCH(sg::Dataset, dataset);
  QFETCH(QString, message);
  try {
    const sg::GridSpec g = dataset.fittingGrid(sg::PoseSource::Odometry, 0.25);
    QFAIL(qPrintable(QStringLiteral("made a grid of %1 x %2 cells").arg(g.width).arg(g.height)));
  } catch (const sg::GridLimitError& e) {
    QCOMPARE(QString::fromStdString(e.what()), message);
  }
}

void TstGeometry::gridLimitErrorInFile() {
  // The caller that knows the file puts it in front; the type stays, so the CLI still maps it to
  // exit status 2.
  const sg::GridLimitError e("the extent is not finite: x nan to 1 m, y 0 to 1 m");
  const sg::GridLimitError named = e.inFile("logs/run 1.sglog");
  QCOMPARE(std::string(named.what()),
           std::string("logs/run 1.sglog: the extent is not finite: x nan to 1 m, y 0 to 1 m"));
  QCOMPARE(named.file(), std::string("logs/run 1.sglog"));
  QCOMPARE(named.message(), e.message());
}

void TstGeometry::fittingGrid() {
  QFETCH(sg::Dataset, dataset);
  QFETCH(bool, truth);
  QFETCH(double, margin);
  QFETCH(double, ox);
  QFETCH(double, oy);
  QFETCH(int, width);
  QFETCH(int, height);
  const sg::PoseSource source = truth ? sg::PoseSource::Truth : sg::PoseSource::Odometry;
  const sg::GridSpec g =
      margin < 0.0 ? dataset.fittingGrid(source, 0.25) : dataset.fittingGrid(source, 0.25, margin);
  QCOMPARE(g.cellSize, 0.25);
  QVERIFY2(near(g.origin.x(), ox, 1e-12), describe(g.origin.x(), ox));
  QVERIFY2(near(g.origin.y(), oy, 1e-12), describe(g.origin.y(), oy));
  QCOMPARE(g.width, width);
  QCOMPARE(g.height, height);
}

// ---------------------------------------------------------------------------------------------
// ParameterSet

void TstGeometry::parameterSetGet() {
  sg::ParameterSet p = threeParameters();
  // Built from the specs: every declared parameter at its default.
  QCOMPARE(p.get("epsilon"), 0.2);
  QCOMPARE(p.get("n"), 3.0);
  QCOMPARE(p.get("k"), 0.0);
  QCOMPARE(p.values().size(), std::size_t{3});
  QVERIFY(p.has("n") && !p.has("m"));

  p.set("epsilon", 0.75);
  QCOMPARE(p.get("epsilon"), 0.75);
  // The bounds are inclusive.
  p.set("epsilon", 0.0);
  QCOMPARE(p.get("epsilon"), 0.0);
  p.set("epsilon", 1.0);
  QCOMPARE(p.get("epsilon"), 1.0);
  p.set("k", -5.0);
  QCOMPARE(p.get("k"), -5.0);
  p.set("n", 10.0);
  QCOMPARE(p.get("n"), 10.0);
  p.set("n", 0.0);
  QCOMPARE(p.get("n"), 0.0);

  // Equality compares values only.
  sg::ParameterSet q = threeParameters();
  QVERIFY(!(p == q));
  q.set("epsilon", 1.0);
  q.set("k", -5.0);
  q.set("n", 0.0);
  QVERIFY(p == q);

  QCOMPARE(parameterError([&] { p.get("m"); }), QByteArray("no parameter 'm'"));
}

void TstGeometry::parameterErrors_data() {
  QTest::addColumn<QString>("name");
  QTest::addColumn<double>("value");
  QTest::addColumn<QByteArray>("expected");

  // Messages of ParameterSet::set, written out from parameters.cpp for the three specs of
  // threeParameters(): epsilon [0, 1] m, n whole in [0, 10], k [-5, 5] (no unit).
  QTest::addRow("unknown name lists the names")
      << "eps" << 0.5
      << QByteArray("unknown parameter 'eps'; this model and rule take: epsilon n k");
  QTest::addRow("above max, with unit")
      << "epsilon" << 1.5 << QByteArray("parameter 'epsilon' = 1.5 is outside [0, 1] m");
  QTest::addRow("below min, no unit")
      << "k" << -6.0 << QByteArray("parameter 'k' = -6 is outside [-5, 5]");
  QTest::addRow("NaN") << "epsilon" << kNaN
                       << QByteArray("parameter 'epsilon' = nan is outside [0, 1] m");
  QTest::addRow("infinity") << "k" << kInf << QByteArray("parameter 'k' = inf is outside [-5, 5]");
  QTest::addRow("integer 0.5") << "n" << 0.5 << QByteArray("parameter 'n' takes a whole number");
  QTest::addRow("integer 2.25") << "n" << 2.25 << QByteArray("parameter 'n' takes a whole number");
  // The range is checked before wholeness.
  QTest::addRow("integer out of range")
      << "n" << 10.5 << QByteArray("parameter 'n' = 10.5 is outside [0, 10]");
}

void TstGeometry::parameterErrors() {
  QFETCH(QString, name);
  QFETCH(double, value);
  QFETCH(QByteArray, expected);
  sg::ParameterSet p = threeParameters();
  const std::map<std::string, double> before = p.values();
  QCOMPARE(parameterError([&] { p.set(name.toStdString(), value); }), expected);
  QVERIFY(p.values() == before);  // a refused value changes nothing
}

void TstGeometry::parameterAppend() {
  sg::ParameterSet model = threeParameters();
  model.set("k", 2.0);
  sg::ParameterSet rule({spec("alpha", "", 0.0, 1.0, 0.5), spec("beta", "deg", 0.0, 90.0, 10.0)});
  rule.set("beta", 45.0);

  // Declarations and current values both move over, after the existing ones.
  sg::ParameterSet both = model;
  both.append(rule);
  QCOMPARE(both.specs().size(), std::size_t{5});
  QCOMPARE(both.specs()[3].name, std::string("alpha"));
  QCOMPARE(both.get("k"), 2.0);
  QCOMPARE(both.get("alpha"), 0.5);
  QCOMPARE(both.get("beta"), 45.0);
  both.set("beta", 90.0);  // and the appended range is enforced
  QCOMPARE(parameterError([&] { both.set("beta", 91.0); }),
           QByteArray("parameter 'beta' = 91 is outside [0, 90] deg"));
  QCOMPARE(
      parameterError([&] { both.set("gamma", 1.0); }),
      QByteArray("unknown parameter 'gamma'; this model and rule take: epsilon n k alpha beta"));

  // A name declared twice is refused.
  sg::ParameterSet clash({spec("k", "", 0.0, 1.0, 0.0)});
  sg::ParameterSet target = threeParameters();
  QCOMPARE(parameterError([&] { target.append(clash); }),
           QByteArray("parameter 'k' is declared twice"));
  sg::ParameterSet self = threeParameters();
  QCOMPARE(parameterError([&] { self.append(threeParameters()); }),
           QByteArray("parameter 'epsilon' is declared twice"));

  // An empty set names no parameters.
  sg::ParameterSet none;
  QCOMPARE(parameterError([&] { none.set("x", 1.0); }),
           QByteArray("unknown parameter 'x'; this model and rule take: none"));
}

// ---------------------------------------------------------------------------------------------
// BeamTables

void TstGeometry::beamTableEntries_data() {
  QTest::addColumn<int>("qx");
  QTest::addColumn<int>("qy");
  QTest::addColumn<int>("dx");
  QTest::addColumn<int>("dy");
  QTest::addColumn<double>("distance");
  QTest::addColumn<double>("bearing");

  // 0.1 m cells, 4 x 4 sub-cells: sub-cell q's centre is at (q + 0.5) / 4 = 0.125, 0.375, 0.625,
  // 0.875 of the cell. Entry (dx, dy) goes from there to the centre of cell (dx, dy), which is at
  // dx + 0.5: e = ((dx + 0.5 - sx) * 0.1, (dy + 0.5 - sy) * 0.1).
  // q (0, 0), own cell: e = (0.0375, 0.0375): |e| = 0.0375 sqrt2 = 0.0530330086, bearing pi/4.
  QTest::addRow("own cell from the corner sub-cell") << 0 << 0 << 0 << 0 << 0.0530330086 << kPi / 4;
  // q (0, 0), cell (1, 0): e = (0.1375, 0.0375): sqrt(0.0203125) = 0.1425219282,
  // atan(0.0375 / 0.1375) = atan(3 / 11) = 0.2662520491.
  QTest::addRow("east neighbour") << 0 << 0 << 1 << 0 << 0.1425219282 << 0.2662520491;
  // q (3, 3), cell (-1, -1): e = (-0.1375, -0.1375): 0.1375 sqrt2 = 0.1944543648, bearing -3pi/4.
  QTest::addRow("south-west") << 3 << 3 << -1 << -1 << 0.1944543648 << -3 * kPi / 4;
  // q (1, 2), cell (2, -2): sx 0.375, sy 0.625: e = (0.2125, -0.2125): 0.3005203820, -pi/4.
  QTest::addRow("table corner") << 1 << 2 << 2 << -2 << 0.3005203820 << -kPi / 4;
  // q (0, 1), cell (-2, 0): sx 0.125, sy 0.375: e = (-0.1625, 0.0125): sqrt(0.0265625) =
  // 0.1629800601; bearing pi - atan(0.0125 / 0.1625) = pi - atan(1 / 13) = 3.0648207621.
  QTest::addRow("west, just above the axis") << 0 << 1 << -2 << 0 << 0.1629800601 << 3.0648207621;
  // q (2, 1), cell (0, 2): sx 0.625, sy 0.375: e = (-0.0125, 0.2125): sqrt(0.0453125) =
  // 0.2128673295; bearing pi/2 + atan(0.0125 / 0.2125) = pi/2 + atan(1 / 17) = 1.6295521495.
  QTest::addRow("north, just left of the axis") << 2 << 1 << 0 << 2 << 0.2128673295 << 1.6295521495;
}

void TstGeometry::beamTableEntries() {
  QFETCH(int, qx);
  QFETCH(int, qy);
  QFETCH(int, dx);
  QFETCH(int, dy);
  QFETCH(double, distance);
  QFETCH(double, bearing);
  const sg::BeamTables tables(0.1, 2);
  QCOMPARE(tables.cellSize(), 0.1);
  QCOMPARE(tables.radius(), 2);
  QCOMPARE(tables.side(), 5);
  QCOMPARE(tables.subdivisions(), sg::BeamTables::kDefaultSubdivisions);
  QCOMPARE(tables.subdivisions(), 4);

  const sg::BeamTables::Entry e = tables.entry(qx, qy, dx, dy);
  // Floats: 1e-7 is a few float ulps at these magnitudes; the hand values have 10 decimals.
  QVERIFY2(near(e.distance, distance, 1e-7), describe(e.distance, distance));
  QVERIFY2(near(e.bearing, bearing, 2e-7), describe(e.bearing, bearing));
  // And the same formula in double, rounded once to float, exactly.
  const double ex = (dx + 0.5 - (qx + 0.5) / 4) * 0.1;
  const double ey = (dy + 0.5 - (qy + 0.5) / 4) * 0.1;
  QCOMPARE(e.distance, static_cast<float>(std::hypot(ex, ey)));
  QCOMPARE(e.bearing, static_cast<float>(std::atan2(ey, ex)));
}

void TstGeometry::beamTablesShared() {
  // 0.0625 m cells (exact in binary) and 1 m: ceil(1 / 0.0625) + 2 = 16 + 2 = 18 cells, rounded up
  // to the next multiple of kRadiusStep = 32: 32.
  QCOMPARE(sg::BeamTables::kRadiusStep, 32);
  QCOMPARE(sg::BeamTables::radiusFor(0.0625, 1.0), 32);
  const std::shared_ptr<const sg::BeamTables> a = sg::BeamTables::shared(0.0625, 1.0);
  QVERIFY(a != nullptr);
  QCOMPARE(a->cellSize(), 0.0625);
  QCOMPARE(a->radius(), 32);
  // The same cell size and the same or a shorter reach: the same object.
  QCOMPARE(sg::BeamTables::shared(0.0625, 1.0), a);
  QCOMPARE(sg::BeamTables::shared(0.0625, 0.5), a);
  QCOMPARE(sg::BeamTables::shared(0.0625, 0.01), a);
  // A longer reach inside the same step, as a slider moving the reach gives: ceil(1.875 / 0.0625)
  // + 2 = 32 still fits, so no new table (the reason for the step).
  QCOMPARE(sg::BeamTables::radiusFor(0.0625, 1.875), 32);
  QCOMPARE(sg::BeamTables::shared(0.0625, 1.875), a);

  // Past the step a bigger table is built: ceil(1.9 / 0.0625) + 2 = 31 + 2 = 33 → 64 (5/4 of the
  // cached 32 is 40 → 64 too). It then serves its own reach again.
  QCOMPARE(sg::BeamTables::radiusFor(0.0625, 1.9), 64);
  const std::shared_ptr<const sg::BeamTables> b = sg::BeamTables::shared(0.0625, 1.9);
  QVERIFY(b != a);
  QCOMPARE(b->radius(), 64);
  QCOMPARE(sg::BeamTables::shared(0.0625, 1.9), b);

  // A bigger table replaces the smaller ones of its cell size in the cache: a shorter reach now
  // gets it too.
  QCOMPARE(sg::BeamTables::shared(0.0625, 0.5), b);

  // Another cell size never shares: 1 / 0.03125 = 32, + 2 = 34 → 64.
  const std::shared_ptr<const sg::BeamTables> c = sg::BeamTables::shared(0.03125, 1.0);
  QVERIFY(c != a && c != b);
  QCOMPARE(c->cellSize(), 0.03125);
  QCOMPARE(c->radius(), 64);
  QCOMPARE(sg::BeamTables::shared(0.03125, 1.0), c);

  // Outgrowing a table grows it by a quarter at least. 0.125 m cells (used by no other test):
  // 27.5 m needs ceil(220) + 2 = 222 → 224; 27.9 m needs ceil(223.2) + 2 = 226 → 256 by the step,
  // but 5/4 · 224 = 280 → 288 is built, which then serves up to (288 − 2) · 0.125 = 35.75 m.
  QCOMPARE(sg::BeamTables::shared(0.125, 27.5)->radius(), 224);
  QCOMPARE(sg::BeamTables::radiusFor(0.125, 27.9), 256);
  const std::shared_ptr<const sg::BeamTables> d = sg::BeamTables::shared(0.125, 27.9);
  QCOMPARE(d->radius(), 288);
  QCOMPARE(sg::BeamTables::shared(0.125, 35.75), d);
}

void TstGeometry::beamTablesFilledByEveryCore() {
  // Big enough (side 129² > 10 000 entries) that the constructor splits the 16 tables between
  // threads: every entry of every table must still be the formula's value, the same as a table
  // small enough to be filled by one thread gives for the cells both hold.
  const sg::BeamTables big(0.05, 64);
  const sg::BeamTables small(0.05, 10);
  QVERIFY(static_cast<long>(big.side()) * big.side() >= 10000);
  QVERIFY(static_cast<long>(small.side()) * small.side() < 10000);
  for (int qy = 0; qy < 4; ++qy)
    for (int qx = 0; qx < 4; ++qx)
      for (int dy = -10; dy <= 10; ++dy)
        for (int dx = -10; dx <= 10; ++dx) {
          const sg::BeamTables::Entry e = big.entry(qx, qy, dx, dy);
          const sg::BeamTables::Entry f = small.entry(qx, qy, dx, dy);
          QCOMPARE(e.distance, f.distance);
          QCOMPARE(e.bearing, f.bearing);
        }
  // And one far entry by hand: sub-cell (3, 0) centre at (0.875, 0.125) cells; cell (64, -64) has
  // its centre at (64.5, -63.5); offset (63.625, -63.625) cells, 45° below the x axis.
  const sg::BeamTables::Entry far = big.entry(3, 0, 64, -64);
  QVERIFY(std::abs(far.distance - 63.625 * 0.05 * std::sqrt(2.0)) < 1e-6);
  QVERIFY(std::abs(far.bearing + std::numbers::pi / 4) < 1e-6);
}

void TstGeometry::beamTablesMirrorIsExact() {
  // The upper sub-cells (qy = 2, 3 of 4) read the lower ones' tables upside down with the bearing
  // negated (BeamTables::View): every entry of every sub-cell must still be the formula's own value
  // for that sub-cell, bit for bit, or the cone pairs' maps would change. A 5 cm table as the
  // benchmark's 5 m sonar gets (radius 128: 257² entries, 16 sub-cells, about a million atan2).
  const sg::BeamTables tables(0.05, 128);
  const int r = tables.radius();
  for (int qy = 0; qy < 4; ++qy) {
    for (int qx = 0; qx < 4; ++qx) {
      const sg::BeamTables::View v = tables.view(qx, qy);
      QCOMPARE(v.mirrored, qy >= 2);
      QCOMPARE(v.rowStep, qy >= 2 ? -tables.side() : tables.side());
      int wrong = 0;
      for (int dy = -r; dy <= r; ++dy) {
        for (int dx = -r; dx <= r; ++dx) {
          const double ex = (dx + 0.5 - (qx + 0.5) / 4) * 0.05;
          const double ey = (dy + 0.5 - (qy + 0.5) / 4) * 0.05;
          const sg::BeamTables::Entry e = tables.entry(qx, qy, dx, dy);
          const float raw = v.row(dy)[dx].bearing;
          wrong += e.distance != static_cast<float>(std::hypot(ex, ey)) ||
                   e.bearing != static_cast<float>(std::atan2(ey, ex)) ||
                   raw != (v.mirrored ? -e.bearing : e.bearing);
        }
      }
      QVERIFY2(wrong == 0,
               qPrintable(QString("sub-cell (%1, %2): %3 entries differ from the formula")
                              .arg(qx)
                              .arg(qy)
                              .arg(wrong)));
    }
  }
  // Half the tables: 4 × 2 of 257² entries of 8 bytes, and the padding of 7 entries.
  QCOMPARE(tables.bytes(), std::size_t{(8 * 257 * 257 + 7) * 8});
  // Only a power of two keeps the sub-cell centres, and so the mirror, exact.
  QVERIFY_THROWS_EXCEPTION(std::invalid_argument, sg::BeamTables(0.05, 4, 3));
  QCOMPARE(sg::BeamTables(0.05, 4, 1).view(0, 0).mirrored, false);
}

// ---------------------------------------------------------------------------------------------
// The cone rasteriser

void TstGeometry::coneTiny_data() {
  QTest::addColumn<double>("sx");
  QTest::addColumn<double>("sy");
  QTest::addColumn<double>("headingDeg");
  QTest::addColumn<double>("reach");
  QTest::addColumn<double>("halfAngleDeg");
  QTest::addColumn<QList<int>>("cells");
  QTest::addColumn<double>("firstDelta");
  QTest::addColumn<double>("firstTheta");

  // A 10 x 10 grid of 0.05 m cells at (0, 0). The sensor (0.11875, 0.26875) is at 2.375, 5.375
  // cells: cell (2, 5), sub-cell (1, 1), whose centre 0.375, 0.375 is exactly the sensor. So cell
  // (2 + dx, 5 + dy) has its centre at (dx + 0.125, dy + 0.125) cells from the apex; reach 0.12 m
  // is 2.4 cells. Bearings below are atan(|y| / |x|) of those offsets.
  //
  // Heading 0, half-angle 10°. Row 5 (dy 0, y 0.125): dx 1 -> x 1.125, 6.34°, 1.1319 cells: in;
  // dx 2 -> 2.125, 3.37°, 2.1287: in; dx 3 -> 3.125 cells: too far; dx 0 -> 45°: out. Rows 4 and 6
  // (y -0.875, 1.125) are at >= 22.4° for every cell within reach. Cells 5 * 10 + 3, 5 * 10 + 4.
  // First cell (3, 5): delta 0.05 * sqrt(1.125² + 0.125²) = 0.05 * 1.1319231422 = 0.0565961571,
  // theta atan(0.125 / 1.125) = atan(1 / 9) = 0.1106572212.
  QTest::addRow("heading 0, 10 deg") << 0.11875 << 0.26875 << 0.0 << 0.12 << 10.0
                                     << QList<int>{53, 54} << 0.0565961571 << 0.1106572212;
  // Half-angle 25° adds (4, 4): (2.125, -0.875), 22.38°, sqrt(5.28125) = 2.2981 cells. Its
  // neighbours stay out: (3, 4) 37.9°, (4, 6) 27.9° (and 2.404 cells). Row 4 comes first: 44.
  // delta 0.05 * 2.2980970388 = 0.1149048519, theta -atan(0.875 / 2.125) = -0.3906070436.
  QTest::addRow("heading 0, 25 deg") << 0.11875 << 0.26875 << 0.0 << 0.12 << 25.0
                                     << QList<int>{44, 53, 54} << 0.1149048519 << -0.3906070436;
  // Reach 0.1 m = 2 cells drops (4, 5) at 2.1287 cells.
  QTest::addRow("reach 0.1") << 0.11875 << 0.26875 << 0.0 << 0.1 << 10.0 << QList<int>{53}
                             << 0.0565961571 << 0.1106572212;
  // Heading 90°: the mirror image in the diagonal (the apex is on it): cells (2, 6) and (2, 7),
  // 6 * 10 + 2 and 7 * 10 + 2; (2, 6) is at bearing 83.66°, theta -atan(1 / 9).
  QTest::addRow("heading 90, 10 deg") << 0.11875 << 0.26875 << 90.0 << 0.12 << 10.0
                                      << QList<int>{62, 72} << 0.0565961571 << -0.1106572212;
  // Heading 180°, half-angle 20°: dx -1 -> x -0.875 (8.13° off the axis, 0.8839 cells), dx -2 ->
  // -1.875 (3.81°, 1.8792 cells), both in row 5; (0, 4) is 25.02° off, (0, 6) 30.96°. Cells 50, 51.
  // First (0, 5): delta 0.05 * sqrt(3.53125) = 0.0939581024; bearing pi - atan(1 / 15), so theta =
  // -atan(1 / 15) = -0.0665681637.
  QTest::addRow("heading 180, 20 deg") << 0.11875 << 0.26875 << 180.0 << 0.12 << 20.0
                                       << QList<int>{50, 51} << 0.0939581024 << -0.0665681637;
  // The sensor one cell left of the grid, x -0.03125 = -0.625 cells: cell -1, sub-cell 1 (0.375),
  // the same offsets as the first row shifted by 3 columns: cells (0, 5) and (1, 5).
  QTest::addRow("sensor outside the grid") << -0.03125 << 0.26875 << 0.0 << 0.12 << 10.0
                                           << QList<int>{50, 51} << 0.0565961571 << 0.1106572212;
  // In the top-right cell (9.8, 9.8 cells: sub-cell 3, apex 0.875) looking out of the grid at 45°:
  // every cell of the grid is behind or beside the sensor (its own centre is at -135°).
  QTest::addRow("looking out of the grid")
      << 0.49 << 0.49 << 45.0 << 0.12 << 20.0 << QList<int>{} << 0.0 << 0.0;
}

void TstGeometry::coneTiny() {
  QFETCH(double, sx);
  QFETCH(double, sy);
  QFETCH(double, headingDeg);
  QFETCH(double, reach);
  QFETCH(double, halfAngleDeg);
  QFETCH(QList<int>, cells);
  QFETCH(double, firstDelta);
  QFETCH(double, firstTheta);

  sg::GridSpec grid;
  grid.origin = sg::Position(0.0, 0.0);
  grid.cellSize = 0.05;
  grid.width = 10;
  grid.height = 10;
  const sg::BeamTables tables(0.05, 5);  // ceil(0.12 / 0.05) + 2 = 5
  const sg::Pose2D sensor(sx, sy, deg(headingDeg));
  const Raster raster = rasterise(sensor, reach, deg(halfAngleDeg), grid, tables);
  QCOMPARE(raster.reserveCalls, 1);
  QVERIFY(raster.bound >= raster.visits.size());
  const std::vector<Visit>& got = raster.visits;
  // The overload without reserve() visits the same cells.
  std::vector<std::uint32_t> plain;
  sg::forEachConeCell(sensor, reach, deg(halfAngleDeg), grid, tables,
                      [&plain](std::uint32_t cell, double, double) { plain.push_back(cell); });
  QCOMPARE(plain.size(), got.size());
  QList<int> gotCells;
  for (const Visit& v : got) gotCells.push_back(static_cast<int>(v.cell));
  QCOMPARE(gotCells, cells);
  if (got.empty()) return;
  QVERIFY2(near(got.front().delta, firstDelta, 1e-8), describe(got.front().delta, firstDelta));
  QVERIFY2(near(got.front().theta, firstTheta, 2e-7), describe(got.front().theta, firstTheta));
}

void TstGeometry::coneMatchesBruteForce() {
  // A 120 x 90 grid of 5 cm cells away from the world origin, x in [-1.3, 4.7], y in [0.45, 4.95].
  sg::GridSpec grid;
  grid.origin = sg::Position(-1.3, 0.45);
  grid.cellSize = 0.05;
  grid.width = 120;
  grid.height = 90;
  const double x0 = grid.origin.x(), x1 = x0 + grid.widthMetres();
  const double y0 = grid.origin.y(), y1 = y0 + grid.heightMetres();
  // The tables the mapper would get for a 5 m reach: ceil(5 / 0.05) + 2 = 102 cells.
  const sg::BeamTables tables(0.05, 102);

  Random random(0x5eed'0ca7'2024'0601ULL);  // fixed: a failure must be reproducible
  constexpr int kBeams = 2000;
  std::size_t visitedTotal = 0;
  int emptyBeams = 0, outsideWithCells = 0;
  std::size_t maxSlack = 0;  // bound - cells, for information
  for (int beam = 0; beam < kBeams; ++beam) {
    // Positions: anywhere around the grid (1 m outside included), near an edge, near a corner, or
    // on the sub-cell lattice up to rounding (sub-cell boundaries are where the apex jumps).
    double x = 0.0, y = 0.0;
    const double near3 = 3 * grid.cellSize;
    switch (beam % 4) {
      case 0:
        x = random.uniform(x0 - 1.0, x1 + 1.0);
        y = random.uniform(y0 - 1.0, y1 + 1.0);
        break;
      case 1: {
        const int edge = random.below(4);
        x = edge == 0   ? x0 + random.uniform(-near3, near3)
            : edge == 1 ? x1 + random.uniform(-near3, near3)
                        : random.uniform(x0 - 0.5, x1 + 0.5);
        y = edge == 2   ? y0 + random.uniform(-near3, near3)
            : edge == 3 ? y1 + random.uniform(-near3, near3)
                        : random.uniform(y0 - 0.5, y1 + 0.5);
        break;
      }
      case 2:
        x = (random.below(2) == 0 ? x0 : x1) + random.uniform(-near3, near3);
        y = (random.below(2) == 0 ? y0 : y1) + random.uniform(-near3, near3);
        break;
      default:
        x = x0 + (random.below(4 * (grid.width + 20)) - 40) * (grid.cellSize / 4);
        y = y0 + (random.below(4 * (grid.height + 20)) - 40) * (grid.cellSize / 4);
        break;
    }
    // Headings in [-pi, pi), as Pose2D::compose produces them; one in eight is an axis direction
    // or puts a cone edge on an axis.
    const double halfAngle = deg(random.uniform(1.0, 45.0));
    double heading = random.uniform(-kPi, kPi);
    if (beam % 8 == 7) {
      const double axis = (random.below(4) - 2) * (kPi / 2);  // -pi, -pi/2, 0, pi/2
      const int kind = random.below(3);
      heading = sg::wrapAngle(kind == 0 ? axis : kind == 1 ? axis + halfAngle : axis - halfAngle);
    }
    const double reach = random.uniform(0.1, 5.0);
    const sg::Pose2D sensor(x, y, heading);

    const Raster raster = rasterise(sensor, reach, halfAngle, grid, tables);
    const std::vector<Visit>& got = raster.visits;
    const std::vector<Visit> want = bruteForceCone(sensor, reach, halfAngle, grid, tables);
    const QByteArray where =
        "beam " + QByteArray::number(beam) + ": " + beamText(sensor, reach, halfAngle);

    // reserve() once, before any cell, with a bound the cells stay within (coneFootprint writes
    // through a pointer into a buffer of exactly that size).
    QVERIFY2(raster.reserveCalls == 1 && raster.reservedFirst, where);
    QVERIFY2(raster.bound >= got.size(), where + " bound " + QByteArray::number(raster.bound) +
                                             " < " + QByteArray::number(got.size()) + " cells");
    maxSlack = std::max(maxSlack, raster.bound - got.size());
    // Row-major order, each cell once: strictly increasing linear indices.
    for (std::size_t i = 1; i < got.size(); ++i) {
      QVERIFY2(got[i - 1].cell < got[i].cell, where + " visits " + QByteArray::number(got[i].cell) +
                                                  " after " + QByteArray::number(got[i - 1].cell));
    }
    // The same cells, with the same delta and theta.
    std::size_t i = 0, j = 0;
    while (i < got.size() || j < want.size()) {
      if (j == want.size() || (i < got.size() && got[i].cell < want[j].cell)) {
        const sg::CellIndex c = grid.fromLinear(got[i].cell);
        QFAIL(where + " visits cell (" + QByteArray::number(c.x()) + ", " +
              QByteArray::number(c.y()) + ") that the brute force rejects");
      }
      if (i == got.size() || want[j].cell < got[i].cell) {
        const sg::CellIndex c = grid.fromLinear(want[j].cell);
        QFAIL(where + " misses cell (" + QByteArray::number(c.x()) + ", " +
              QByteArray::number(c.y()) + "): delta " + QByteArray::number(want[j].delta, 'g', 17) +
              ", theta " + QByteArray::number(want[j].theta, 'g', 17));
      }
      QVERIFY2(got[i].delta == want[j].delta && got[i].theta == want[j].theta, where);
      ++i;
      ++j;
    }
    visitedTotal += got.size();
    if (got.empty()) ++emptyBeams;
    const bool outside = x < x0 || x >= x1 || y < y0 || y >= y1;
    if (outside && !got.empty()) ++outsideWithCells;
  }
  // The draw did exercise the interesting cases.
  qInfo(
      "%d beams: %zu cells visited, %d beams with no cell, %d from outside the grid with cells, "
      "bound at most %zu above the count",
      kBeams, visitedTotal, emptyBeams, outsideWithCells, maxSlack);
  QVERIFY(visitedTotal > 100000);
  QVERIFY(emptyBeams > 10);
  QVERIFY(outsideWithCells > 100);
}

QTEST_GUILESS_MAIN(TstGeometry)
#include "tst_geometry.moc"
