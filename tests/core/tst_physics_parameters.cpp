// SPDX-License-Identifier: BSD-3-Clause
// The simulator's physics declaration (core/sonargrid/sim/physics_parameters.h, docs/simulator.md):
// one default, shared by SonarPhysics and the declaration; the three presets; and the multipath
// path loss worked by hand.

#include <QtTest>
#include <cmath>

#include "sonargrid/sim/physics_parameters.h"
#include "sonargrid/sim/simulation.h"

using namespace sg;

namespace {

// A ray from the origin along +x meets a mirror on the line y = x − 2 at (2, 0), 45° from its
// normal (beyond a 30° limit: reflected), turns to +y and meets the wall y = h head on at (2, h).
// The folded range is 2 + h.
SonarWorld mirrorAndWall(double h) {
  return SonarWorld(std::vector<Segment>{{Position(1.0, -1.0), Position(3.0, 1.0)},
                                         {Position(1.0, h), Position(3.0, h)}});
}

}  // namespace

class TstPhysicsParameters : public QObject {
  Q_OBJECT

 private slots:
  // SonarPhysics's member defaults, the ring window and drift the simulator uses by default are
  // the declared defaults, value for value: there is one default.
  void oneDefault() {
    SonarRing ring;
    ring.minRange = 0.15;
    ring.maxRange = 10.0;
    const ParameterSet fromStruct = physicsParameters(SonarPhysics{}, ring, defaultDrift());
    const ParameterSet declared = defaultPhysicsParameters();
    for (const ParameterSpec& s : physicsParameterSpecs())
      QVERIFY2(fromStruct.get(s.name) == declared.get(s.name), s.name.c_str());
    QVERIFY(*physicsPreset("default") == declared);
  }

  void everyDeclarationIsComplete() {
    QCOMPARE(physicsParameterSpecs().size(), std::size_t(13));
    for (const ParameterSpec& s : physicsParameterSpecs()) {
      QVERIFY2(!s.source.empty() && !s.description.empty(), s.name.c_str());
      QVERIFY2(s.min <= s.defaultValue && s.defaultValue <= s.max, s.name.c_str());
    }
  }

  // docs/simulator.md, "Presets".
  void presets_data() {
    QTest::addColumn<QString>("preset");
    QTest::addColumn<QString>("name");
    QTest::addColumn<double>("value");
    // harsh: `simulate`'s flags before the declaration (20°, multipath on, 1 % misreadings) and
    // SonarPhysics's 3 lossless reflections of that time.
    QTest::newRow("harsh limit") << "harsh"
                                 << "specular_limit" << 20.0;
    QTest::newRow("harsh multipath") << "harsh"
                                     << "multipath" << 1.0;
    QTest::newRow("harsh bounces") << "harsh"
                                   << "max_bounces" << 3.0;
    QTest::newRow("harsh loss") << "harsh"
                                << "reflection_loss" << 0.0;
    QTest::newRow("harsh misreads") << "harsh"
                                    << "misread_rate" << 0.01;
    QTest::newRow("harsh noise") << "harsh"
                                 << "noise" << 0.01;
    QTest::newRow("harsh max range") << "harsh"
                                     << "max_range" << 10.0;
    // clean: every surface echoes, nothing else is heard.
    QTest::newRow("clean limit") << "clean"
                                 << "specular_limit" << 90.0;
    QTest::newRow("clean multipath") << "clean"
                                     << "multipath" << 0.0;
    QTest::newRow("clean misreads") << "clean"
                                    << "misread_rate" << 0.0;
    QTest::newRow("clean noise") << "clean"
                                 << "noise" << 0.01;
    // default: Cao & Borenstein's ±42° less the 12.5° half-cone; the mild ends.
    QTest::newRow("default limit") << "default"
                                   << "specular_limit" << 30.0;
    QTest::newRow("default bounces") << "default"
                                     << "max_bounces" << 1.0;
    QTest::newRow("default loss") << "default"
                                  << "reflection_loss" << 6.0;
    QTest::newRow("default misreads") << "default"
                                      << "misread_rate" << 0.0;
  }
  void presets() {
    QFETCH(QString, preset);
    QFETCH(QString, name);
    QFETCH(double, value);
    const std::optional<ParameterSet> set = physicsPreset(preset.toStdString());
    QVERIFY(set.has_value());
    QCOMPARE(set->get(name.toStdString()), value);
  }

  void unknownPreset() {
    QVERIFY(!physicsPreset("gentle").has_value());
    QCOMPARE(physicsPresetNames(), (std::vector<std::string>{"clean", "default", "harsh"}));
  }

  void applyAndDrift() {
    SonarPhysics p;
    SonarRing ring;
    applyPhysics(*physicsPreset("harsh"), p, ring);
    QCOMPARE(p.maxIncidenceDeg, 20.0);
    QVERIFY(p.specularEcho == SpecularEcho::Multipath);
    QCOMPARE(p.maxBounces, 3);
    QCOMPARE(p.reflectionLossDb, 0.0);
    QCOMPARE(p.misreadRate, 0.01);
    QCOMPARE(ring.minRange, 0.15);
    QCOMPARE(ring.maxRange, 10.0);
    const OdometryErrors e = driftErrors(defaultPhysicsParameters());
    QCOMPARE(e.leftScale, 0.00025);
    QCOMPARE(e.rightScale, -0.00025);
    QCOMPARE(e.wheelbaseScale, 0.005);
    QCOMPARE(e.wheelNoise, 0.001);
  }

  // Path loss: one reflection of `loss` dB is heard while loss <= 20 log10(10 / r), r = 2 + h.
  void multipathPathLoss_data() {
    QTest::addColumn<double>("h");
    QTest::addColumn<double>("loss");
    QTest::addColumn<int>("bounces");
    QTest::addColumn<double>("range");  // NaN: no echo
    const double none = std::numeric_limits<double>::quiet_NaN();
    // r = 4.9: 20 log10(10 / 4.9) = 6.196 dB >= 6: heard at the folded range.
    QTest::newRow("4.9 m, 6 dB") << 2.9 << 6.0 << 1 << 4.9;
    // r = 5.1: 20 log10(10 / 5.1) = 5.849 dB < 6: lost.
    QTest::newRow("5.1 m, 6 dB") << 3.1 << 6.0 << 1 << none;
    // Lossless: any folded range under 10 m is heard.
    QTest::newRow("5.1 m, 0 dB") << 3.1 << 0.0 << 1 << 5.1;
    QTest::newRow("9.5 m, 0 dB") << 7.5 << 0.0 << 1 << 9.5;
    // r = 7: 20 log10(10 / 7) = 3.098 dB >= 3: heard.
    QTest::newRow("7 m, 3 dB") << 5.0 << 3.0 << 1 << 7.0;
    // No reflection followed: the mirror's ray is lost.
    QTest::newRow("no bounce") << 2.9 << 0.0 << 0 << none;
  }
  void multipathPathLoss() {
    QFETCH(double, h);
    QFETCH(double, loss);
    QFETCH(int, bounces);
    QFETCH(double, range);
    SonarPhysics p;
    p.maxIncidenceDeg = 30.0;
    p.specularEcho = SpecularEcho::Multipath;
    p.maxBounces = bounces;
    p.reflectionLossDb = loss;
    const std::optional<Echo> echo =
        traceRay(mirrorAndWall(h), Position(0.0, 0.0), Position(1.0, 0.0), 10.0, p);
    if (std::isnan(range)) {
      QVERIFY(!echo.has_value());
    } else {
      QVERIFY(echo.has_value());
      QVERIFY(std::abs(echo->range - range) < 1e-9);
    }
  }
};

QTEST_GUILESS_MAIN(TstPhysicsParameters)
#include "tst_physics_parameters.moc"
