// SPDX-License-Identifier: GPL-3.0-or-later
// Pixel checks of the pure beam-model render (renderBeamModel), and the view's own controls.
// Colours expected are the 16-level palette (export/palette.cpp) at P values worked by hand from
// the model formulas named beside each row; a pixel centre lies within half a pixel (< 0.01 m) of
// the point asked for, hence the small colour tolerance.

#include <QtTest>

#include <QComboBox>
#include <QSet>
#include <QSlider>
#include <QTemporaryDir>
#include <cmath>

#include "beam_model_view.h"
#include "sonargrid/params/presets.h"

using namespace sg;
using namespace sg::ui;

namespace {

constexpr QSize kSize(900, 820);

BeamScene scene(const std::string& model, double s = 2.0) {
  BeamScene sc;
  sc.settings.model = model;
  sc.settings.rule = model == "himm" ? "himm" : "bayes";
  sc.settings.parameters = defaultParameters(sc.settings.model, sc.settings.rule);
  sc.range = s;
  sc.maxRange = 5.0;
  return sc;
}

bool near(const QColor& a, const QColor& b, int tolerance) {
  return std::abs(a.red() - b.red()) <= tolerance && std::abs(a.green() - b.green()) <= tolerance &&
         std::abs(a.blue() - b.blue()) <= tolerance;
}

QString describe(const QColor& c) {
  return QString("(%1, %2, %3)").arg(c.red()).arg(c.green()).arg(c.blue());
}

// The colour of the map pixel holding plane point (x, y) in column `column`.
QColor mapPixel(const QImage& image, const std::vector<BeamScene>& scenes, int column, double x,
                double y) {
  const BeamLayout layout = beamLayout(image.size(), static_cast<int>(scenes.size()));
  const ConeMapFrame frame =
      coneMapFrame(beamExtent(scenes), layout.map[static_cast<std::size_t>(column)]);
  const QPointF p = frame.toPixel(x, y);
  return image.pixelColor(static_cast<int>(std::floor(p.x())), static_cast<int>(std::floor(p.y())));
}

// A translucent shade over white, as QPainter composes it (source-over).
QColor overWhite(const QColor& shade) {
  const double a = shade.alpha() / 255.0;
  auto mix = [a](int c) { return static_cast<int>(std::lround(255.0 + a * (c - 255.0))); };
  return QColor(mix(shade.red()), mix(shade.green()), mix(shade.blue()));
}

}  // namespace

class TstBeamModelView : public QObject {
  Q_OBJECT

 private slots:
  void mapColours_data();
  void mapColours();
  void twoModelsSideBySide();
  void twoModelsStackInANarrowView();
  void murphyRegions();
  void hpfArcsAndHimmCell();
  void viewControls();
  void snapshots();
  void compareWithPresetsAndPinnedRows();
};

void TstBeamModelView::mapColours_data() {
  QTest::addColumn<QString>("model");
  QTest::addColumn<double>("x");
  QTest::addColumn<double>("y");
  QTest::addColumn<double>("p");  // expected P(occ); negative: the no-update background
  // HPF, ε = 0.1 m, ω = 25°, s = 2 m (paper 000 eqs 1–6, P = 0.5 + (pO − pE)/2):
  // at r = s on the axis Or = Oa = 1 → P = 1.
  QTest::newRow("hpf at s") << "hpf" << 2.0 << 0.0 << 1.0;
  // r = 0.05: Er = 1 − (0.05/1.9)² = 0.99931 → P = 0.00035, the free colour.
  QTest::newRow("hpf near sensor") << "hpf" << 0.05 << 0.0 << 0.00035;
  // r = 1: Er = 1 − (1/1.9)² = 0.72299 → P = 0.1385.
  QTest::newRow("hpf r=1") << "hpf" << 1.0 << 0.0 << 0.1385;
  // 26.6° off the axis (> ω/2 = 12.5°) and beyond s + ε on the axis: no update.
  QTest::newRow("hpf outside cone") << "hpf" << 1.0 << 0.5 << -1.0;
  QTest::newRow("hpf beyond reading") << "hpf" << 2.3 << 0.0 << -1.0;
  // P1–P5 defaults (0.02, 0.15, 0.1 m, 0.98, 15°), s = 2: axis at s → P4 = 0.98; at r = 1,
  // Region II: 0.02 + (0.5 − 0.15 − 0.02)·1/1.9 = 0.19368; at α = 10° (x = cos, y = sin):
  // eq 7 → (15 − 10)/15·(0.19368 − 0.5) + 0.5 = 0.39789.
  QTest::newRow("p1-p5 at s") << "parameterized" << 2.0 << 0.0 << 0.98;
  QTest::newRow("p1-p5 r=1") << "parameterized" << 1.0 << 0.0 << 0.19368;
  QTest::newRow("p1-p5 10deg") << "parameterized" << std::cos(10.0 * M_PI / 180.0)
                               << std::sin(10.0 * M_PI / 180.0) << 0.39789;
  // HIMM (OctoMap hit 0.7, miss 0.4): the axis only, drawn a few pixels wide.
  QTest::newRow("himm before echo") << "himm" << 1.0 << 0.0 << 0.4;
  QTest::newRow("himm echo") << "himm" << 2.0 << 0.0 << 0.7;
  QTest::newRow("himm off axis") << "himm" << 1.0 << 0.2 << -1.0;
}

void TstBeamModelView::mapColours() {
  QFETCH(QString, model);
  QFETCH(double, x);
  QFETCH(double, y);
  QFETCH(double, p);
  const std::vector<BeamScene> scenes{scene(model.toStdString())};
  const QImage image = renderBeamModel(scenes, kSize);
  const QColor expected = p < 0.0 ? noUpdateColour() : occupancyColour(p);
  const QColor got = mapPixel(image, scenes, 0, x, y);
  QVERIFY2(near(got, expected, 6), qPrintable(describe(got) + " vs " + describe(expected)));
}

void TstBeamModelView::twoModelsSideBySide() {
  const std::vector<BeamScene> scenes{scene("hpf"), scene("murphy")};
  const QImage image = renderBeamModel(scenes, kSize);
  // Left, HPF at s: P = 1. Right, Murphy (R = 5, β = 15°, Max_occ 0.98) at s = 2 on the axis:
  // v = ((5 − 2)/5 + 1)/2 = 0.8 → P = 0.8 · 0.98 = 0.784 (paper 002 eq 1).
  QVERIFY(near(mapPixel(image, scenes, 0, 2.0, 0.0), occupancyColour(1.0), 6));
  QVERIFY(near(mapPixel(image, scenes, 1, 2.0, 0.0), occupancyColour(0.784), 6));
  // 14° off the axis at r = 1: outside HPF's ±12.5° but inside Murphy's ±15°, where Region II
  // gives v = (0.8 + 1/15)/2 = 0.4333 → P = 0.5667, above 0.5: paper 002 §3.2's complaint.
  const double x = std::cos(14.0 * M_PI / 180.0), y = std::sin(14.0 * M_PI / 180.0);
  QVERIFY(near(mapPixel(image, scenes, 0, x, y), noUpdateColour(), 0));
  const QColor right = mapPixel(image, scenes, 1, x, y);
  QVERIFY2(near(right, occupancyColour(0.5667), 6), qPrintable(describe(right)));
}

void TstBeamModelView::twoModelsStackInANarrowView() {
  // Issue 49 item 9: at the Beam Model dock's default width (about 250 px) two columns were
  // 83 px wide each and could not be read. Below kMinBeamColumnWidth the scenes stack, each the
  // full width; the same pixel checks as side by side hold in each row.
  const QSize narrow(250, 700);
  const std::vector<BeamScene> scenes{scene("hpf"), scene("murphy")};
  const BeamLayout layout = beamLayout(narrow, 2);
  QVERIFY(layout.stacked);
  QCOMPARE(layout.map[0].width(), layout.map[1].width());
  QVERIFY(layout.map[0].width() > 2 * kMinBeamColumnWidth / 3);
  QVERIFY(layout.map[1].top() >= layout.surface[0].bottom());
  QVERIFY(!beamLayout(kSize, 2).stacked);  // a wide view keeps them side by side
  const QImage image = renderBeamModel(scenes, narrow);
  // HPF at s: P = 1; Murphy at s = 2 on the axis: 0.8 · 0.98 = 0.784 (as twoModelsSideBySide).
  QVERIFY(near(mapPixel(image, scenes, 0, 2.0, 0.0), occupancyColour(1.0), 6));
  const QColor murphy = mapPixel(image, scenes, 1, 2.0, 0.0);
  QVERIFY2(near(murphy, occupancyColour(0.784), 6), qPrintable(describe(murphy)));

  // In the first-launch dock (330 px column, 310 x 300 canvas) a 150 px band has no room for
  // three 90 px panels, nor two after its title: each scene keeps its cone map alone.
  const QSize dock(310, 300);
  const BeamLayout low = beamLayout(dock, 2);
  QVERIFY(low.stacked);
  for (std::size_t c = 0; c < 2; ++c) {
    QVERIFY(low.profile[c].isEmpty());
    QVERIFY(low.surface[c].isEmpty());
    QVERIFY(low.map[c].height() >= kMinBeamPanelHeight);
  }
  const QImage lowImage = renderBeamModel(scenes, dock);
  QVERIFY(near(mapPixel(lowImage, scenes, 0, 2.0, 0.0), occupancyColour(1.0), 6));
  const QColor lowMurphy = mapPixel(lowImage, scenes, 1, 2.0, 0.0);
  QVERIFY2(near(lowMurphy, occupancyColour(0.784), 6), qPrintable(describe(lowMurphy)));
  // One scene there: 300 px less a 48 px title leaves 252 px, room for the map and the profile.
  const BeamLayout one = beamLayout(dock, 1);
  QVERIFY(!one.profile[0].isEmpty());
  QVERIFY(one.surface[0].isEmpty());
  // Its colour bar takes the view's whole height, as low as the view is, for its labels.
  QCOMPARE(one.colourBar.top(), 0);
  QCOMPARE(one.colourBar.height(), dock.height());
  // At any size, a profile or surface that is drawn is at least kMinBeamPanelHeight high, and so
  // is the cone map beside them.
  for (const int columns : {1, 2})
    for (const int w : {250, 800})
      for (int h = 150; h <= 1000; h += 7) {
        const BeamLayout l = beamLayout(QSize(w, h), columns);
        for (std::size_t c = 0; c < l.map.size(); ++c) {
          const QString where = QStringLiteral("%1 x %2, %3 scenes").arg(w).arg(h).arg(columns);
          for (const QRect& panel : {l.profile[c], l.surface[c]})
            QVERIFY2(panel.isEmpty() || panel.height() >= kMinBeamPanelHeight, qPrintable(where));
          if (!l.profile[c].isEmpty())
            QVERIFY2(l.map[c].height() >= kMinBeamPanelHeight, qPrintable(where));
        }
      }
}

void TstBeamModelView::murphyRegions() {
  // Murphy defaults, s = 2, tolerance 0.1: Region II to 1.9 m, Region I 1.9–2.1 m, Region III
  // beyond (paper 002 §3.1, Fig. 3).
  const BeamScene sc = scene("murphy");
  const BeamExtent extent = beamExtent({sc});
  const std::vector<AxialSpan> spans = axialSpans(sc, extent.xMax);
  QCOMPARE(spans.size(), std::size_t{3});
  const double sample = extent.xMax / 1200;  // the spans' resolution
  QCOMPARE(spans[0].label, QString("Region II"));
  QVERIFY(std::abs(spans[0].to - 1.9) <= sample);
  QCOMPARE(spans[1].label, QString("Region I"));
  QVERIFY(std::abs(spans[1].from - 1.9) <= sample && std::abs(spans[1].to - 2.1) <= sample);
  QCOMPARE(spans[2].label, QString("Region III"));
  QCOMPARE(spans[2].to, extent.xMax);

  // The profile shades each region: pixels away from the curve, the labels and the 0.5 line.
  const QImage image = renderBeamModel({sc}, kSize);
  const AxialProfileFrame frame = axialProfileFrame(extent, beamLayout(kSize, 1).profile[0]);
  auto at = [&](double r, double p) {
    const QPointF px = frame.toPixel(r, p);
    return image.pixelColor(static_cast<int>(px.x()), static_cast<int>(px.y()));
  };
  // Region I at P = 0.1 (curve at 0.784), Region II at r = 1, P = 0.7 (curve at 0.1), Region III
  // at r = 2.5, P = 0.3.
  QVERIFY2(near(at(2.0, 0.1), overWhite(QColor(214, 72, 52, 50)), 2),
           qPrintable(describe(at(2.0, 0.1))));
  QVERIFY2(near(at(1.0, 0.7), overWhite(QColor(70, 130, 220, 45)), 2),
           qPrintable(describe(at(1.0, 0.7))));
  QVERIFY2(near(at(2.5, 0.3), overWhite(QColor(150, 150, 150, 40)), 2),
           qPrintable(describe(at(2.5, 0.3))));
  // The curve itself passes through P(r = 1) = 1 − 0.9 = 0.1 (eq 3, v = (0.8 + 1)/2): dark.
  QVERIFY(at(1.0, 0.1).lightness() < 80);
}

void TstBeamModelView::hpfArcsAndHimmCell() {
  const BeamScene hpf = scene("hpf");
  const std::vector<AxialSpan> a = axialSpans(hpf, beamExtent({hpf}).xMax);
  // Empty arc [0, s − ε], occupied arc [s − ε, s + ε], nothing beyond (paper 000 eqs 2, 5).
  QCOMPARE(a.size(), std::size_t{3});
  QCOMPARE(a[0].label, QString("empty arc"));
  QCOMPARE(a[1].label, QString("occupied arc"));
  QCOMPARE(a[2].label, QString("no update"));
  // HIMM: the echo is one cell, exactly at s.
  const BeamScene himm = scene("himm");
  const std::vector<AxialSpan> h = axialSpans(himm, beamExtent({himm}).xMax);
  QCOMPARE(h.size(), std::size_t{3});
  QCOMPARE(h[1].label, QString("I⁺ cell"));
  QCOMPARE(h[1].from, 2.0);
  QCOMPARE(h[1].to, 2.0);
}

void TstBeamModelView::viewControls() {
  BeamModelView view;
  view.setSettings(applyPreset(*findPreset("paper002-fig6-parameterized")));
  view.setRange(2.0);
  QSignalSpy spy(&view, &BeamModelView::rangeChanged);
  auto* slider = view.findChild<QSlider*>("rangeSlider");
  QTest::keyClick(slider, Qt::Key_Right);  // one position = 0.01 m
  QCOMPARE(spy.count(), 1);
  QCOMPARE(view.range(), 2.01);
  view.setRange(99.0);  // clamped to the maximum range
  QCOMPARE(view.range(), 5.0);

  auto* compare = view.findChild<QComboBox*>("compareChooser");
  compare->setFocus();
  compare->setCurrentIndex(0);
  QTest::keyClick(compare, Qt::Key_Down);  // the first model in registry order, hpf
  QVERIFY(view.comparisonSettings().has_value());
  QCOMPARE(view.comparisonSettings()->model, std::string("hpf"));
  QCOMPARE(view.scenes().size(), std::size_t{2});
  view.setComparisonSettings(std::nullopt);
  QCOMPARE(compare->currentIndex(), 0);
  QCOMPARE(view.scenes().size(), std::size_t{1});
}

void TstBeamModelView::snapshots() {
  // The whole view at a projector's size, both models of paper 002 Fig. 6 side by side, saved as
  // PNG. Set SONARGRID_SNAPSHOT_DIR to keep the pictures for a look; otherwise they go to a
  // temporary folder. The checks: every picture saves, and the view's grab is a drawn figure (the
  // palette's 16 levels, the background and the ink give well over 16 colours), not a blank
  // widget.
  QTemporaryDir scratch;
  QString dir = qEnvironmentVariable("SONARGRID_SNAPSHOT_DIR");
  if (dir.isEmpty()) dir = scratch.path();
  BeamModelView view;
  view.setSettings(applyPreset(*findPreset("paper002-fig6-parameterized")));
  view.setComparisonSettings(applyPreset(*findPreset("paper002-fig6-standard")));
  view.setRange(3.0);
  view.resize(1280, 900);
  const QImage grabbed = view.grab().toImage();
  QSet<QRgb> colours;
  for (int y = 0; y < grabbed.height(); y += 3)
    for (int x = 0; x < grabbed.width(); x += 3) colours.insert(grabbed.pixel(x, y));
  QVERIFY2(colours.size() > 32, qPrintable(QString::number(colours.size())));
  QVERIFY(grabbed.save(dir + "/beam_view_fig6.png"));
  QVERIFY(renderBeamModel({scene("hpf"), scene("himm")}, QSize(1200, 860))
              .save(dir + "/beam_hpf_himm.png"));
  // Compare mode in the dock's first-launch size at 1280 x 800 (a 330 px column, the beam view
  // above the parameter panel): stacked.
  QVERIFY(renderBeamModel({scene("hpf"), scene("murphy")}, QSize(310, 300))
              .save(dir + "/beam_compare_narrow.png"));
  BeamScene fig3 = scene("murphy", 5.0);
  fig3.settings = applyPreset(*findPreset("paper002-fig3"));
  fig3.maxRange = 8.0;
  QVERIFY(renderBeamModel({fig3}, QSize(800, 860)).save(dir + "/beam_fig3.png"));
  QVERIFY(
      renderBeamModel({scene("konolige", 1.5)}, QSize(800, 860)).save(dir + "/beam_konolige.png"));
}

void TstBeamModelView::compareWithPresetsAndPinnedRows() {
  BeamModelView view;
  MapperSettings shown = applyPreset(*findPreset("paper002-fig6-parameterized"));  // P5 = 15°
  view.setSettings(shown);
  // A pinned row (Document::pinnedRows) with P5 = 6°, the classroom case.
  MapperSettings narrow = shown;
  narrow.parameters.set("p5", 6.0);
  view.setPinnedConfigurations({{QStringLiteral("P5 6°"), narrow}});
  auto* compare = view.findChild<QComboBox*>("compareChooser");
  QVERIFY(compare->findText("Pinned: P5 6°") >= 0);
  QVERIFY(view.compareWith("pinned:0"));
  QCOMPARE(view.comparisonSettings()->parameters.get("p5"), 6.0);
  QCOMPARE(view.scenes().size(), std::size_t{2});
  QCOMPARE(compare->currentData().toString(), QString("pinned:0"));
  // A paper preset: Arafat et al. Fig. 6 left, Murphy's model (β = 15°).
  QVERIFY(view.compareWith("preset:paper002-fig6-standard"));
  QCOMPARE(view.comparisonSettings()->model, std::string("murphy"));
  QCOMPARE(view.comparisonSettings()->parameters.get("beta"), 15.0);
  // These settings, frozen: they stay while the shown ones move on.
  QVERIFY(view.compareWith("current"));
  view.setSettings(narrow);
  QCOMPARE(view.comparisonSettings()->parameters.get("p5"), 15.0);
  QCOMPARE(view.scenes()[0].settings.parameters.get("p5"), 6.0);
  // Unpinning the row a comparison came from ends that comparison.
  QVERIFY(view.compareWith("pinned:0"));
  view.setPinnedConfigurations({});
  QVERIFY(!view.comparisonSettings().has_value());
  QVERIFY(!view.compareWith("pinned:0"));
  // A model at its defaults comes with its paper's rule.
  QVERIFY(view.compareWith("model:hpf"));
  QCOMPARE(view.comparisonSettings()->rule, std::string("addition"));
  QVERIFY(view.compareWith(QString()));
  QCOMPARE(view.scenes().size(), std::size_t{1});
}

QTEST_MAIN(TstBeamModelView)
#include "tst_beam_model_view.moc"
