// SPDX-License-Identifier: BSD-3-Clause
// Map exports: the palettes, the PNG picture (checked pixel by pixel through renderMapImage, plus
// the PNG file's signature and IHDR size) and the ROS map_server pair (checked byte by byte).

#include <QDir>
#include <QFile>
#include <QTemporaryDir>
#include <QtTest>
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "sonargrid/engine/occupancy_map.h"
#include "sonargrid/export/map_export.h"
#include "sonargrid/export/palette.h"

namespace sg {
// Readable QCOMPARE failures (found by argument-dependent lookup).
char* toString(const Rgb& c) {
  return qstrdup(QString("Rgb(%1, %2, %3)").arg(c.r).arg(c.g).arg(c.b).toUtf8().constData());
}
}  // namespace sg

namespace {

// A map with every layer sized for w x h cells; levels 8 / p 0.5 / unobserved, like an empty map.
sg::OccupancyMap makeMap(int w, int h) {
  sg::GridSpec spec;
  spec.origin = sg::Position(-1.5, 0.25);
  spec.cellSize = 0.1;
  spec.width = w;
  spec.height = h;
  return sg::OccupancyMap::unobserved(spec);
}

// The 3 x 2 map of the PNG cases. Storage is row-major from the bottom row (index = iy * 3 + ix):
//   iy = 1 (top, north):   13 14 15
//   iy = 0 (bottom):        0  1  2
sg::OccupancyMap levelMap() {
  sg::OccupancyMap m = makeMap(3, 2);
  m.level = {0, 1, 2, 13, 14, 15};
  return m;
}

std::string readAll(const QString& path) {
  std::ifstream in(path.toStdString(), std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// QCOMPARE prints QByteArrays (escaping binary bytes) but not std::strings.
QByteArray qb(const std::string& s) {
  return QByteArray::fromStdString(s);
}

std::uint32_t bigEndian32(const std::string& bytes, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(bytes[at + i]);
  return v;
}

// Sum of the channel differences: a crude but sufficient "visibly different" measure.
int channelDistance(const sg::Rgb& a, const sg::Rgb& b) {
  return std::abs(a.r - b.r) + std::abs(a.g - b.g) + std::abs(a.b - b.b);
}

double luma(const sg::Rgb& c) {
  return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

sg::Rgb grey(int v) {
  const auto u = static_cast<std::uint8_t>(v);
  return sg::Rgb{u, u, u};
}

const sg::Rgb kWhite{255, 255, 255};

// Legend layout for maps narrower than 16 x 32 pixels (docs/exports.md): columns of 32 pixels, a
// pad of 32 / 4 = 8 above the swatches, swatches 32 / 2 = 16 high.
constexpr int kSwatch = 32;
constexpr int kPad = 8;
constexpr int kBox = 16;

}  // namespace

class TstExport : public QObject {
  Q_OBJECT

 private slots:
  void greyPaletteIsEvenSteps();
  void defaultPaletteIsDistinctAndDiverging();
  void pngPixelsAreNorthUp();
  void pngScaleRepeatsPixels();
  void pngUnobservedCellsAreNotSpecial();
  void pngLegendWidensNarrowMap();
  void pngOverlayDrawsWorldLines();
  void pngLegendFollowsWideMap();
  void pngFileHasSignatureAndSize();
  void pngRejectsBadInput();
  void pngBadPathThrowsWithPath();
  void rosPgmBytes();
  void rosYamlText();
  void rosNumbersRoundTrip();
  void rosQuotesUnusualImageName();
  void rosRejectsBadInput();
  void rosBadPathThrowsWithPath();
};

void TstExport::greyPaletteIsEvenSteps() {
  const sg::LevelPalette& p = sg::greyLevelPalette();
  for (int k = 0; k < 16; ++k)
    QCOMPARE(p[static_cast<std::size_t>(k)], grey(255 - 17 * k));  // 255 / 15 = 17 per level
  QCOMPARE(p[0], kWhite);
  QCOMPARE(p[15], grey(0));  // 255 - 17 * 15 = 0
}

void TstExport::defaultPaletteIsDistinctAndDiverging() {
  const sg::LevelPalette& p = sg::defaultLevelPalette();
  std::set<std::array<int, 3>> unique;
  for (const sg::Rgb& c : p) unique.insert({c.r, c.g, c.b});
  QCOMPARE(unique.size(), std::size_t{16});

  for (std::size_t k = 0; k + 1 < p.size(); ++k) {
    // The closest neighbours in the table are 11/12 and 12..15 (a channel sum of 32..37).
    QVERIFY2(channelDistance(p[k], p[k + 1]) >= 30,
             qPrintable(QString("levels %1/%2").arg(k).arg(k + 1)));
    // Lightness falls with the level, so the order also reads in greyscale.
    QVERIFY2(luma(p[k]) > luma(p[k + 1]), qPrintable(QString("level %1").arg(k)));
  }
  // Free side: light and bluish.
  QVERIFY(luma(p[0]) > 240.0);
  QVERIFY(p[0].b >= p[0].r && p[0].b >= p[0].g);
  QVERIFY(p[4].b > p[4].r + 60);
  // Unknown, levels 7 and 8 (p = 0.5 is level round(7.5) = 8): near-neutral mid greys.
  for (std::size_t k : {std::size_t{7}, std::size_t{8}}) {
    const int hi = std::max({p[k].r, p[k].g, p[k].b});
    const int lo = std::min({p[k].r, p[k].g, p[k].b});
    QVERIFY(hi - lo <= 40);
    QVERIFY(luma(p[k]) > 100.0 && luma(p[k]) < 160.0);
  }
  // Occupied side: red, ending almost black.
  QVERIFY(p[11].r > p[11].g + 80 && p[11].r > p[11].b + 80);
  QVERIFY(luma(p[15]) < 30.0);
  QVERIFY(p[15].r > p[15].b);
  // The table endpoints of docs/exports.md.
  QCOMPARE(p[0], (sg::Rgb{246, 249, 255}));
  QCOMPARE(p[7], (sg::Rgb{126, 135, 148}));
  QCOMPARE(p[8], (sg::Rgb{133, 115, 110}));
  QCOMPARE(p[15], (sg::Rgb{45, 14, 8}));
}

void TstExport::pngPixelsAreNorthUp() {
  sg::PngOptions options;
  options.palette = &sg::greyLevelPalette();
  const sg::RgbImage img = sg::renderMapImage(levelMap(), options);
  QCOMPARE(img.width, 3);
  QCOMPARE(img.height, 2);
  QCOMPARE(img.pixels.size(), std::size_t{6});
  // Image row 0 = grid row iy = 1 (levels 13 14 15); grey of level k is 255 - 17k.
  QCOMPARE(img.at(0, 0), grey(34));  // level 13: 255 - 221
  QCOMPARE(img.at(1, 0), grey(17));  // level 14: 255 - 238
  QCOMPARE(img.at(2, 0), grey(0));   // level 15: 255 - 255
  // Image row 1 = grid row iy = 0 (levels 0 1 2).
  QCOMPARE(img.at(0, 1), grey(255));  // level 0
  QCOMPARE(img.at(1, 1), grey(238));  // level 1: 255 - 17
  QCOMPARE(img.at(2, 1), grey(221));  // level 2: 255 - 34

  // The default palette (options.palette == nullptr) is used the same way.
  const sg::RgbImage coloured = sg::renderMapImage(levelMap());
  const sg::LevelPalette& p = sg::defaultLevelPalette();
  QCOMPARE(coloured.at(0, 0), p[13]);
  QCOMPARE(coloured.at(2, 0), p[15]);
  QCOMPARE(coloured.at(0, 1), p[0]);
  QCOMPARE(coloured.at(2, 1), p[2]);
}

void TstExport::pngScaleRepeatsPixels() {
  sg::PngOptions options;
  options.palette = &sg::greyLevelPalette();
  options.scale = 2;
  const sg::RgbImage img = sg::renderMapImage(levelMap(), options);
  QCOMPARE(img.width, 6);   // 3 cells x 2
  QCOMPARE(img.height, 4);  // 2 cells x 2
  // Pixel (x, y) shows cell (x / 2, 1 - y / 2).
  const int expected[2][3] = {{34, 17, 0},
                              {255, 238, 221}};  // image rows as in pngPixelsAreNorthUp
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 6; ++x) QCOMPARE(img.at(x, y), grey(expected[y / 2][x / 2]));
}

void TstExport::pngUnobservedCellsAreNotSpecial() {
  // Unobserved cells carry level 8 like any p = 0.5 cell; the picture only follows the levels.
  sg::OccupancyMap m = levelMap();
  m.observed = {1, 0, 1, 0, 1, 0};
  sg::PngOptions options;
  options.palette = &sg::greyLevelPalette();
  const sg::RgbImage a = sg::renderMapImage(m, options);
  const sg::RgbImage b = sg::renderMapImage(levelMap(), options);
  QVERIFY(a.pixels == b.pixels);
  sg::OccupancyMap empty = makeMap(2, 1);                            // all level 8, unobserved
  QCOMPARE(sg::renderMapImage(empty, options).at(1, 0), grey(119));  // 255 - 17 * 8
}

// A 10 x 10 map of 0.1 m cells from the origin at 4 pixels per cell: the world line y = 0.5 m
// from x = 0.05 to 0.95 m lands on pixel row 40 − 0.5 / 0.1 · 4 = 20 (north up) and is drawn in
// the overlay colour; a pixel two cells away keeps the palette's level-8 colour, and the legend
// strip below the map is not drawn on.
void TstExport::pngOverlayDrawsWorldLines() {
  sg::OccupancyMap map = makeMap(10, 10);
  map.spec.cellSize = 0.1;
  map.spec.origin = sg::Position(0.0, 0.0);
  sg::PngOptions o;
  o.scale = 4;
  o.lines.push_back({sg::Position(0.05, 0.5), sg::Position(0.95, 0.5)});
  o.overlayColour = sg::Rgb{1, 2, 3};
  sg::PngOptions bare;
  bare.scale = 4;
  const sg::RgbImage plain = sg::renderMapImage(map, bare);
  const sg::RgbImage drawn = sg::renderMapImage(map, o);
  // The line is anti-aliased: its centre row is the overlay colour blended with at most a few
  // percent of the level-8 background (OpenCV's LINE_AA coverage), so allow 16 levels a channel.
  const auto nearOverlay = [](sg::Rgb c) { return c.r <= 17 && c.g <= 18 && c.b <= 19; };
  QVERIFY(nearOverlay(drawn.at(20, 20)));
  QCOMPARE(drawn.at(20, 28), plain.at(20, 28));
  QCOMPARE(drawn.at(20, 28), sg::defaultLevelPalette()[8]);
  o.legend = true;
  o.lines = {{sg::Position(0.5, 0.5), sg::Position(0.5, -5.0)}};  // runs off the map's bottom
  const sg::RgbImage legend = sg::renderMapImage(map, o);
  QVERIFY(nearOverlay(legend.at(20, 30)));
  QVERIFY(!nearOverlay(legend.at(20, 41)));
}

void TstExport::pngLegendWidensNarrowMap() {
  sg::PngOptions options;
  options.legend = true;
  const sg::RgbImage img = sg::renderMapImage(levelMap(), options);
  const sg::LevelPalette& p = sg::defaultLevelPalette();
  // 16 columns of 32 pixels = 512 > the map's 3 pixels.
  QCOMPARE(img.width, 16 * kSwatch);
  // Strip = pad + swatch + pad + text + pad = 8 + 16 + 8 + text + 8, text a few pixels to ~20.
  QVERIFY2(img.height > 2 + 3 * kPad + kBox + 4 && img.height < 2 + 3 * kPad + kBox + 25,
           qPrintable(QString::number(img.height)));
  // The map itself is unchanged, top-left, with white to its right.
  QCOMPARE(img.at(0, 0), p[13]);
  QCOMPARE(img.at(2, 0), p[15]);
  QCOMPARE(img.at(0, 1), p[0]);
  QCOMPARE(img.at(2, 1), p[2]);
  for (int y = 0; y < 2; ++y)
    for (int x = 3; x < img.width; ++x) QCOMPARE(img.at(x, y), kWhite);
  // A white pad row between the map and the swatches.
  for (int x = 0; x < img.width; ++x) QCOMPARE(img.at(x, 2), kWhite);

  const int boxCentreY = 2 + kPad + kBox / 2;  // 2 map rows, the pad, half a swatch = 18
  const int textTop = 2 + kPad + kBox + kPad;  // = 34
  for (int k = 0; k < 16; ++k) {
    const int centreX = k * kSwatch + kSwatch / 2;  // 16, 48, ...
    QCOMPARE(img.at(centreX, boxCentreY), p[static_cast<std::size_t>(k)]);
    // The number below the swatch: some dark ink in the column's text band.
    bool ink = false;
    for (int y = textTop; y < img.height && !ink; ++y)
      for (int x = k * kSwatch; x < (k + 1) * kSwatch && !ink; ++x)
        ink = luma(img.at(x, y)) < 100.0;
    QVERIFY2(ink, qPrintable(QString("no label under swatch %1").arg(k)));
  }
}

void TstExport::pngLegendFollowsWideMap() {
  // 40 cells x scale 20 = 800 pixels: columns of 800 / 16 = 50, pad 50 / 4 = 12, swatch 25 high.
  sg::OccupancyMap m = makeMap(40, 2);
  sg::PngOptions options;
  options.legend = true;
  options.scale = 20;
  const sg::RgbImage img = sg::renderMapImage(m, options);
  QCOMPARE(img.width, 800);
  QVERIFY(img.height > 40 + 12 + 25 + 12 + 12);
  const sg::LevelPalette& p = sg::defaultLevelPalette();
  QCOMPARE(img.at(799, 39), p[8]);  // the map's last pixel: level 8
  for (int k = 0; k < 16; ++k)
    QCOMPARE(img.at(k * 50 + 25, 40 + 12 + 12), p[static_cast<std::size_t>(k)]);
}

void TstExport::pngFileHasSignatureAndSize() {
  QTemporaryDir dir;
  QVERIFY(dir.isValid());
  struct Case {
    sg::PngOptions options;
    int width, height;
  };
  sg::PngOptions scaled;
  scaled.scale = 2;
  sg::PngOptions legend;
  legend.legend = true;
  const int legendHeight = sg::renderMapImage(levelMap(), legend).height;
  const Case cases[] = {{{}, 3, 2}, {scaled, 6, 4}, {legend, 512, legendHeight}};
  for (const Case& c : cases) {
    const QString path = dir.filePath("map.png");
    sg::writeMapPng(levelMap(), path.toStdString(), c.options);
    const std::string bytes = readAll(path);
    QVERIFY(bytes.size() > 33);
    // PNG signature, then the IHDR chunk: length (4), "IHDR" (4), width (4), height (4).
    QCOMPARE(qb(bytes.substr(0, 8)), qb("\x89PNG\r\n\x1a\n"));
    QCOMPARE(qb(bytes.substr(12, 4)), qb("IHDR"));
    QCOMPARE(bigEndian32(bytes, 16), static_cast<std::uint32_t>(c.width));
    QCOMPARE(bigEndian32(bytes, 20), static_cast<std::uint32_t>(c.height));
    QCOMPARE(static_cast<int>(bytes[24]), 8);  // bit depth 8
    QCOMPARE(static_cast<int>(bytes[25]), 2);  // colour type 2: RGB
  }
  // The temporary file was renamed away: only the PNG is left.
  QCOMPARE(QDir(dir.path()).entryList(QDir::Files), QStringList{"map.png"});

  // The PNG encoder is chosen by the code, not by the name: a .jpg name still gets a PNG.
  const QString odd = dir.filePath("map.jpg");
  sg::writeMapPng(levelMap(), odd.toStdString());
  QCOMPARE(qb(readAll(odd).substr(0, 8)), qb("\x89PNG\r\n\x1a\n"));
}

void TstExport::pngRejectsBadInput() {
  QTemporaryDir dir;
  const std::string path = dir.filePath("bad.png").toStdString();
  sg::PngOptions zero;
  zero.scale = 0;
  QVERIFY_THROWS_EXCEPTION(std::invalid_argument, sg::writeMapPng(levelMap(), path, zero));
  QVERIFY_THROWS_EXCEPTION(std::invalid_argument, sg::renderMapImage(levelMap(), zero));
  sg::PngOptions huge;
  huge.scale = std::numeric_limits<int>::max();  // 3 * (2^31 - 1) pixels wide: refused, no overflow
  QVERIFY_THROWS_EXCEPTION(std::invalid_argument, sg::renderMapImage(levelMap(), huge));

  sg::OccupancyMap shortLayer = levelMap();
  shortLayer.level.pop_back();  // 5 entries for 6 cells
  QVERIFY_THROWS_EXCEPTION(std::invalid_argument, sg::writeMapPng(shortLayer, path));

  sg::OccupancyMap badLevel = levelMap();
  badLevel.level[3] = 16;
  QVERIFY_THROWS_EXCEPTION(std::invalid_argument, sg::writeMapPng(badLevel, path));

  QVERIFY_THROWS_EXCEPTION(std::invalid_argument, sg::writeMapPng(makeMap(0, 4), path));
  QVERIFY(!QFile::exists(QString::fromStdString(path)));
}

void TstExport::pngBadPathThrowsWithPath() {
  QTemporaryDir dir;
  const std::string path = dir.filePath("missing/map.png").toStdString();
  try {
    sg::writeMapPng(levelMap(), path);
    QFAIL("no exception");
  } catch (const std::runtime_error& e) {
    QVERIFY2(std::string(e.what()).find(path) != std::string::npos, e.what());
    QVERIFY2(std::string(e.what()).find("does not exist") != std::string::npos, e.what());
  }
}

namespace {

// The 3 x 2 map of the ROS cases, storage order (index = iy * 3 + ix):
//   iy = 0 (bottom): p 0, 0.25, 0.5
//   iy = 1 (top):    p 1, unobserved (p 0.9, ignored), 0.65
sg::OccupancyMap rosMap() {
  sg::OccupancyMap m = makeMap(3, 2);
  m.probability = {0.0, 0.25, 0.5, 1.0, 0.9, 0.65};
  m.observed = {1, 1, 1, 1, 0, 1};
  return m;
}

}  // namespace

void TstExport::rosPgmBytes() {
  QTemporaryDir dir;
  const QString base = dir.filePath("room");
  sg::writeRosMap(rosMap(), base.toStdString());
  // Header without a comment line, then the top grid row (iy = 1) first.
  const std::string expected = std::string("P5\n3 2\n255\n") +
                               std::string{
                                   '\x00',  // p 1:    255 (1 - 1) = 0
                                   '\xCD',  // never observed: 205
                                   '\x59',  // p 0.65: 255 * 0.35 = 89.25 -> 89
                                   '\xFF',  // p 0:    255 (1 - 0) = 255
                                   '\xBF',  // p 0.25: 255 * 0.75 = 191.25 -> 191
                                   '\x80',  // p 0.5:  255 * 0.5 = 127.5 -> 128 (half away from 0)
                               };
  QCOMPARE(qb(readAll(base + ".pgm")), qb(expected));
  QCOMPARE(QDir(dir.path()).entryList(QDir::Files), (QStringList{"room.pgm", "room.yaml"}));
}

void TstExport::rosYamlText() {
  QTemporaryDir dir;
  const QString base = dir.filePath("room");
  sg::writeRosMap(rosMap(), base.toStdString());
  // origin (-1.5, 0.25) and cell size 0.1 from makeMap; image is the file name only.
  const std::string expected =
      "image: room.pgm\n"
      "resolution: 0.1\n"
      "origin: [-1.5, 0.25, 0.0]\n"
      "negate: 0\n"
      "occupied_thresh: 0.65\n"
      "free_thresh: 0.196\n"
      "mode: trinary\n";
  QCOMPARE(qb(readAll(base + ".yaml")), qb(expected));

  // Writing again replaces both files.
  sg::OccupancyMap m = rosMap();
  m.observed.assign(6, 0);
  sg::writeRosMap(m, base.toStdString());
  QCOMPARE(qb(readAll(base + ".pgm")), qb(std::string("P5\n3 2\n255\n") + std::string(6, '\xCD')));
  QCOMPARE(QDir(dir.path()).entryList(QDir::Files), (QStringList{"room.pgm", "room.yaml"}));
}

void TstExport::rosNumbersRoundTrip() {
  QTemporaryDir dir;
  const QString base = dir.filePath("n");
  sg::OccupancyMap m = rosMap();
  m.spec.origin = sg::Position(0.1 + 0.2, 2.0);  // 0.1 + 0.2 is 0.30000000000000004 in binary
  m.spec.cellSize = 1e-5;
  sg::writeRosMap(m, base.toStdString());
  const std::string yaml = readAll(base + ".yaml");
  // Shortest round-trip text, with a decimal point added where to_chars gives none ("2", "1e-05")
  // so that YAML 1.1 readers take them as floats.
  QVERIFY2(yaml.find("resolution: 1.0e-05\n") != std::string::npos, yaml.c_str());
  QVERIFY2(yaml.find("origin: [0.30000000000000004, 2.0, 0.0]\n") != std::string::npos,
           yaml.c_str());
  QCOMPARE(std::stod("0.30000000000000004"), 0.1 + 0.2);
}

void TstExport::rosQuotesUnusualImageName() {
  QTemporaryDir dir;
  const QString base = dir.filePath("my map");
  sg::writeRosMap(rosMap(), base.toStdString());
  const std::string yaml = readAll(base + ".yaml");
  QVERIFY2(yaml.rfind("image: \"my map.pgm\"\n", 0) == 0, yaml.c_str());
  QVERIFY(QFile::exists(base + ".pgm"));
}

void TstExport::rosRejectsBadInput() {
  QTemporaryDir dir;
  const std::string base = dir.filePath("bad").toStdString();
  sg::OccupancyMap shortProbability = rosMap();
  shortProbability.probability.resize(5);
  QVERIFY_THROWS_EXCEPTION(std::invalid_argument, sg::writeRosMap(shortProbability, base));
  sg::OccupancyMap shortObserved = rosMap();
  shortObserved.observed.resize(7);
  QVERIFY_THROWS_EXCEPTION(std::invalid_argument, sg::writeRosMap(shortObserved, base));
  sg::OccupancyMap nan = rosMap();
  nan.probability[2] = std::numeric_limits<double>::quiet_NaN();
  QVERIFY_THROWS_EXCEPTION(std::invalid_argument, sg::writeRosMap(nan, base));
  QVERIFY(QDir(dir.path()).entryList(QDir::Files).isEmpty());
}

void TstExport::rosBadPathThrowsWithPath() {
  QTemporaryDir dir;
  const std::string base = dir.filePath("missing/room").toStdString();
  try {
    sg::writeRosMap(rosMap(), base);
    QFAIL("no exception");
  } catch (const std::runtime_error& e) {
    QVERIFY2(std::string(e.what()).find(base + ".pgm") != std::string::npos, e.what());
  }
}

QTEST_GUILESS_MAIN(TstExport)
#include "tst_export.moc"
