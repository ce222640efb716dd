// SPDX-License-Identifier: BSD-3-Clause
// The ray-cast sonar against hand-computed geometry, its determinism and its noise statistics.

#include <QtTest>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "sonargrid/sim/ray_sonar.h"

using namespace sg;

namespace {

// A ring whose only sonar sits at the robot centre facing forward: the tests place the sensor
// directly with a world pose. Aperture 25 degrees, range window [0.15, 5) m.
SonarRing oneSonar() {
  SonarRing ring;
  ring.sonars = {SonarMount{Pose2D(0, 0, 0)}};
  return ring;
}

SonarPhysics exact() {
  SonarPhysics p;
  p.rangeNoiseSd = 0.0;
  p.rangeDecimals = -1;  // hand-computed values are not whole millimetres
  return p;
}

std::vector<Segment> wallAtX(double x) {
  return {Segment{Position(x, -5.0), Position(x, 5.0)}};
}

// An axis-aligned square of side `side` centred on `c`.
std::vector<Segment> square(const Position& c, double side) {
  const double h = 0.5 * side;
  const std::vector<Position> corners{c + Position(-h, -h), c + Position(h, -h), c + Position(h, h),
                                      c + Position(-h, h)};
  return polygonSegments(corners, true);
}

}  // namespace

class TstRaySonar : public QObject {
  Q_OBJECT

 private slots:
  void polygonSegmentsClosesOnlyWhenAsked() {
    const std::vector<Position> corners{{0, 0}, {1, 0}, {1, 1}};
    QCOMPARE(polygonSegments(corners, false).size(), std::size_t(2));
    const std::vector<Segment> closed = polygonSegments(corners, true);
    QCOMPARE(closed.size(), std::size_t(3));
    QCOMPARE(closed.back().a, Position(1, 1));
    QCOMPARE(closed.back().b, Position(0, 0));
  }

  void raysSpanTheAperture() {
    // 9 rays over 25 degrees: from edge to edge, 3.125 degrees apart, one on the axis.
    const SonarPhysics p;
    const double aperture = degToRad(25.0);
    for (int i = 0; i < 9; ++i) {
      QVERIFY(std::abs(rayBearing(i, aperture, p) - degToRad(-12.5 + 3.125 * i)) < 1e-15);
    }
    SonarPhysics single;
    single.raysPerCone = 1;
    QCOMPARE(rayBearing(0, aperture, single), 0.0);
  }

  void wallAheadGivesExactRange() {
    SimRng rng(1);
    SonarPhysics p = exact();
    QCOMPARE(fireSonar(wallAtX(2.0), Pose2D(0, 0, 0), oneSonar(), p, rng), 2.0);
    // The default 1 mm resolution keeps a whole-millimetre range exact too.
    p.rangeDecimals = 3;
    QCOMPARE(fireSonar(wallAtX(2.0), Pose2D(0, 0, 0), oneSonar(), p, rng), 2.0);
  }

  void nothingInRangeGivesNoEcho() {
    SimRng rng(1);
    // Facing +y, the cone's outermost ray (77.5 degrees) reaches x = 2 only at 9.2 m.
    QCOMPARE(fireSonar(wallAtX(2.0), Pose2D(0, 0, degToRad(90.0)), oneSonar(), exact(), rng),
             Reading::kNoEcho);
    QCOMPARE(fireSonar({}, Pose2D(0, 0, 0), oneSonar(), exact(), rng), Reading::kNoEcho);
  }

  void rangeWindow() {
    SimRng rng(1);
    const SonarRing ring = oneSonar();
    // Beyond maxRange (5 m) every ray's hit is discarded.
    QCOMPARE(fireSonar(wallAtX(5.5), Pose2D(0, 0, 0), ring, exact(), rng), Reading::kNoEcho);
    // Exactly at maxRange counts as no echo (the ring's convention).
    QCOMPARE(fireSonar(wallAtX(5.0), Pose2D(0, 0, 0), ring, exact(), rng), Reading::kNoEcho);
    // Closer than minRange reads as minRange.
    QCOMPARE(fireSonar(wallAtX(0.1), Pose2D(0, 0, 0), ring, exact(), rng), ring.minRange);
  }

  void obliqueWallAndMaxIncidence() {
    // The wall x + y = 2 meets the axis at 45 degrees incidence; ray j at bearing b has incidence
    // |45 - b| degrees, from 32.5 (b = +12.5) to 57.5 (b = -12.5).
    const std::vector<Segment> wall{Segment{Position(-3, 5), Position(5, -3)}};
    SimRng rng(1);
    SonarPhysics p = exact();
    p.maxIncidenceDeg = 30.0;  // every ray glances off
    QCOMPARE(fireSonar(wall, Pose2D(0, 0, 0), oneSonar(), p, rng), Reading::kNoEcho);
    p.maxIncidenceDeg = 60.0;  // every ray returns; the shortest is the +12.5 degree edge ray:
    // t (cos b + sin b) = 2  =>  t = 2 / (cos 12.5 + sin 12.5) = 1.676818...
    const double b = degToRad(12.5);
    const double expected = 2.0 / (std::cos(b) + std::sin(b));
    const double got = fireSonar(wall, Pose2D(0, 0, 0), oneSonar(), p, rng);
    QVERIFY2(std::abs(got - expected) < 1e-12, qPrintable(QString::number(got, 'g', 17)));
    QVERIFY(std::abs(expected - 1.6768175) < 1e-6);
  }

  void specularRayDoesNotSeeBeyond() {
    // A ray that glances off its nearest surface is lost, even with a good wall behind it. With a
    // single ray: an oblique mirror at 1 m in front of a square wall at 3 m.
    SonarPhysics p = exact();
    p.raysPerCone = 1;
    std::vector<Segment> world = wallAtX(3.0);
    world.push_back(Segment{Position(0, -1), Position(2, 1)});  // 45 degrees, crosses the axis at 1
    SimRng rng(1);
    p.maxIncidenceDeg = 30.0;
    QCOMPARE(fireSonar(world, Pose2D(0, 0, 0), oneSonar(), p, rng), Reading::kNoEcho);
    p.maxIncidenceDeg = 60.0;
    QVERIFY(std::abs(fireSonar(world, Pose2D(0, 0, 0), oneSonar(), p, rng) - 1.0) < 1e-12);
  }

  void offAxisPoleGivesItsNearFace() {
    // A 4 cm pole whose near face (x = 1.5) is crossed by ray 6 at bearing +6.25 degrees, in
    // front of a wall at x = 4. Neighbouring rays (3.125 and 9.375 degrees) pass 6 cm beside it, so
    // the reading is ray 6's distance to the near face: 1.5 / cos(6.25 degrees) = 1.508969...
    const double bearing = degToRad(6.25);
    const double face = 1.5;
    const Position centre(face + 0.02, face * std::tan(bearing));
    std::vector<Segment> world = square(centre, 0.04);
    world.push_back(wallAtX(4.0).front());
    SimRng rng(1);
    const double got = fireSonar(world, Pose2D(0, 0, 0), oneSonar(), exact(), rng);
    QVERIFY2(std::abs(got - face / std::cos(bearing)) < 1e-12,
             qPrintable(QString::number(got, 'g', 17)));
    QVERIFY(std::abs(got - 1.508969) < 1e-6);
    // Without the pole the same sonar hears the wall on its axis.
    const std::vector<Segment> wallOnly = wallAtX(4.0);
    QCOMPARE(fireSonar(wallOnly, Pose2D(0, 0, 0), oneSonar(), exact(), rng), 4.0);
  }

  void sensorPoseIsHonoured() {
    // A sensor at (1, 1) facing -x sees the wall x = -1 at 2 m.
    SimRng rng(1);
    QCOMPARE(fireSonar(wallAtX(-1.0), Pose2D(1, 1, std::numbers::pi), oneSonar(), exact(), rng),
             2.0);
  }

  void sameSeedSameRanges() {
    const SonarPhysics p;  // default noise 1 cm, 1 mm resolution
    auto fire = [&](std::uint64_t seed) {
      SimRng rng(seed);
      std::vector<double> ranges;
      for (int i = 0; i < 200; ++i) {
        ranges.push_back(fireSonar(wallAtX(2.0), Pose2D(0, 0, 0), oneSonar(), p, rng));
      }
      return ranges;
    };
    const std::vector<double> a = fire(7);
    QCOMPARE(fire(7), a);
    QVERIFY(fire(8) != a);
    // The noise does move the readings, by whole millimetres.
    bool moved = false;
    for (double r : a) {
      moved = moved || r != 2.0;
      QCOMPARE(std::round(r * 1000.0) / 1000.0, r);
    }
    QVERIFY(moved);
  }

  void uniformIsInUnitInterval() {
    SimRng rng(3);
    double lo = 1.0, hi = 0.0;
    for (int i = 0; i < 10000; ++i) {
      const double u = uniform01(rng);
      lo = std::min(lo, u);
      hi = std::max(hi, u);
    }
    QVERIFY(lo >= 0.0 && lo < 0.01);
    QVERIFY(hi < 1.0 && hi > 0.99);
  }

  void noiseStatistics() {
    // n = 20000 readings of a wall at 2 m with sigma = 1 cm, full precision. Standard errors:
    // mean sigma/sqrt(n) = 7.1e-5 m, sample sd about sigma/sqrt(2n) = 5.0e-5 m. The tolerance is
    // 5 standard errors: a correct generator misses it with probability below 1e-6 whatever the
    // seed, while a wrong scale (variance for sd, a factor sqrt(2)) or a biased mean is 10+ away.
    const int n = 20000;
    SonarPhysics p;
    p.rangeDecimals = -1;
    const double sigma = p.rangeNoiseSd;
    SimRng rng(11);
    double sum = 0.0, sumSq = 0.0;
    for (int i = 0; i < n; ++i) {
      const double e = fireSonar(wallAtX(2.0), Pose2D(0, 0, 0), oneSonar(), p, rng) - 2.0;
      sum += e;
      sumSq += e * e;
    }
    const double mean = sum / n;
    const double sd = std::sqrt((sumSq - n * mean * mean) / (n - 1));
    const double meanTol = 5.0 * sigma / std::sqrt(double(n));
    const double sdTol = 5.0 * sigma / std::sqrt(2.0 * n);
    QVERIFY2(std::abs(mean) < meanTol, qPrintable(QString("mean %1").arg(mean)));
    QVERIFY2(std::abs(sd - sigma) < sdTol, qPrintable(QString("sd %1").arg(sd)));
  }

  void misreadingsArePhantomEchoes() {
    // With rate 1 every reading is uniform over [minRange, maxRange), even facing nothing.
    SonarPhysics p = exact();
    p.misreadRate = 1.0;
    const SonarRing ring = oneSonar();
    SimRng rng(5);
    double lo = ring.maxRange, hi = 0.0;
    for (int i = 0; i < 2000; ++i) {
      const double r = fireSonar({}, Pose2D(0, 0, 0), ring, p, rng);
      QVERIFY(r >= ring.minRange && r < ring.maxRange);
      lo = std::min(lo, r);
      hi = std::max(hi, r);
    }
    QVERIFY(lo < 0.3 && hi > 4.8);
  }

  void routeFiresEverySonarAtEveryPose() {
    const SonarRing ring = SonarRing::pioneer3dx();
    const std::vector<Position> corners{{-3, -3}, {3, -3}, {3, 3}, {-3, 3}};
    const std::vector<Segment> room = polygonSegments(corners, true);
    const std::vector<TimedPose> route{{0.0, Pose2D(0, 0, 0)}, {0.1, Pose2D(0.5, 0, 0.2)}};
    SonarPhysics p;
    p.seed = 42;
    const Dataset d = simulateRoute(room, route, ring, p, "square");
    QCOMPARE(d.name, std::string("square"));
    QCOMPARE(d.ring, ring);
    QCOMPARE(d.scans.size(), std::size_t(2));
    QVERIFY(d.hasTruth());
    for (std::size_t k = 0; k < d.scans.size(); ++k) {
      const Scan& s = d.scans[k];
      QCOMPARE(s.time, route[k].time);
      QCOMPARE(s.odometry, route[k].pose);
      QCOMPARE(*s.truth, route[k].pose);
      QCOMPARE(s.readings.size(), ring.size());
      for (std::size_t i = 0; i < ring.size(); ++i) {
        QCOMPARE(s.readings[i].sonar, std::uint16_t(i));
        QVERIFY(std::abs(s.readings[i].time - (s.time + 0.0025 * double(i))) < 1e-9);
        // Every sonar faces a wall within 5 m of the middle of a 6 m square.
        QVERIFY(s.readings[i].echo());
      }
    }
    // Sonar 4 at (0.166, -0.027) facing -10 degrees: its ray closest to the wall normal is the one
    // at -0.625 degrees (ray 7), which reaches x = 3 at 2.834 / cos(0.625 degrees); noise 1 cm.
    const double front = d.scans[0].readings[4].range;
    QVERIFY2(std::abs(front - (3.0 - 0.166) / std::cos(degToRad(0.625))) < 0.05,
             qPrintable(QString::number(front)));
    // The seed alone decides the readings.
    QCOMPARE(simulateRoute(room, route, ring, p, "square"), d);
  }
};

QTEST_GUILESS_MAIN(TstRaySonar)
#include "tst_ray_sonar.moc"
