// SPDX-License-Identifier: BSD-3-Clause
// Reference maps: the sonargrid-reference JSON reader and writer, the ArMap and ROS map_server
// imports, the actual position grid (supercover) and the ideal map. Fixtures are in
// tests/data/reference/ (small.map is written by hand in ArMap's layout; box.* is one 4 x 3
// map_server image as P5, P2 and PNG). Bad input must give a LogError naming file, line and field,
// never a crash: a table of bad files and a mutation sweep check that.

#include <QTemporaryDir>
#include <QtTest>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <iterator>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "sonargrid/export/map_export.h"
#include "sonargrid/metrics/ideal_map.h"
#include "sonargrid/reference/actual_position_grid.h"
#include "sonargrid/reference/armap_reader.h"
#include "sonargrid/reference/grey_image.h"
#include "sonargrid/reference/read_reference.h"
#include "sonargrid/reference/reference_json.h"
#include "sonargrid/reference/ros_map_reader.h"

namespace {

const std::string kData = SONARGRID_TEST_DATA "/reference/";

using Cells = std::set<std::pair<int, int>>;

Cells marked(const sg::GridSpec& spec, const std::vector<std::uint8_t>& cells) {
  Cells out;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (cells[i] != 0) {
      const sg::CellIndex c = spec.fromLinear(i);
      out.emplace(c.x(), c.y());
    }
  }
  return out;
}

QString cellsText(const Cells& cells) {
  QStringList parts;
  for (const auto& [x, y] : cells) parts << QString("(%1,%2)").arg(x).arg(y);
  return parts.join(' ');
}

sg::GridSpec unitGrid(int w, int h) {
  sg::GridSpec s;
  s.origin = sg::Position(0.0, 0.0);
  s.cellSize = 1.0;
  s.width = w;
  s.height = h;
  return s;
}

void writeFile(const QString& path, const std::string& bytes) {
  std::ofstream out(path.toStdString(), std::ios::binary);
  out << bytes;
}

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

const char* kExample =
    R"({"format": "sonargrid-reference", "version": 1, "units": "m", "objects": [{"name": "box", "closed": true, "corners": [[1.0, 1.0], [1.5, 1.0], [1.5, 1.4], [1.0, 1.4]]}]})";

// The valid document that the bad-JSON rows below start from, one key per line:
//   1 {
//   2   "format": "sonargrid-reference",
//   3   "version": 1,
//   4   "units": "m",
//   5   "objects": [
//   6     {"name": "a", "closed": false, "corners": [[0, 0], [1, 0]]},
//   7     {"name": "b", "closed": true, "corners": [[0, 0], [1, 0], [1, 1]]}
//   8   ]
//   9 }
std::string document(
    const std::string& format = "\"sonargrid-reference\"", const std::string& version = "1",
    const std::string& units = "\"m\"",
    const std::string& first = R"({"name": "a", "closed": false, "corners": [[0, 0], [1, 0]]})",
    const std::string& second =
        R"({"name": "b", "closed": true, "corners": [[0, 0], [1, 0], [1, 1]]})") {
  return "{\n  \"format\": " + format + ",\n  \"version\": " + version +
         ",\n  \"units\": " + units + ",\n  \"objects\": [\n    " + first + ",\n    " + second +
         "\n  ]\n}\n";
}

}  // namespace

class TstReference : public QObject {
  Q_OBJECT

 private slots:
  void jsonReadsTheIssueExample();
  void jsonKeepsUnitAndNumbersOnSave();
  void jsonFileRoundTrip();
  void jsonReadsBundledRoom();
  void jsonRejectsBadFiles_data();
  void jsonRejectsBadFiles();
  void jsonWriterRefusesWhatItCannotHold();
  void armapReadsLines();
  void armapToleratesCrlfAndBom();
  void armapRejectsBadFiles_data();
  void armapRejectsBadFiles();
  void rosReadsEveryImageKind_data();
  void rosReadsEveryImageKind();
  void rosAsReference();
  void rosAsBuiltMap();
  void rosNegate();
  void rosExportRoundTrip();
  void rosRejectsBadFiles_data();
  void rosRejectsBadFiles();
  void readReferenceDispatches();
  void readersSurviveMutations();
  void supercover_data();
  void supercover();
  void supercoverOnRoundedBoundary();
  void apgOfArmap();
  void rasterResampling_data();
  void rasterResampling();
  void idealMap_data();
  void idealMap();
  void idealMapOfRosReference();
};

// ---------------------------------------------------------------------------------------------
// JSON

void TstReference::jsonReadsTheIssueExample() {
  const sg::ReferenceMap map = sg::parseReferenceJson(kExample, "example.json");
  QCOMPARE(map.unit, sg::LengthUnit::Metre);
  QCOMPARE(map.objects.size(), std::size_t{1});
  const sg::ReferenceObject& box = map.objects[0];
  QCOMPARE(box.name, std::string("box"));
  QVERIFY(box.closed);
  QCOMPARE(box.corners.size(), std::size_t{4});
  QCOMPARE(box.corners[2], Eigen::Vector2d(1.5, 1.4));
  // Closed: 4 edges, the last from (1.0, 1.4) back to (1.0, 1.0).
  const auto edges = map.edgesMetres(box);
  QCOMPARE(edges.size(), std::size_t{4});
  QCOMPARE(edges[3].first, sg::Position(1.0, 1.4));
  QCOMPARE(edges[3].second, sg::Position(1.0, 1.0));
}

void TstReference::jsonKeepsUnitAndNumbersOnSave() {
  const sg::ReferenceMap map = sg::readReferenceJson(kData + "box_cm.json");
  QCOMPARE(map.unit, sg::LengthUnit::Centimetre);
  QCOMPARE(map.objects.size(), std::size_t{2});
  QVERIFY(!map.objects[0].closed);
  QCOMPARE(map.objects[0].corners.size(), std::size_t{5});
  // 40.5 cm = 0.405 m; 200 cm = 2 m.
  QCOMPARE(map.cornerMetres(map.objects[1], 0), sg::Position(1.0, 0.405));
  QCOMPARE(map.cornerMetres(map.objects[0], 2), sg::Position(2.0, 1.2));
  // Saved in centimetres with the numbers as typed (integers without a fraction).
  const std::string expected =
      "{\n"
      "  \"format\": \"sonargrid-reference\",\n"
      "  \"version\": 1,\n"
      "  \"units\": \"cm\",\n"
      "  \"objects\": [\n"
      "    {\"name\": \"walls\", \"closed\": false, \"corners\": [[0, 0], [200, 0], [200, 120], "
      "[0, 120], [0, 0]]},\n"
      "    {\"name\": \"box\", \"closed\": true, \"corners\": [[100, 40.5], [150, 40.5], [150, "
      "80.25], [100, 80.25]]}\n"
      "  ]\n"
      "}\n";
  QCOMPARE(QByteArray::fromStdString(sg::referenceJsonText(map)),
           QByteArray::fromStdString(expected));
}

void TstReference::jsonFileRoundTrip() {
  QTemporaryDir dir;
  QVERIFY(dir.isValid());
  sg::ReferenceMap map;
  map.unit = sg::LengthUnit::Millimetre;
  sg::ReferenceObject o;
  o.name = "pillar \"A\" \xC3\xA9";  // a quote and a UTF-8 é survive
  o.closed = true;
  // Numbers that need every digit to round-trip.
  o.corners = {{0.1, 0.2}, {1.0 / 3.0, -2.5e-7}, {123456789.0, 1e21}};
  map.objects.push_back(o);
  const std::string path = dir.filePath("ref.json").toStdString();
  sg::writeReferenceJson(map, path);
  const sg::ReferenceMap back = sg::readReferenceJson(path);
  QCOMPARE(back.unit, sg::LengthUnit::Millimetre);
  QCOMPARE(back.objects.size(), std::size_t{1});
  QCOMPARE(back.objects[0].name, o.name);
  QVERIFY(back.objects[0].closed);
  for (std::size_t k = 0; k < o.corners.size(); ++k)
    QCOMPARE(back.objects[0].corners[k], o.corners[k]);
  // Saving what was read gives the same bytes.
  QCOMPARE(sg::referenceJsonText(back), readFile(path));

  // A missing directory is reported with the path.
  try {
    sg::writeReferenceJson(map, dir.filePath("no/such/dir/ref.json").toStdString());
    QFAIL("expected std::runtime_error");
  } catch (const std::runtime_error& e) {
    QVERIFY2(std::string(e.what()).find("no/such/dir/ref.json") != std::string::npos, e.what());
  }
}

void TstReference::jsonReadsBundledRoom() {
  const sg::ReferenceMap room = sg::readReferenceJson(SONARGRID_DATASETS "/room/room.json");
  QCOMPARE(room.objects.size(), std::size_t{3});
  QCOMPARE(room.objects[0].name, std::string("walls"));
  QCOMPARE(room.objects[2].name, std::string("pole"));
  QCOMPARE(room.objects[0].corners[2], Eigen::Vector2d(6.0, 4.0));
}

void TstReference::jsonRejectsBadFiles_data() {
  QTest::addColumn<QByteArray>("text");
  QTest::addColumn<int>("line");
  QTest::addColumn<QString>("field");
  QTest::addColumn<QString>("message");  // a part of the message

  const auto row = [](const char* name, const std::string& text, int line, const char* field,
                      const char* message) {
    QTest::newRow(name) << QByteArray::fromStdString(text) << line << field << message;
  };
  row("empty", "", 0, "", "empty");
  row("blank", " \n\t\n", 0, "", "empty");
  row("truncated", "{\n  \"format\": ", 2, "", "not valid JSON");
  row("not JSON", "hello", 1, "", "not valid JSON");
  row("binary", std::string("\x00\xff\xfe", 3), 1, "", "not valid JSON");
  row("trailing garbage", document() + "x", 10, "", "not valid JSON");
  row("number overflow", document("\"sonargrid-reference\"", "1e999"), 3, "", "not valid JSON");
  row("invalid UTF-8", document("\"sonargrid-reference\"", "1", "\"\xff\""), 4, "",
      "not valid JSON");
  row("an array", "[]", 1, "", "expected a JSON object");
  row("wrong format", document("\"geojson\""), 2, "format", "expected \"sonargrid-reference\"");
  row("format not a string", document("1"), 2, "format", "expected \"sonargrid-reference\"");
  row("version 2", document("\"sonargrid-reference\"", "2"), 3, "version", "reads version 1");
  row("version a string", document("\"sonargrid-reference\"", "\"1\""), 3, "version",
      "reads version 1");
  row("unit km", document("\"sonargrid-reference\"", "1", "\"km\""), 4, "units",
      "\"m\", \"cm\" or \"mm\"");
  row("missing objects", "{\"format\": \"sonargrid-reference\", \"version\": 1, \"units\": \"m\"}",
      1, "objects", "missing");
  row("unknown key",
      "{\"format\": \"sonargrid-reference\", \"version\": 1, \"units\": \"m\",\n\"object\": []}", 2,
      "object", "unknown key");
  row("repeated key", "{\"format\": \"sonargrid-reference\",\n\"format\": \"sonargrid-reference\"}",
      2, "", "appears twice");
  row("closed with 2 corners", document(), 0, "", "");  // placeholder replaced below
  row("open with 1 corner",
      document("\"sonargrid-reference\"", "1", "\"m\"",
               R"({"name": "a", "closed": false, "corners": [[0, 0]]})"),
      6, "objects[0].corners", "at least 2 corners");
  row("corner of 3 numbers",
      document("\"sonargrid-reference\"", "1", "\"m\"",
               R"({"name": "a", "closed": false, "corners": [[0, 0], [1, 0, 2]]})"),
      6, "objects[0].corners[1]", "two numbers");
  row("corner of strings",
      document("\"sonargrid-reference\"", "1", "\"m\"",
               R"({"name": "a", "closed": false, "corners": [["0", "0"], [1, 0]]})"),
      6, "objects[0].corners[0]", "two numbers");
  row("empty name",
      document("\"sonargrid-reference\"", "1", "\"m\"",
               R"({"name": "", "closed": false, "corners": [[0, 0], [1, 0]]})"),
      6, "objects[0].name", "non-empty string");
  row("closed not a boolean",
      document("\"sonargrid-reference\"", "1", "\"m\"",
               R"({"name": "a", "closed": 1, "corners": [[0, 0], [1, 0]]})"),
      6, "objects[0].closed", "true or false");
  row("repeated name",
      document("\"sonargrid-reference\"", "1", "\"m\"",
               R"({"name": "a", "closed": false, "corners": [[0, 0], [1, 0]]})",
               R"({"name": "a", "closed": false, "corners": [[0, 0], [1, 0]]})"),
      7, "objects[1].name", "already used by objects[0]");
  row("unknown object key",
      document("\"sonargrid-reference\"", "1", "\"m\"",
               R"({"name": "a", "closed": false, "corners": [[0, 0], [1, 0]], "height": 2})"),
      6, "objects[0].height", "unknown key");
  row("object not an object", document("\"sonargrid-reference\"", "1", "\"m\"", "[1, 2]"), 6,
      "objects[0]", "expected an object");
}

void TstReference::jsonRejectsBadFiles() {
  QFETCH(QByteArray, text);
  QFETCH(int, line);
  QFETCH(QString, field);
  QFETCH(QString, message);
  std::string input = text.toStdString();
  if (QByteArray(QTest::currentDataTag()) == "closed with 2 corners") {
    input = document("\"sonargrid-reference\"", "1", "\"m\"",
                     R"({"name": "a", "closed": false, "corners": [[0, 0], [1, 0]]})",
                     R"({"name": "b", "closed": true, "corners": [[0, 0], [1, 0]]})");
    line = 7;
    field = "objects[1].corners";
    message = "a closed object needs at least 3 corners";
  }
  try {
    sg::parseReferenceJson(input, "bad.json");
    QFAIL("expected a LogError");
  } catch (const sg::LogError& e) {
    QCOMPARE(QString::fromStdString(e.file()), QString("bad.json"));
    QCOMPARE(static_cast<int>(e.line()), line);
    QCOMPARE(QString::fromStdString(e.field()), field);
    QVERIFY2(QString::fromStdString(e.message()).contains(message), e.what());
  }
}

void TstReference::jsonWriterRefusesWhatItCannotHold() {
  sg::ReferenceMap withRaster = sg::rosMapAsReference(sg::readRosMap(kData + "box.yaml"));
  QVERIFY_THROWS_EXCEPTION(std::invalid_argument, sg::referenceJsonText(withRaster));

  sg::ReferenceMap twice;
  sg::ReferenceObject o{"wall", false, {{0, 0}, {1, 0}}};
  twice.objects = {o, o};
  QVERIFY_THROWS_EXCEPTION(std::invalid_argument, sg::referenceJsonText(twice));

  sg::ReferenceMap bad;
  bad.objects = {sg::ReferenceObject{"tri", true, {{0, 0}, {1, 0}}}};  // closed needs 3
  QVERIFY_THROWS_EXCEPTION(std::invalid_argument, sg::referenceJsonText(bad));
  bad.objects = {sg::ReferenceObject{"nan", false, {{0, 0}, {std::nan(""), 0}}}};
  QVERIFY_THROWS_EXCEPTION(std::invalid_argument, sg::referenceJsonText(bad));
}

// ---------------------------------------------------------------------------------------------
// ArMap

void TstReference::armapReadsLines() {
  const sg::ReferenceMap map = sg::readArMap(kData + "small.map");
  // NumLines says 99; the LINES section holds 3 segments (a blank line between them is skipped)
  // and the DATA points are not objects.
  QCOMPARE(map.objects.size(), std::size_t{3});
  QCOMPARE(map.unit, sg::LengthUnit::Millimetre);
  QCOMPARE(map.objects[0].name, std::string("line 1"));
  QCOMPARE(map.objects[2].name, std::string("line 3"));
  for (const sg::ReferenceObject& o : map.objects) {
    QVERIFY(!o.closed);
    QCOMPARE(o.corners.size(), std::size_t{2});
  }
  QCOMPARE(map.objects[1].corners[0], Eigen::Vector2d(2000, 0));
  QCOMPARE(map.objects[1].corners[1], Eigen::Vector2d(2000, 1500));
  QCOMPARE(map.cornerMetres(map.objects[2], 0), sg::Position(-0.2, 0.1));  // -200 mm, 100 mm
  // Saved as reference JSON it stays in whole millimetres.
  const std::string json = sg::referenceJsonText(map);
  QVERIFY(json.find("\"units\": \"mm\"") != std::string::npos);
  QVERIFY(
      json.find(
          "{\"name\": \"line 3\", \"closed\": false, \"corners\": [[-200, 100], [-200, 1200]]}") !=
      std::string::npos);
}

void TstReference::armapToleratesCrlfAndBom() {
  const std::string text =
      "\xEF\xBB\xBF"
      "2D-Map-Ex2\r\nNumLines: 1\r\nLINES\r\n  10 20   30 40 \r\nDATA\r\n1 2\r\n";
  const sg::ReferenceMap map = sg::parseArMap(text, "crlf.map");
  QCOMPARE(map.objects.size(), std::size_t{1});
  QCOMPARE(map.objects[0].corners[1], Eigen::Vector2d(30, 40));
}

void TstReference::armapRejectsBadFiles_data() {
  QTest::addColumn<QByteArray>("text");
  QTest::addColumn<int>("line");
  QTest::addColumn<QString>("field");
  QTest::addColumn<QString>("message");
  QTest::newRow("empty") << QByteArray("") << 0 << ""
                         << "empty";
  QTest::newRow("not an ArMap") << QByteArray("P5\n4 3\n255\n") << 1 << "magic"
                                << "2D-Map";
  QTest::newRow("no LINES") << QByteArray("2D-Map\nNumLines: 0\nDATA\n1 2\n") << 0 << "LINES"
                            << "no LINES";
  QTest::newRow("LINES empty") << QByteArray("2D-Map\nLINES\nDATA\n") << 0 << "LINES"
                               << "no segment";
  QTest::newRow("three fields") << QByteArray("2D-Map\nLINES\n0 0 10 10\n0 0 10\n") << 4 << "y2"
                                << "missing";
  QTest::newRow("five fields") << QByteArray("2D-Map\nLINES\n0 0 10 10 5\n") << 3 << "LINES"
                               << "too many";
  QTest::newRow("not an integer") << QByteArray("2D-Map\nLINES\n0 0 1.5 10\n") << 3 << "x2"
                                  << "integer";
  QTest::newRow("a word") << QByteArray("2D-Map\nLINES\n0 zero 1 10\n") << 3 << "y1"
                          << "integer";
  QTest::newRow("header in LINES") << QByteArray("2D-Map\nLINES\nNumLines: 1\n") << 3 << "x2"
                                   << "integer";
  QTest::newRow("beyond 1000 km") << QByteArray("2D-Map\nLINES\n0 0 1000000001 0\n") << 3 << "x2"
                                  << "beyond";
  QTest::newRow("64-bit overflow")
      << QByteArray("2D-Map\nLINES\n0 0 99999999999999999999 0\n") << 3 << "x2"
      << "integer";
}

void TstReference::armapRejectsBadFiles() {
  QFETCH(QByteArray, text);
  QFETCH(int, line);
  QFETCH(QString, field);
  QFETCH(QString, message);
  try {
    sg::parseArMap(text.toStdString(), "bad.map");
    QFAIL("expected a LogError");
  } catch (const sg::LogError& e) {
    QCOMPARE(QString::fromStdString(e.file()), QString("bad.map"));
    QCOMPARE(static_cast<int>(e.line()), line);
    QCOMPARE(QString::fromStdString(e.field()), field);
    QVERIFY2(QString::fromStdString(e.message()).contains(message), e.what());
  }
}

// ---------------------------------------------------------------------------------------------
// ROS map_server

void TstReference::rosReadsEveryImageKind_data() {
  QTest::addColumn<QString>("yaml");
  QTest::newRow("P5") << "box.yaml";
  QTest::newRow("P2, quoted name, spaces, mode") << "box_ascii.yaml";
  QTest::newRow("PNG") << "box_png.yaml";
}

void TstReference::rosReadsEveryImageKind() {
  QFETCH(QString, yaml);
  const sg::RosMap map = sg::readRosMap(kData + yaml.toStdString());
  QCOMPARE(map.spec.origin, sg::Position(-1.0, 2.0));
  QCOMPARE(map.spec.cellSize, 0.5);
  QCOMPARE(map.spec.width, 4);
  QCOMPARE(map.spec.height, 3);
  QVERIFY(!map.negate);
  QCOMPARE(map.occupiedThresh, 0.65);
  QCOMPARE(map.freeThresh, 0.196);
  // The image, top row first:   0 254 254 205 / 254 0 128 205 / 254 254 0 100.
  // Image row 0 is the grid's top row iy = 2; row 2 is iy = 0.
  const std::vector<std::uint8_t> expected{254, 254, 0,   100,   // iy = 0
                                           254, 0,   128, 205,   // iy = 1
                                           0,   254, 254, 205};  // iy = 2
  QCOMPARE(map.pixels, expected);
}

void TstReference::rosAsReference() {
  const sg::ReferenceMap ref = sg::rosMapAsReference(sg::readRosMap(kData + "box.yaml"));
  QVERIFY(ref.objects.empty());
  QVERIFY(ref.raster.has_value());
  using C = sg::RasterCell;
  // p = (255 − v) / 255: 0 → 1 (obstacle, > 0.65); 254 → 0.004 (free, < 0.196);
  // 205 → 0.196 (unknown: 50/255 = 0.19608 is not below 0.196); 128 → 0.498 and 100 → 0.608
  // (unknown, between the thresholds).
  const std::vector<C> expected{C::Free,     C::Free,     C::Obstacle, C::Unknown,   // iy = 0
                                C::Free,     C::Obstacle, C::Unknown,  C::Unknown,   // iy = 1
                                C::Obstacle, C::Free,     C::Free,     C::Unknown};  // iy = 2
  QVERIFY(ref.raster->cells == expected);
}

void TstReference::rosAsBuiltMap() {
  const sg::OccupancyMap m = sg::rosMapAsBuiltMap(sg::readRosMap(kData + "box.yaml"));
  QCOMPARE(m.spec.width, 4);
  // Cell (2, 0), pixel 0: p = 1, CV = 15, filled.
  QCOMPARE(m.probability[2], 1.0);
  QCOMPARE(int(m.level[2]), 15);
  QCOMPARE(int(m.filled[2]), 1);
  // Cell (0, 0), pixel 254: p = 1/255 = 0.0039, CV = round(0.059) = 0, not filled.
  QCOMPARE(m.probability[0], 1.0 / 255.0);
  QCOMPARE(int(m.level[0]), 0);
  QCOMPARE(int(m.filled[0]), 0);
  // Cell (2, 1), pixel 128: p = 127/255 = 0.498, CV = round(7.47) = 7, filled (CV > 0).
  QCOMPARE(m.probability[6], 127.0 / 255.0);
  QCOMPARE(int(m.level[6]), 7);
  QCOMPARE(int(m.filled[6]), 1);
  // Cell (3, 0), pixel 100: p = 155/255 = 0.608, CV = round(9.12) = 9.
  QCOMPARE(int(m.level[3]), 9);
  // Cells (3, 1) and (3, 2), pixel 205: never observed, p 0.5, level 8, not filled.
  for (std::size_t i : {std::size_t{7}, std::size_t{11}}) {
    QCOMPARE(int(m.observed[i]), 0);
    QCOMPARE(m.probability[i], 0.5);
    QCOMPARE(int(m.level[i]), 8);
    QCOMPARE(int(m.filled[i]), 0);
  }
  QCOMPARE(std::count(m.observed.begin(), m.observed.end(), std::uint8_t{1}), 10L);
}

void TstReference::rosNegate() {
  // negate 1: p = v / 255. Pixel 0 (cell (2, 0)) is now free, 254 is p = 0.996.
  const sg::RosMap map = sg::readRosMap(kData + "box_negate.yaml");
  QVERIFY(map.negate);
  QCOMPARE(map.occupancy(2), 0.0);
  QCOMPARE(map.occupancy(0), 254.0 / 255.0);
  // 205 is map_saver's unknown only after negation: raw 205 becomes 50, an ordinary value here.
  QVERIFY(!map.unknownPixel(7));
  const sg::ReferenceMap ref = sg::rosMapAsReference(map);
  QVERIFY(ref.raster->cells[2] == sg::RasterCell::Free);
  QVERIFY(ref.raster->cells[0] == sg::RasterCell::Obstacle);
}

void TstReference::rosExportRoundTrip() {
  // A map written by writeRosMap reads back on the same grid, with p within half a grey step.
  sg::OccupancyMap m;
  m.spec.origin = sg::Position(-1.25, 0.5);
  m.spec.cellSize = 0.05;
  m.spec.width = 7;
  m.spec.height = 5;
  const std::size_t n = m.spec.cellCount();
  m.probability.resize(n);
  m.native.assign(n, 0.0);
  m.level.resize(n);
  m.filled.resize(n);
  m.observed.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    m.probability[i] = static_cast<double>(i) / static_cast<double>(n - 1);
    m.observed[i] = i % 5 == 3 ? 0 : 1;
    if (m.observed[i] == 0) m.probability[i] = 0.5;
    m.level[i] = sg::levelOfProbability(m.probability[i]);
    m.filled[i] = m.probability[i] > 0.5 ? 1 : 0;
  }
  QTemporaryDir dir;
  const std::string base = dir.filePath("built").toStdString();
  sg::writeRosMap(m, base);
  const sg::OccupancyMap back = sg::rosMapAsBuiltMap(sg::readRosMap(base + ".yaml"));
  QCOMPARE(back.spec.width, m.spec.width);
  QCOMPARE(back.spec.height, m.spec.height);
  QVERIFY(std::abs(back.spec.origin.x() - m.spec.origin.x()) < 1e-12);
  QVERIFY(std::abs(back.spec.origin.y() - m.spec.origin.y()) < 1e-12);
  QCOMPARE(back.observed, m.observed);
  for (std::size_t i = 0; i < n; ++i) {
    if (m.observed[i] == 0) continue;
    // 205 is reserved for "unknown", so p = 50/255 would be misread; the ramp avoids it:
    // i/34 is never within 1/510 of 50/255.
    QVERIFY2(std::abs(back.probability[i] - m.probability[i]) <= 0.5 / 255.0 + 1e-12,
             qPrintable(QString::number(i)));
  }
}

void TstReference::rosRejectsBadFiles_data() {
  QTest::addColumn<QByteArray>("yaml");
  QTest::addColumn<QByteArray>("image");  // written as img.pgm beside the YAML
  QTest::addColumn<QString>("file");      // "yaml" or "image"
  QTest::addColumn<int>("line");
  QTest::addColumn<QString>("field");
  QTest::addColumn<QString>("message");

  const QByteArray pgm("P5\n2 1\n255\n\x00\xfe", 13);
  const QByteArray good(
      "image: img.pgm\nresolution: 0.1\norigin: [0.0, 0.0, 0.0]\nnegate: 0\noccupied_thresh: "
      "0.65\nfree_thresh: 0.196\n");
  auto replace = [&](const char* from, const char* to) {
    QByteArray y = good;
    return y.replace(from, to);
  };
  QTest::newRow("empty") << QByteArray() << pgm << "yaml" << 0 << "image"
                         << "missing";
  QTest::newRow("no resolution") << replace("resolution: 0.1\n", "") << pgm << "yaml" << 0
                                 << "resolution"
                                 << "missing";
  QTest::newRow("negative resolution")
      << replace("0.1", "-0.1") << pgm << "yaml" << 2 << "resolution"
      << "(0, 1000]";
  QTest::newRow("resolution a word") << replace("0.1", "fine") << pgm << "yaml" << 2 << "resolution"
                                     << "a number";
  QTest::newRow("origin of two") << replace("[0.0, 0.0, 0.0]", "[0.0, 0.0]") << pgm << "yaml" << 3
                                 << "origin"
                                 << "[x, y, yaw]";
  QTest::newRow("origin a number")
      << replace("[0.0, 0.0, 0.0]", "0.0") << pgm << "yaml" << 3 << "origin"
      << "[x, y, yaw]";
  QTest::newRow("rotated") << replace("[0.0, 0.0, 0.0]", "[0.0, 0.0, 0.5]") << pgm << "yaml" << 3
                           << "origin"
                           << "rotated";
  QTest::newRow("negate 2") << replace("negate: 0", "negate: 2") << pgm << "yaml" << 4 << "negate"
                            << "0 or 1";
  QTest::newRow("occupied 1.5") << replace("0.65", "1.5") << pgm << "yaml" << 5 << "occupied_thresh"
                                << "[0, 1]";
  QTest::newRow("free above occupied")
      << replace("0.196", "0.7") << pgm << "yaml" << 6 << "free_thresh"
      << "occupied_thresh";
  QTest::newRow("raw mode") << good + "mode: raw\n"
                            << pgm << "yaml" << 7 << "mode"
                            << "not supported";
  QTest::newRow("repeated key") << good + "negate: 1\n"
                                << pgm << "yaml" << 7 << "negate"
                                << "given twice";
  QTest::newRow("nested") << good + "  deeper: 1\n"
                          << pgm << "yaml" << 7 << ""
                          << "nested";
  QTest::newRow("no colon") << good + "just words\n"
                            << pgm << "yaml" << 7 << ""
                            << "key: value";
  QTest::newRow("unterminated quote")
      << replace("img.pgm", "\"img.pgm") << pgm << "yaml" << 1 << "image"
      << "unterminated";
  QTest::newRow("missing image") << replace("img.pgm", "nothing.pgm") << pgm << "image" << 0 << ""
                                 << "cannot open";
  QTest::newRow("truncated P5") << good << QByteArray("P5\n2 1\n255\n\x00", 12) << "image" << 0
                                << "pixels"
                                << "ends after 1 of 2";
  QTest::newRow("16-bit PGM") << good << QByteArray("P5\n2 1\n65535\n\x00\x00\x00\x00", 16)
                              << "image" << 3 << "maxval"
                              << "16-bit";
  QTest::newRow("P2 value above maxval")
      << good << QByteArray("P2\n2 1\n15\n3 16\n") << "image" << 4 << "pixels"
      << "above 15";
  QTest::newRow("P2 short") << good << QByteArray("P2\n2 1\n255\n3\n") << "image" << 5 << "pixels"
                            << "ends after 1 of 2";
  QTest::newRow("zero width") << good << QByteArray("P5\n0 1\n255\n") << "image" << 2 << "width"
                              << "at least 1";
  QTest::newRow("huge") << good << QByteArray("P5\n100000 100000\n255\n") << "image" << 2 << "width"
                        << "pixels";
  QTest::newRow("not an image") << good << QByteArray("GIF89a nonsense") << "image" << 0 << "image"
                                << "cannot decode";
}

void TstReference::rosRejectsBadFiles() {
  QFETCH(QByteArray, yaml);
  QFETCH(QByteArray, image);
  QFETCH(QString, file);
  QFETCH(int, line);
  QFETCH(QString, field);
  QFETCH(QString, message);
  QTemporaryDir dir;
  writeFile(dir.filePath("map.yaml"), yaml.toStdString());
  writeFile(dir.filePath("img.pgm"), image.toStdString());
  try {
    sg::readRosMap(dir.filePath("map.yaml").toStdString());
    QFAIL("expected a LogError");
  } catch (const sg::LogError& e) {
    const QString f = QString::fromStdString(e.file());
    QVERIFY2(f.endsWith(file == "yaml" ? "map.yaml"
                                       : (QTest::currentDataTag() == QByteArray("missing image")
                                              ? "nothing.pgm"
                                              : "img.pgm")),
             e.what());
    QCOMPARE(static_cast<int>(e.line()), line);
    QCOMPARE(QString::fromStdString(e.field()), field);
    QVERIFY2(QString::fromStdString(e.message()).contains(message), e.what());
  }
}

void TstReference::readReferenceDispatches() {
  QCOMPARE(sg::readReference(kData + "box_cm.json").objects.size(), std::size_t{2});
  QCOMPARE(sg::readReference(kData + "small.map").objects.size(), std::size_t{3});
  QVERIFY(sg::readReference(kData + "box.yaml").raster.has_value());
  // Another name: sniffed from the first bytes.
  QTemporaryDir dir;
  writeFile(dir.filePath("ref.txt"), kExample);
  writeFile(dir.filePath("walls.lines"), "2D-Map\nLINES\n0 0 10 0\n");
  writeFile(dir.filePath("other.txt"), "hello");
  QCOMPARE(sg::readReference(dir.filePath("ref.txt").toStdString()).objects.size(), std::size_t{1});
  QCOMPARE(sg::readReference(dir.filePath("walls.lines").toStdString()).objects.size(),
           std::size_t{1});
  QVERIFY_THROWS_EXCEPTION(sg::LogError,
                           sg::readReference(dir.filePath("other.txt").toStdString()));
  QVERIFY_THROWS_EXCEPTION(sg::LogError,
                           sg::readReference(dir.filePath("missing.json").toStdString()));
  QVERIFY_THROWS_EXCEPTION(sg::LogError,
                           sg::readReference(dir.path().toStdString()));  // a directory
}

void TstReference::readersSurviveMutations() {
  // Every prefix of each fixture and every single-byte change from a small set either reads or
  // throws LogError: never another exception, a crash or a hang.
  struct Case {
    std::string text;
    std::function<void(const std::string&)> read;
  };
  QTemporaryDir dir;
  const std::string yamlPath = dir.filePath("m.yaml").toStdString();
  writeFile(dir.filePath("box.pgm"), readFile(kData + "box.pgm"));
  const std::vector<Case> cases{
      {readFile(kData + "box_cm.json"),
       [](const std::string& t) { sg::parseReferenceJson(t, "m.json"); }},
      {readFile(kData + "small.map"), [](const std::string& t) { sg::parseArMap(t, "m.map"); }},
      {readFile(kData + "box.pgm"), [](const std::string& t) { sg::parsePgm(t, "m.pgm"); }},
      {readFile(kData + "box_ascii.pgm"), [](const std::string& t) { sg::parsePgm(t, "m.pgm"); }},
      {readFile(kData + "box.yaml"),
       [&](const std::string& t) {
         writeFile(QString::fromStdString(yamlPath), t);
         sg::readRosMap(yamlPath);
       }},
  };
  // PNG decoding is OpenCV's (libpng's): a few corruptions stand for the sweep, which would fill
  // the log with libpng's own messages.
  const std::string png = readFile(kData + "box.png");
  writeFile(QString::fromStdString(yamlPath), readFile(kData + "box_png.yaml"));
  for (const std::size_t len : {std::size_t{8}, std::size_t{20}, png.size() - 13}) {
    writeFile(dir.filePath("box.png"), png.substr(0, len));
    QVERIFY_THROWS_EXCEPTION(sg::LogError, sg::readRosMap(yamlPath));
  }
  const char replacements[] = {'\0', '\n', ' ', '[', ']',    '{', '}',
                               '"',  ',',  '-', '9', '\xff', 'x'};
  std::size_t runs = 0;
  for (const Case& c : cases) {
    QVERIFY(!c.text.empty());
    auto attempt = [&](const std::string& t) {
      ++runs;
      try {
        c.read(t);
      } catch (const sg::LogError&) {
      }
    };
    for (std::size_t len = 0; len < c.text.size(); ++len) attempt(c.text.substr(0, len));
    for (std::size_t i = 0; i < c.text.size(); ++i) {
      for (char r : replacements) {
        std::string t = c.text;
        t[i] = r;
        attempt(t);
      }
    }
  }
  QVERIFY(runs > 1000);
}

// ---------------------------------------------------------------------------------------------
// Actual position grid

void TstReference::supercover_data() {
  // On a grid of 1 m cells with its origin at (0, 0), so cell coordinates are metres.
  QTest::addColumn<double>("x0");
  QTest::addColumn<double>("y0");
  QTest::addColumn<double>("x1");
  QTest::addColumn<double>("y1");
  QTest::addColumn<QString>("cells");
  // Inside one row: the 4 cells it crosses.
  QTest::newRow("horizontal, mid-cell") << 0.5 << 0.5 << 3.5 << 0.5 << "(0,0) (1,0) (2,0) (3,0)";
  // On the boundary y = 1 between rows 0 and 1: both rows, no half-cell bias.
  QTest::newRow("on a row boundary")
      << 0.5 << 1.0 << 2.5 << 1.0 << "(0,0) (0,1) (1,0) (1,1) (2,0) (2,1)";
  QTest::newRow("on a column boundary") << 3.0 << 0.5 << 3.0 << 1.5 << "(2,0) (2,1) (3,0) (3,1)";
  // Through the corners (1, 1) and (2, 2): the four cells around each corner, so consecutive
  // cells share a side. Column 0 holds v in [0.5, 1] → rows 0, 1; column 1 v in [1, 2] → rows
  // 0..2; column 2 v in [2, 2.5] → rows 1, 2.
  QTest::newRow("diagonal through corners")
      << 0.5 << 0.5 << 2.5 << 2.5 << "(0,0) (0,1) (1,0) (1,1) (1,2) (2,1) (2,2)";
  // Slope 1/3 from (0.5, 0.5): v = 0.667 at u = 1, 1.0 at u = 2 (a corner), 1.333 at u = 3.
  QTest::newRow("slope one third")
      << 0.5 << 0.5 << 3.5 << 1.5 << "(0,0) (1,0) (1,1) (2,0) (2,1) (3,1)";
  QTest::newRow("reversed direction")
      << 3.5 << 1.5 << 0.5 << 0.5 << "(0,0) (1,0) (1,1) (2,0) (2,1) (3,1)";
  // Slope 3.5: v = 1.95 at u = 1, so column 0 holds rows 0, 1 and column 1 rows 1..3.
  QTest::newRow("steep") << 0.5 << 0.2 << 1.5 << 3.7 << "(0,0) (0,1) (1,1) (1,2) (1,3)";
  // Slope 3.6 reaches v = 2 at u = 1, a corner: (0, 2) and (1, 1) both touch it.
  QTest::newRow("steep through a corner")
      << 0.5 << 0.2 << 1.5 << 3.8 << "(0,0) (0,1) (0,2) (1,1) (1,2) (1,3)";
  QTest::newRow("a point in a cell") << 2.5 << 2.5 << 2.5 << 2.5 << "(2,2)";
  QTest::newRow("a point on a corner") << 2.0 << 2.0 << 2.0 << 2.0 << "(1,1) (1,2) (2,1) (2,2)";
  QTest::newRow("clipped at the edge") << -3.0 << 0.5 << 1.5 << 0.5 << "(0,0) (1,0)";
  QTest::newRow("outside") << -3.0 << -1.5 << -1.0 << -1.5 << "";
  QTest::newRow("huge coordinates")
      << -1e12 << 0.5 << 1e12 << 0.5 << "(0,0) (1,0) (2,0) (3,0) (4,0) (5,0)";
}

void TstReference::supercover() {
  QFETCH(double, x0);
  QFETCH(double, y0);
  QFETCH(double, x1);
  QFETCH(double, y1);
  QFETCH(QString, cells);
  const sg::GridSpec spec = unitGrid(6, 5);
  std::vector<std::uint8_t> out(spec.cellCount(), 0);
  sg::markSupercover(spec, sg::Position(x0, y0), sg::Position(x1, y1), out);
  QCOMPARE(cellsText(marked(spec, out)), cells);
}

void TstReference::supercoverOnRoundedBoundary() {
  // A wall at x = 3.2 on a 5 cm grid whose origin comes from GridSpec::covering: 3.2 / 0.05 and
  // the origin are not exact in binary, yet the wall lies on a boundary and marks exactly two
  // columns, on every row it spans.
  const sg::GridSpec spec =
      sg::GridSpec::covering(sg::Position(-5.1234, -3.3), sg::Position(9.0, 7.0), 0.05, 0.5);
  std::vector<std::uint8_t> out(spec.cellCount(), 0);
  sg::markSupercover(spec, sg::Position(3.2, 1.8), sg::Position(3.2, 2.2), out);
  const Cells c = marked(spec, out);
  std::set<int> columns;
  for (const auto& [x, y] : c) columns.insert(x);
  QCOMPARE(columns.size(), std::size_t{2});
  // 0.4 m spans 8 cells plus the rows touched at both ends (1.8 and 2.2 are boundaries too): 10.
  QCOMPARE(c.size(), std::size_t{2 * 10});
}

void TstReference::apgOfArmap() {
  // small.map on 10 cm cells with the origin at (-0.35, -0.05): every segment lies on cell centres
  // (u = (x + 0.35) / 0.1 = k + 0.5), so each marks one cell per 10 cm plus one.
  const sg::ReferenceMap map = sg::readArMap(kData + "small.map");
  sg::GridSpec spec;
  spec.origin = sg::Position(-0.35, -0.05);
  spec.cellSize = 0.1;
  spec.width = 30;
  spec.height = 20;
  const sg::ActualPositionGrid apg = sg::ActualPositionGrid::rasterise(map, spec);
  // line 1: x 0..2 m at y 0 → 21 cells; line 2: y 0..1.5 at x 2 → 16 cells, one shared with
  // line 1 at (2, 0); line 3: y 0.1..1.2 at x −0.2 → 12 cells. 21 + 15 + 12 = 48.
  QCOMPARE(apg.count(), std::size_t{48});
  QCOMPARE(int(apg.cells[spec.linear(spec.worldToCell(sg::Position(-0.2, 0.6)))]), 1);
  QCOMPARE(int(apg.cells[spec.linear(spec.worldToCell(sg::Position(1.0, 0.6)))]), 0);
}

void TstReference::rasterResampling_data() {
  QTest::addColumn<double>("originX");
  QTest::addColumn<double>("originY");
  QTest::addColumn<double>("cell");
  QTest::addColumn<int>("expected");
  // box.yaml: 0.5 m pixels from (−1, 2); obstacles at pixels (2, 0), (1, 1), (0, 2).
  // The same grid: one cell each.
  QTest::newRow("same grid") << -1.0 << 2.0 << 0.5 << 3;
  // 0.25 m cells aligned with the pixels: each pixel covers 2 x 2 cells.
  QTest::newRow("half cells, aligned") << -1.0 << 2.0 << 0.25 << 12;
  // 0.25 m cells shifted by 0.1 m in x: each pixel overlaps 3 columns x 2 rows.
  QTest::newRow("half cells, shifted") << -1.1 << 2.0 << 0.25 << 18;
  // 1 m cells: pixel (2, 0) → cell (1, 0); (1, 1) → cell (0, 0); (0, 2) → cell (0, 1).
  QTest::newRow("double cells") << -1.0 << 2.0 << 1.0 << 3;
}

void TstReference::rasterResampling() {
  QFETCH(double, originX);
  QFETCH(double, originY);
  QFETCH(double, cell);
  QFETCH(int, expected);
  const sg::ReferenceMap ref = sg::rosMapAsReference(sg::readRosMap(kData + "box.yaml"));
  sg::GridSpec spec;
  spec.origin = sg::Position(originX, originY);
  spec.cellSize = cell;
  spec.width = static_cast<int>(std::ceil(3.0 / cell)) + 1;
  spec.height = static_cast<int>(std::ceil(2.0 / cell)) + 1;
  QCOMPARE(static_cast<int>(sg::ActualPositionGrid::rasterise(ref, spec).count()), expected);
}

void TstReference::idealMap_data() {
  QTest::addColumn<QByteArray>("json");
  QTest::addColumn<int>("occupied");
  QTest::addColumn<int>("free");
  QTest::addColumn<int>("unknown");
  // On 10 cm cells from (−0.15, −0.15), 14 x 14 = 196 cells; x = 0 is column 1 (u = 1.5), x = 1 is
  // column 11, x = 0.4 column 5 and x = 0.6 column 7: every edge runs along cell centres.
  // walls: the ring of columns/rows 1..11 = 11·4 − 4 = 40 cells; box: ring of 5..7 = 8 cells,
  // its inside one cell (6, 6).
  const QByteArray walls =
      R"({"name": "walls", "closed": true, "corners": [[0, 0], [1, 0], [1, 1], [0, 1]]})";
  const QByteArray openWalls =
      R"({"name": "walls", "closed": false, "corners": [[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]]})";
  const QByteArray box =
      R"({"name": "box", "closed": true, "corners": [[0.4, 0.4], [0.6, 0.4], [0.6, 0.6], [0.4, 0.6]]})";
  const auto doc = [](const QByteArray& objects) {
    return R"({"format": "sonargrid-reference", "version": 1, "units": "m", "objects": [)" +
           objects + "]}";
  };
  // The walls enclose the box: inside the room (9 x 9 = 81 cells) less the box's 3 x 3 is free
  // (72); the box's inside (1) and the 196 − 121 = 75 cells outside the walls are unknown.
  QTest::newRow("room with a box") << doc(walls + "," + box) << 48 << 72 << 76;
  // A closed room with nothing inside reads as a solid block: its inside (81) unknown, and with
  // no enclosure the 75 cells outside are free.
  QTest::newRow("lone closed room") << doc(walls) << 40 << 75 << 81;
  // The same walls as an open polyline: no inside, everything but the ring is free.
  QTest::newRow("open polyline room") << doc(openWalls) << 40 << 156 << 0;
  // A lone box in the open: its inside unknown, everything else free (196 − 8 − 1 = 187).
  QTest::newRow("box in the open") << doc(box) << 8 << 187 << 1;
}

void TstReference::idealMap() {
  QFETCH(QByteArray, json);
  QFETCH(int, occupied);
  QFETCH(int, free);
  QFETCH(int, unknown);
  const sg::ReferenceMap ref = sg::parseReferenceJson(json.toStdString(), "ideal.json");
  sg::GridSpec spec;
  spec.origin = sg::Position(-0.15, -0.15);
  spec.cellSize = 0.1;
  spec.width = 14;
  spec.height = 14;
  const sg::ActualPositionGrid apg = sg::ActualPositionGrid::rasterise(ref, spec);
  const sg::IdealMap ideal = sg::IdealMap::fromReference(ref, apg);
  QCOMPARE(static_cast<int>(ideal.count(sg::IdealCell::Occupied)), occupied);
  QCOMPARE(static_cast<int>(ideal.count(sg::IdealCell::Free)), free);
  QCOMPARE(static_cast<int>(ideal.count(sg::IdealCell::Unknown)), unknown);
}

void TstReference::idealMapOfRosReference() {
  // On the image's own grid: obstacles occupied, free pixels free, the rest unknown (see
  // rosAsReference: 3 obstacles, 5 free, 4 unknown).
  const sg::ReferenceMap ref = sg::rosMapAsReference(sg::readRosMap(kData + "box.yaml"));
  const sg::ActualPositionGrid apg = sg::ActualPositionGrid::rasterise(ref, ref.raster->spec);
  const sg::IdealMap ideal = sg::IdealMap::fromReference(ref, apg);
  QCOMPARE(ideal.count(sg::IdealCell::Occupied), std::size_t{3});
  QCOMPARE(ideal.count(sg::IdealCell::Free), std::size_t{5});
  QCOMPARE(ideal.count(sg::IdealCell::Unknown), std::size_t{4});
  // Beyond the image: unknown.
  sg::GridSpec wider = ref.raster->spec;
  wider.width += 2;
  const sg::IdealMap w =
      sg::IdealMap::fromReference(ref, sg::ActualPositionGrid::rasterise(ref, wider));
  QCOMPARE(w.count(sg::IdealCell::Unknown), std::size_t{4 + 2 * 3});
}

QTEST_GUILESS_MAIN(TstReference)
#include "tst_reference.moc"
