// SPDX-License-Identifier: BSD-3-Clause
// The paper presets: every value is declared and inside its declared range, every pair is
// allowed, and the values are the ones the papers print (the expected numbers below are copied
// from the paper place each row names, not from presets.cpp).

#include <QtTest>
#include <algorithm>
#include <set>

#include "sonargrid/params/presets.h"

using namespace sg;

class TstPresets : public QObject {
  Q_OBJECT

 private slots:
  void everyValueIsDeclaredAndInRange();
  void everyPairIsAllowedAndCited();
  void companionsPointBack();
  void printedValues_data();
  void printedValues();
  void unstatedValuesKeepDefaults();
  void unknownNameIsNull();
};

void TstPresets::everyValueIsDeclaredAndInRange() {
  QVERIFY(!paperPresets().empty());
  for (const Preset& p : paperPresets()) {
    const ParameterSet declared = defaultParameters(p.model, p.rule);
    for (const PresetValue& v : p.values) {
      const auto& specs = declared.specs();
      const auto spec = std::find_if(specs.begin(), specs.end(),
                                     [&](const ParameterSpec& s) { return s.name == v.parameter; });
      QVERIFY2(spec != specs.end(), qPrintable(QString::fromStdString(p.name + ": " + v.parameter +
                                                                      " is not declared")));
      QVERIFY2(
          v.value >= spec->min && v.value <= spec->max,
          qPrintable(QString::fromStdString(p.name + ": " + v.parameter) +
                     QString(" = %1 outside [%2, %3]").arg(v.value).arg(spec->min).arg(spec->max)));
      if (spec->integer) QCOMPARE(v.value, std::round(v.value));
    }
    // applyPreset runs ParameterSet::set, the same range check the CLI and the panel use.
    const MapperSettings s = applyPreset(p);
    QCOMPARE(QString::fromStdString(s.model), QString::fromStdString(p.model));
    QCOMPARE(QString::fromStdString(s.rule), QString::fromStdString(p.rule));
  }
}

void TstPresets::everyPairIsAllowedAndCited() {
  std::set<std::string> names;
  for (const Preset& p : paperPresets()) {
    QVERIFY2(names.insert(p.name).second, p.name.c_str());
    QVERIFY2(compatibility(p.model, p.rule).allowed, p.name.c_str());
    QVERIFY(!p.title.empty());
    QVERIFY(p.source.rfind("paper 00", 0) == 0);
    for (const PresetValue& v : p.values) {
      QVERIFY2(v.citation.rfind("paper 00", 0) == 0, (p.name + ": " + v.parameter).c_str());
    }
  }
}

void TstPresets::companionsPointBack() {
  for (const Preset& p : paperPresets()) {
    if (p.companion.empty()) continue;
    const Preset* other = findPreset(p.companion);
    QVERIFY2(other, p.companion.c_str());
    QCOMPARE(QString::fromStdString(other->companion), QString::fromStdString(p.name));
  }
}

void TstPresets::printedValues_data() {
  QTest::addColumn<QString>("preset");
  QTest::addColumn<QString>("parameter");
  QTest::addColumn<double>("value");
  // Paper 000 §2.2: "the increment is actually 3", "CV_max = 15", decrements "in steps of −1".
  QTest::newRow("000 HIMM I+") << "paper000-himm"
                               << "increment" << 3.0;
  QTest::newRow("000 HIMM I-") << "paper000-himm"
                               << "decrement" << 1.0;
  QTest::newRow("000 HIMM CVmax") << "paper000-himm"
                                  << "cv_max" << 15.0;
  // Paper 000 eqs 7–8: Occ if Occ ≥ Emp, else −Emp (combine = 0).
  QTest::newRow("000 HPF combine") << "paper000-hpf"
                                   << "combine" << 0.0;
  // Paper 001 §3.1: normalise Po over the arc; Map = 1 − Emp or Occ (combine = 1).
  QTest::newRow("001 simple normalise") << "paper001-2dg-simple"
                                        << "normalise" << 1.0;
  QTest::newRow("001 simple combine") << "paper001-2dg-simple"
                                      << "combine" << 1.0;
  // Paper 001 §3.3: "a range of [−2..+2] was used".
  QTest::newRow("001 log min") << "paper001-2dg-log"
                               << "cut_min" << -2.0;
  QTest::newRow("001 log max") << "paper001-mt-log"
                               << "cut_max" << 2.0;
  // Paper 001 §2.2: F = 0.05, a(r) = 0.6(1 − min(1, 0.4r)), d(r) = .01 + 0.015r.
  QTest::newRow("001 F") << "paper001-mt-log"
                         << "false_rate" << 0.05;
  QTest::newRow("001 a0") << "paper001-mt-simple"
                          << "attenuation" << 0.6;
  QTest::newRow("001 k") << "paper001-mt-bayes"
                         << "attenuation_slope" << 0.4;
  QTest::newRow("001 d0") << "paper001-mt-log"
                          << "range_sd0" << 0.01;
  QTest::newRow("001 d1") << "paper001-mt-log"
                          << "range_sd1" << 0.015;
  // Paper 002 Figure 3 caption: Max_occupied = 0.9, Tolerance = ±0.5.
  QTest::newRow("002 fig3 maxocc") << "paper002-fig3"
                                   << "max_occupied" << 0.9;
  QTest::newRow("002 fig3 tol") << "paper002-fig3"
                                << "tolerance" << 0.5;
  // Paper 002 Figure 6 caption: Beta = 15, Tolerance = 1.0, Max_Occupied = 0.98 (left);
  // P1 = 0.02, P2 = 0.15, P3 = 1.0, P4 = 0.98, P5 = 15 (right).
  QTest::newRow("002 fig6 beta") << "paper002-fig6-standard"
                                 << "beta" << 15.0;
  QTest::newRow("002 fig6 tol") << "paper002-fig6-standard"
                                << "tolerance" << 1.0;
  QTest::newRow("002 fig6 maxocc") << "paper002-fig6-standard"
                                   << "max_occupied" << 0.98;
  QTest::newRow("002 fig6 P1") << "paper002-fig6-parameterized"
                               << "p1" << 0.02;
  QTest::newRow("002 fig6 P2") << "paper002-fig6-parameterized"
                               << "p2" << 0.15;
  QTest::newRow("002 fig6 P3") << "paper002-fig6-parameterized"
                               << "p3" << 1.0;
  QTest::newRow("002 fig6 P4") << "paper002-fig6-parameterized"
                               << "p4" << 0.98;
  QTest::newRow("002 fig6 P5") << "paper002-fig6-parameterized"
                               << "p5" << 15.0;
  // Paper 002 Table 1, column 5 (lowest histogram bin): 0.03, 0.171, 2·P3 = 0.786, 0.97, 6.14.
  QTest::newRow("002 T1 hist P1") << "paper002-table1-histogram"
                                  << "p1" << 0.03;
  QTest::newRow("002 T1 hist P2") << "paper002-table1-histogram"
                                  << "p2" << 0.171;
  QTest::newRow("002 T1 hist P3") << "paper002-table1-histogram"
                                  << "p3" << 0.393;
  QTest::newRow("002 T1 hist P4") << "paper002-table1-histogram"
                                  << "p4" << 0.97;
  QTest::newRow("002 T1 hist P5") << "paper002-table1-histogram"
                                  << "p5" << 6.14;
  // Column 6 (minimum VSDNS; also Table 2's first row): 0.02, 0.2, 2·P3 = 0.5, 0.98, 6.
  QTest::newRow("002 T1 min P2") << "paper002-table1-min-vsdns"
                                 << "p2" << 0.2;
  QTest::newRow("002 T1 min P3") << "paper002-table1-min-vsdns"
                                 << "p3" << 0.25;
  QTest::newRow("002 T1 min P5") << "paper002-table1-min-vsdns"
                                 << "p5" << 6.0;
  // Column 7 (mean VSDNS): 0.02, 0.05, 2·P3 = 2.0, 0.98, 14.
  QTest::newRow("002 T1 mean P2") << "paper002-table1-mean-vsdns"
                                  << "p2" << 0.05;
  QTest::newRow("002 T1 mean P3") << "paper002-table1-mean-vsdns"
                                  << "p3" << 1.0;
  QTest::newRow("002 T1 mean P5") << "paper002-table1-mean-vsdns"
                                  << "p5" << 14.0;
  // Figure 9: P1 = 0.05, P2 = 0.2, P3 = 0.5, P4 = 0.95, P5 = 40; Figure 10: 2·P3 = 3, P5 = 35.
  QTest::newRow("002 fig9 P4") << "paper002-fig9-derivative"
                               << "p4" << 0.95;
  QTest::newRow("002 fig9 P5") << "paper002-fig9-derivative"
                               << "p5" << 40.0;
  QTest::newRow("002 fig10 P3") << "paper002-fig10-two-runs"
                                << "p3" << 1.5;
  QTest::newRow("002 fig10 P5") << "paper002-fig10-two-runs"
                                << "p5" << 35.0;
}

void TstPresets::printedValues() {
  QFETCH(QString, preset);
  QFETCH(QString, parameter);
  QFETCH(double, value);
  const Preset* p = findPreset(preset.toStdString());
  QVERIFY(p);
  QCOMPARE(applyPreset(*p).parameters.get(parameter.toStdString()), value);
}

void TstPresets::unstatedValuesKeepDefaults() {
  // Paper 000 prints no ε or ω for its HPF: the declared defaults (hpf.cpp) stay.
  const MapperSettings s = applyPreset(*findPreset("paper000-hpf"));
  const ParameterSet defaults = defaultParameters("hpf", "addition");
  QCOMPARE(s.parameters.get("epsilon"), defaults.get("epsilon"));
  QCOMPARE(s.parameters.get("omega"), defaults.get("omega"));
  QCOMPARE(s.parameters.values().size(), defaults.values().size());
}

void TstPresets::unknownNameIsNull() {
  QVERIFY(findPreset("paper003-nothing") == nullptr);
}

QTEST_GUILESS_MAIN(TstPresets)
#include "tst_presets.moc"
