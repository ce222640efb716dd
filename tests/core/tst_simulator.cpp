// SPDX-License-Identifier: BSD-3-Clause
// The full simulator (docs/simulator.md) against hand-computed geometry: surfaces and their
// specular limits, multipath, crosstalk, round poles, the range window, differential-drive
// kinematics, odometry drift statistics with a fixed seed, routes and stop spacing, and the world
// properties of the reference JSON.

#include <QtTest>
#include <cmath>
#include <numbers>
#include <vector>

#include "sonargrid/reference/reference_json.h"
#include "sonargrid/sim/differential_drive.h"
#include "sonargrid/sim/route.h"
#include "sonargrid/sim/simulation.h"

using namespace sg;

namespace {

// One sonar at the robot centre facing forward; 25-degree cone, 9 rays 3.125 degrees apart.
SonarRing oneSonar(double maxRange = 10.0) {
  SonarRing ring;
  ring.sonars = {SonarMount{Pose2D(0, 0, 0)}};
  ring.maxRange = maxRange;
  return ring;
}

SonarPhysics exact() {
  SonarPhysics p;
  p.rangeNoiseSd = 0.0;
  p.rangeDecimals = -1;
  p.maxIncidenceDeg = 20.0;
  return p;
}

Segment wall(Position a, Position b, double limit) {
  return Segment{a, b, limit};
}

double sampleSd(const std::vector<double>& v, double& mean) {
  mean = 0.0;
  for (double x : v) mean += x;
  mean /= static_cast<double>(v.size());
  double ss = 0.0;
  for (double x : v) ss += (x - mean) * (x - mean);
  return std::sqrt(ss / static_cast<double>(v.size() - 1));
}

}  // namespace

class TstSimulator : public QObject {
  Q_OBJECT

 private slots:
  void wallAtKnownDistance_data() {
    QTest::addColumn<double>("distance");
    QTest::addColumn<double>("expected");
    // A diffuse wall across the axis: the axis ray meets it head on at `distance`.
    QTest::newRow("2 m") << 2.0 << 2.0;
    QTest::newRow("9.99 m, inside the 10 m window") << 9.99 << 9.99;
    // The range window (Polaroid 6500: 0.15 m to about 10 m): closer reads as the minimum,
    // at the maximum or beyond is no echo.
    QTest::newRow("0.1 m reads 0.15 m") << 0.1 << 0.15;
    QTest::newRow("10 m is no echo") << 10.0 << Reading::kNoEcho;
  }
  void wallAtKnownDistance() {
    QFETCH(double, distance);
    QFETCH(double, expected);
    const SonarWorld world(
        {wall(Position(distance, -20), Position(distance, 20), kDiffuseIncidenceLimit)});
    SimRng rng(1);
    QCOMPARE(fireSonar(world, Pose2D(0, 0, 0), oneSonar(), exact(), rng), expected);
  }

  // A mirror through (2, 0) at 45 degrees: every ray of the cone meets it 32.5 to 57.5 degrees
  // from its normal, beyond the 20-degree limit. A diffuse wall at y = 3 faces the reflected axis
  // ray, which travels 2 m to the mirror and 3 m up to the wall: a 5 m multipath reading, the
  // shortest of the fan (the rays at +-3.125 degrees fold to 5.0075 m).
  void incidenceBeyondTheLimit_data() {
    QTest::addColumn<int>("mode");
    QTest::addColumn<double>("maxRange");
    QTest::addColumn<double>("expected");
    QTest::newRow("no echo") << int(SpecularEcho::None) << 10.0 << Reading::kNoEcho;
    QTest::newRow("multipath 5 m") << int(SpecularEcho::Multipath) << 10.0 << 5.0;
    QTest::newRow("multipath beyond max range")
        << int(SpecularEcho::Multipath) << 5.0 << Reading::kNoEcho;
  }
  void incidenceBeyondTheLimit() {
    QFETCH(int, mode);
    QFETCH(double, maxRange);
    QFETCH(double, expected);
    const SonarWorld world({wall(Position(0, -2), Position(4.9, 2.9), kPhysicsIncidenceLimit),
                            wall(Position(-1, 3), Position(8, 3), kDiffuseIncidenceLimit)});
    SonarPhysics p = exact();
    p.specularEcho = static_cast<SpecularEcho>(mode);
    SimRng rng(1);
    const double got = fireSonar(world, Pose2D(0, 0, 0), oneSonar(maxRange), p, rng);
    if (std::isinf(expected)) {
      QCOMPARE(got, expected);
    } else {
      QVERIFY2(std::abs(got - expected) < 1e-9, qPrintable(QString::number(got, 'g', 17)));
    }
  }

  // The surface's own limit wins over the physics default: the same 45-degree wall, silent when
  // specular, echoes when diffuse, from the edge ray at -12.5 degrees, the one nearest the wall's
  // normal (ray at bearing b meets y = x - 2 after 2 / (cos b - sin b) m).
  void surfaceLimitOverridesTheDefault() {
    SonarPhysics p = exact();
    SimRng rng(1);
    const SonarWorld specular({wall(Position(0, -2), Position(4.9, 2.9), 20.0)});
    QCOMPARE(fireSonar(specular, Pose2D(0, 0, 0), oneSonar(), p, rng), Reading::kNoEcho);
    const SonarWorld diffuse({wall(Position(0, -2), Position(4.9, 2.9), kDiffuseIncidenceLimit)});
    const double b = degToRad(-12.5);
    const double expected = 2.0 / (std::cos(b) - std::sin(b));
    const double got = fireSonar(diffuse, Pose2D(0, 0, 0), oneSonar(), p, rng);
    QVERIFY2(std::abs(got - expected) < 1e-9, qPrintable(QString::number(got, 'g', 17)));
  }

  // Sonar 0 at (0, 0) faces a wall at x = 2 with a 10-degree specular limit: its axis ray echoes
  // from (2, 0) at 2 m. Sonar 1 at (0, 1) points straight at (2, 0), 26.57 degrees off the wall's
  // normal: all its rays (14.1 to 39.1 degrees) glance off, so alone it hears nothing. Hearing its
  // neighbour's ping, it reads half of 2 m out plus sqrt(5) m back: (2 + sqrt 5) / 2 = 2.1180 m.
  void crosstalk_data() {
    QTest::addColumn<double>("rate");
    QTest::addColumn<double>("sonar1");
    QTest::newRow("off") << 0.0 << Reading::kNoEcho;
    QTest::newRow("always") << 1.0 << (2.0 + std::sqrt(5.0)) / 2.0;
  }
  void crosstalk() {
    QFETCH(double, rate);
    QFETCH(double, sonar1);
    SonarRing ring;
    ring.sonars = {SonarMount{Pose2D(0, 0, 0)}, SonarMount{Pose2D(0, 1, std::atan2(-1.0, 2.0))}};
    ring.maxRange = 10.0;
    const SonarWorld world({wall(Position(2, -20), Position(2, 20), 10.0)});
    SonarPhysics p = exact();
    p.crosstalkRate = rate;
    const std::vector<Pose2D> sensors{ring.sonars[0].pose, ring.sonars[1].pose};
    SimRng rng(7);
    const std::vector<double> r = fireRing(world, sensors, ring, p, rng);
    QCOMPARE(r.size(), std::size_t(2));
    QCOMPARE(r[0], 2.0);  // sonar 1 has no echo to lend it
    if (std::isinf(sonar1)) {
      QCOMPARE(r[1], sonar1);
    } else {
      QVERIFY2(std::abs(r[1] - sonar1) < 1e-9, qPrintable(QString::number(r[1], 'g', 17)));
    }
  }

  // A 3/4-inch pole (radius 9.5 mm, paper 000 §4.1) 3 m ahead and 5 cm to the side falls between
  // two rays (0 and 3.125 degrees pass 5 cm and 11 cm from its centre). As a circle it still
  // answers from its nearest point: sqrt(3^2 + 0.05^2) - 0.0095 m. As a square of the same size
  // it is missed.
  void thinPoleBetweenRays() {
    SonarPhysics p = exact();
    SimRng rng(1);
    const SonarWorld pole({}, {Circle{Position(3.0, 0.05), 0.0095, kDiffuseIncidenceLimit}});
    const double got = fireSonar(pole, Pose2D(0, 0, 0), oneSonar(), p, rng);
    QVERIFY2(std::abs(got - (std::sqrt(9.0025) - 0.0095)) < 1e-12,
             qPrintable(QString::number(got, 'g', 17)));
    const std::vector<Position> square{
        {2.9905, 0.0405}, {3.0095, 0.0405}, {3.0095, 0.0595}, {2.9905, 0.0595}};
    const SonarWorld box(polygonSegments(square, true));
    QCOMPARE(fireSonar(box, Pose2D(0, 0, 0), oneSonar(), p, rng), Reading::kNoEcho);
    // A ray that does hit the circle head on reports the same distance as the analytic echo.
    const std::optional<RayHit> hit =
        castRay(SonarWorld({}, {Circle{Position(2, 0), 0.5}}), Position(0, 0), Position(1, 0));
    QVERIFY(hit);
    QCOMPARE(hit->distance, 1.5);
    QCOMPARE(hit->cosIncidence, 1.0);
  }

  // v = 0.5 m/s, w = 0.25 rad/s for 2 s: an arc of radius 2 m through 0.5 rad, ending at
  // (2 sin 0.5, 2 (1 - cos 0.5)) = (0.958851, 0.244835).
  void differentialDriveArc() {
    const Pose2D p = integrateUnicycle(Pose2D(0, 0, 0), 0.5, 0.25, 2.0);
    QVERIFY(std::abs(p.x() - 2.0 * std::sin(0.5)) < 1e-12);
    QVERIFY(std::abs(p.y() - 2.0 * (1.0 - std::cos(0.5))) < 1e-12);
    QVERIFY(std::abs(p.heading - 0.5) < 1e-12);
    QVERIFY(std::abs(0.958851 - p.x()) < 1e-6 && std::abs(0.244835 - p.y()) < 1e-6);
    // The same arc as a path piece, driven at 0.5 m/s: half way in time is half the angle.
    DriveLimits limits;
    limits.speed = 0.5;
    limits.turnRate = 1.0;  // above v * curvature = 0.25, so the arc is not slowed
    const Trajectory t(Pose2D(0, 0, 0), {PathPiece{1.0, 0.5, 0.0}}, limits);
    QCOMPARE(t.duration(), 2.0);
    const Pose2D half = t.poseAt(1.0);
    QVERIFY(std::abs(half.x() - 2.0 * std::sin(0.25)) < 1e-12);
    QVERIFY(std::abs(half.heading - 0.25) < 1e-12);
    // Turn rate caps a tight arc: radius 0.2 m at 45 deg/s allows 0.157 m/s, not 0.3.
    const Trajectory tight(Pose2D(0, 0, 0), {PathPiece{0.2, 5.0, 0.0}}, DriveLimits{});
    QVERIFY(std::abs(tight.duration() - 0.2 / (0.2 * degToRad(45.0))) < 1e-12);
    // A quarter turn on the spot at 45 deg/s takes 2 s.
    const Trajectory spot(Pose2D(0, 0, 0), {PathPiece{0.0, 0.0, std::numbers::pi / 2}},
                          DriveLimits{});
    QVERIFY(std::abs(spot.duration() - 2.0) < 1e-12);
  }

  // Systematic errors (UMBmark): wheels reading 1 % short (left) and 1 % long (right) over a
  // 1 m straight with a 0.4 m wheelbase turn the odometry by (1.01 - 0.99) / 0.4 = 0.05 rad, on an
  // arc of radius 1 / 0.05 = 20 m: it ends at (20 sin 0.05, 20 (1 - cos 0.05)). A wheelbase taken
  // 1 % too long makes a full turn on the spot read 2 pi / 1.01.
  void systematicDrift() {
    OdometryErrors e;
    e.leftScale = -0.01;
    e.rightScale = 0.01;
    Odometry odo(Pose2D(0, 0, 0), 0.4, e, 1);
    for (int k = 0; k < 100; ++k) odo.step(Pose2D(0.01 * k, 0, 0), Pose2D(0.01 * (k + 1), 0, 0));
    QVERIFY2(std::abs(odo.pose().heading - 0.05) < 1e-12,
             qPrintable(QString::number(odo.pose().heading, 'g', 17)));
    QVERIFY(std::abs(odo.pose().x() - 20.0 * std::sin(0.05)) < 1e-12);
    QVERIFY(std::abs(odo.pose().y() - 20.0 * (1.0 - std::cos(0.05))) < 1e-12);

    OdometryErrors base;
    base.wheelbaseScale = 0.01;
    Odometry turn(Pose2D(0, 0, 0), 0.4, base, 1);
    for (int k = 0; k < 360; ++k)
      turn.step(Pose2D(0, 0, wrapAngle(degToRad(k))), Pose2D(0, 0, wrapAngle(degToRad(k + 1))));
    QVERIFY(std::abs(turn.pose().heading - wrapAngle(2.0 * std::numbers::pi / 1.01)) < 1e-9);
  }

  // Random wheel noise sigma per sqrt(metre): over D metres straight, the distance error is the
  // mean of the two wheels' errors, sd sigma sqrt(D / 2); the heading error their difference over
  // the wheelbase, sd sigma sqrt(2 D) / b. sigma = 0.01, D = 5, b = 0.4: 0.0158 m and 0.0791 rad.
  // 400 runs from seeds 1..400 (fixed): the sample sd is within 10 % of the truth with
  // probability > 0.95 for 400 samples, and these seeds are fixed, so the test is deterministic.
  void randomDriftStatistics() {
    OdometryErrors e;
    e.wheelNoise = 0.01;
    std::vector<double> along, heading;
    for (std::uint64_t seed = 1; seed <= 400; ++seed) {
      Odometry odo(Pose2D(0, 0, 0), 0.4, e, seed);
      for (int k = 0; k < 100; ++k) odo.step(Pose2D(0.05 * k, 0, 0), Pose2D(0.05 * (k + 1), 0, 0));
      // Distance driven by the odometry, as the straight-line position is bent by heading error.
      along.push_back(odo.pose().position.norm() - 5.0);
      heading.push_back(odo.pose().heading);
    }
    double meanAlong = 0.0, meanHeading = 0.0;
    const double sdAlong = sampleSd(along, meanAlong);
    const double sdHeading = sampleSd(heading, meanHeading);
    const double expectAlong = 0.01 * std::sqrt(2.5);
    const double expectHeading = 0.01 * std::sqrt(10.0) / 0.4;
    QVERIFY2(std::abs(sdAlong / expectAlong - 1.0) < 0.1, qPrintable(QString::number(sdAlong)));
    QVERIFY2(std::abs(sdHeading / expectHeading - 1.0) < 0.1,
             qPrintable(QString::number(sdHeading)));
    // Zero mean: within three standard errors.
    QVERIFY(std::abs(meanHeading) < 3.0 * expectHeading / 20.0);
  }

  // A corner rounded with a 0.5 m arc: legs of 2 m lose r tan(45 deg) = 0.5 m each, and the arc is
  // a quarter circle, 0.25 pi m long with curvature 2 /m.
  void roundedCorner() {
    const std::vector<Position> w{{2, 0}, {2, 2}};
    const std::vector<PathPiece> p = waypointPath(Pose2D(0, 0, 0), w, 0.5);
    QCOMPARE(p.size(), std::size_t(3));
    QVERIFY(std::abs(p[0].length - 1.5) < 1e-12 && p[0].curvature == 0.0);
    QVERIFY(std::abs(p[1].length - 0.25 * std::numbers::pi) < 1e-12);
    QVERIFY(std::abs(p[1].curvature - 2.0) < 1e-12);
    QVERIFY(std::abs(p[2].length - 1.5) < 1e-12);
    const Trajectory t(Pose2D(0, 0, 0), p, DriveLimits{});
    QVERIFY((t.end().position - Position(2, 2)).norm() < 1e-12);
    QVERIFY(std::abs(t.end().heading - std::numbers::pi / 2) < 1e-12);
  }

  // U-turn sweep over [0, 4] x [0, 1.6] with lanes 0.8 m apart: three lanes along x joined by
  // semicircles of radius 0.4 m (two quarter arcs, nothing straight between them).
  void uTurnSweep() {
    const std::vector<Position> w = sweepWaypoints(Position(0, 0), Position(4, 1.6), 0.8);
    QCOMPARE(w.size(), std::size_t(6));
    QCOMPARE(w[2], Position(4, 0.8));
    QCOMPARE(w[3], Position(0, 0.8));
    const std::vector<PathPiece> p = waypointPath(Pose2D(0, 0, 0), w, 0.4);
    int arcs = 0;
    for (const PathPiece& piece : p) {
      if (piece.curvature != 0.0) {
        ++arcs;
        QVERIFY(std::abs(std::abs(piece.curvature) - 2.5) < 1e-12);
      }
    }
    QCOMPARE(arcs, 4);
    QCOMPARE(p.size(), std::size_t(7));  // 3 lanes + 4 quarter arcs: no straight between arcs
    // Lane length 4 - 0.4 at each U-turn end: 3.6, 3.2, 3.6.
    QVERIFY(std::abs(p[0].length - 3.6) < 1e-12 && std::abs(p[3].length - 3.2) < 1e-12);
  }

  // Paper 000 §4.2: 4 well-spaced stops. On a 10 m straight at 0.5 m/s they are at the middles of
  // four 2.5 m parts, 1.25, 3.75, 6.25 and 8.75 m, reached at s / v plus one 0.1 s ring cycle
  // held still at each earlier stop.
  void stopAndScanSpacing() {
    const std::vector<double> s = stopDistances(10.0, 4);
    QCOMPARE(s, (std::vector<double>{1.25, 3.75, 6.25, 8.75}));
    SimulationSettings settings;
    settings.route = RouteKind::StopAndScan;
    settings.stops = 4;
    settings.limits.speed = 0.5;
    const std::vector<Position> w{{10, 0}};
    const Trajectory path = planTrajectory(Pose2D(0, 0, 0), w, settings);
    const SonarRing ring = SonarRing::k2a();
    const Dataset d = simulate(SonarWorld{}, ring, path, settings, "stops");
    QCOMPARE(d.scans.size(), std::size_t(4));
    for (std::size_t k = 0; k < 4; ++k) {
      QVERIFY(std::abs(d.scans[k].truth->x() - s[k]) < 1e-9);
      QVERIFY(std::abs(d.scans[k].time - (s[k] / 0.5 + 0.1 * double(k))) < 1e-6);
      QCOMPARE(d.scans[k].readings.size(), std::size_t(24));
      QCOMPARE(d.scans[k].odometry, *d.scans[k].truth);  // no drift asked
    }
  }

  // In motion: one scan per ring cycle; drift changes the odometry only, never the sonar readings
  // (its noise has its own engine) or the true poses.
  void inMotionWithAndWithoutDrift() {
    SimulationSettings settings;
    settings.physics.seed = 5;
    settings.physics.misreadRate = 0.01;
    const std::vector<Position> corners{{-1, -1}, {6, -1}, {6, 1}, {-1, 1}};
    const SonarWorld world(polygonSegments(corners, true));
    const std::vector<Position> w{{5, 0}};
    const Trajectory path = planTrajectory(Pose2D(0, 0, 0), w, settings);
    const SonarRing ring = SonarRing::pioneer3dx();
    const Dataset still = simulate(world, ring, path, settings, "a");
    settings.drift = defaultDrift();
    const Dataset drifting = simulate(world, ring, path, settings, "a");
    // 5 m at 0.3 m/s: 16.67 s, scans at 0, 0.1, ..., 16.6 s.
    QCOMPARE(still.scans.size(), std::size_t(167));
    QCOMPARE(drifting.scans.size(), still.scans.size());
    bool odometryDiffers = false;
    for (std::size_t k = 0; k < still.scans.size(); ++k) {
      QCOMPARE(drifting.scans[k].readings, still.scans[k].readings);
      QCOMPARE(*drifting.scans[k].truth, *still.scans[k].truth);
      odometryDiffers |= !(drifting.scans[k].odometry == still.scans[k].odometry);
    }
    QVERIFY(odometryDiffers);
  }

  void worldJsonProperties() {
    const std::string text = R"({"format": "sonargrid-reference", "version": 1, "units": "cm",
      "start": {"x": 80, "y": 100, "heading_deg": 90},
      "objects": [
        {"name": "wall", "closed": false, "corners": [[0, 0], [500, 0]], "surface": "specular",
         "specular_limit_deg": 15},
        {"name": "pole", "centre": [390, 140], "radius": 0.95, "surface": "diffuse"},
        {"name": "box", "closed": true, "corners": [[0, 0], [10, 0], [10, 10]]}]})";
    const ReferenceMap map = parseReferenceJson(text, "w.json");
    QVERIFY(map.start);
    const std::optional<Pose2D> start = startPose(map);
    QVERIFY(std::abs(start->x() - 0.8) < 1e-12 && std::abs(start->y() - 1.0) < 1e-12);
    QVERIFY(std::abs(start->heading - std::numbers::pi / 2) < 1e-12);
    QCOMPARE(map.objects[1].corners.size(), std::size_t(kCircleCorners));
    const SonarWorld world = sonarWorld(map);
    QCOMPARE(world.segments.size(), std::size_t(1 + 3));
    QCOMPARE(world.segments[0].maxIncidenceDeg, 15.0);
    QCOMPARE(world.segments[1].maxIncidenceDeg, kPhysicsIncidenceLimit);  // unspecified
    QCOMPARE(world.circles.size(), std::size_t(1));
    QVERIFY((world.circles[0].centre - Position(3.9, 1.4)).norm() < 1e-12);
    QVERIFY(std::abs(world.circles[0].radius - 0.0095) < 1e-15);
    QCOMPARE(world.circles[0].maxIncidenceDeg, kDiffuseIncidenceLimit);
    // Written back, it reads back the same.
    const ReferenceMap again = parseReferenceJson(referenceJsonText(map), "again.json");
    QCOMPARE(referenceJsonText(again), referenceJsonText(map));
    QCOMPARE(again.objects[1].circle->radius, 0.95);
    QCOMPARE(again.objects[0].surface, Surface::Specular);
  }

  void worldJsonErrors_data() {
    QTest::addColumn<QString>("objects");
    QTest::addColumn<QString>("message");
    QTest::newRow("radius 0") << R"({"name": "p", "centre": [1, 1], "radius": 0})"
                              << "w.json:1: objects[0].radius: a circle's radius must be above 0";
    QTest::newRow("limit without specular")
        << R"({"name": "w", "closed": false, "corners": [[0, 0], [1, 0]], "specular_limit_deg": 9})"
        << "w.json:1: objects[0].specular_limit_deg: object \"w\": specular_limit_deg needs "
           "\"surface\": \"specular\"";
    QTest::newRow("unknown surface")
        << R"({"name": "w", "closed": false, "corners": [[0, 0], [1, 0]], "surface": "glass"})"
        << "w.json:1: objects[0].surface: expected \"specular\" or \"diffuse\", got \"glass\"";
    QTest::newRow("circle with corners")
        << R"({"name": "p", "centre": [1, 1], "radius": 1, "corners": [[0, 0], [1, 0]]})"
        << "w.json:1: objects[0].corners: unknown key for a circle (expected name, centre, "
           "radius, surface, specular_limit_deg)";
  }
  void worldJsonErrors() {
    QFETCH(QString, objects);
    QFETCH(QString, message);
    const std::string text =
        R"({"format": "sonargrid-reference", "version": 1, "units": "m", "objects": [)" +
        objects.toStdString() + "]}";
    try {
      parseReferenceJson(text, "w.json");
      QFAIL("accepted");
    } catch (const std::exception& e) {
      QCOMPARE(QString::fromUtf8(e.what()), message);
    }
  }

  void routeFile() {
    const std::vector<Position> w = parseRouteText("# a comment\n1 2\n\n3.5 -4  # end\n", "r.txt");
    QCOMPARE(w, (std::vector<Position>{{1, 2}, {3.5, -4}}));
    try {
      parseRouteText("1 2\n3\n", "r.txt");
      QFAIL("accepted");
    } catch (const std::exception& e) {
      QCOMPARE(QString::fromUtf8(e.what()),
               QString("r.txt:2: waypoint: expected two numbers 'X Y' (metres), got 1"));
    }
  }
};

QTEST_GUILESS_MAIN(TstSimulator)
#include "tst_simulator.moc"
