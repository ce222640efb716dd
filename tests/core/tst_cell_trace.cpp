// SPDX-License-Identifier: BSD-3-Clause
// The cell trace (cell_trace.h): its last value is the map's value at the cell, bit for bit, for
// every model × rule pair the registry allows, and a hand-built HIMM case gives the values of
// paper 000 §2.2 reading by reading.

#include <QtTest>
#include <cstring>

#include "sonargrid/engine/cell_trace.h"
#include "sonargrid/engine/mapper.h"
#include "sonargrid/io/sglog.h"

using namespace sg;

namespace {

// The bundled room log's first 150 scans (2400 readings: most of the first lap), true pose.
const Dataset& room() {
  static const Dataset d = [] {
    Dataset full = readSglog(SONARGRID_DATASETS "/room/room.sglog");
    full.scans.resize(150);
    return full;
  }();
  return d;
}

bool sameBits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// The value of `map` at `cell`, as CellValue holds it.
CellValue mapValue(const OccupancyMap& map, std::size_t cell) {
  return CellValue{map.probability[cell], map.native[cell], map.level[cell], map.filled[cell] != 0};
}

void compareBits(const CellValue& traced, const CellValue& mapped, const char* what) {
  if (!sameBits(traced.probability, mapped.probability) || !sameBits(traced.native, mapped.native))
    qWarning("%s: traced p %.17g native %.17g, map p %.17g native %.17g", what, traced.probability,
             traced.native, mapped.probability, mapped.native);
  QVERIFY2(sameBits(traced.probability, mapped.probability), what);
  QVERIFY2(sameBits(traced.native, mapped.native), what);
  QCOMPARE(traced.level, mapped.level);
  QCOMPARE(traced.filled, mapped.filled);
}

}  // namespace

class TestCellTrace : public QObject {
  Q_OBJECT

 private slots:
  void matchesTheMap_data();
  void matchesTheMap();
  void handHimm();
  void untilIsAPrefix();
  void errors();
  void cancels();
};

void TestCellTrace::matchesTheMap_data() {
  QTest::addColumn<QString>("model");
  QTest::addColumn<QString>("rule");
  // Every pair the registry allows (docs/models.md has the table); none may be left out.
  int rows = 0;
  for (const std::string& m : sensorModelNames())
    for (const std::string& r : updateRuleNames())
      if (compatibility(m, r).allowed) {
        QTest::newRow((m + " x " + r).c_str())
            << QString::fromStdString(m) << QString::fromStdString(r);
        ++rows;
      }
  QVERIFY(rows >= 20);
}

void TestCellTrace::matchesTheMap() {
  QFETCH(QString, model);
  QFETCH(QString, rule);
  const Dataset& data = room();
  MapperSettings settings;
  settings.model = model.toStdString();
  settings.rule = rule.toStdString();
  settings.pose = PoseSource::Truth;
  const GridSpec grid = data.fittingGrid(settings.pose, 0.1);
  Mapper mapper(data.ring, grid, settings);
  QVERIFY(mapper.mapDataset(data));
  const OccupancyMap map = mapper.snapshot();

  // A wall (or box) cell: the filled cell of highest probability; a free cell: the observed cell
  // of lowest; a never-touched cell: the first one no reading wrote. Plus the cells under three
  // points of the room (room.json): on the south wall, in the open middle, on the box's edge.
  std::size_t wall = map.probability.size(), free = wall, untouched = wall;
  for (std::size_t i = 0; i < map.probability.size(); ++i) {
    if (!map.observed[i]) {
      if (untouched == map.probability.size()) untouched = i;
      continue;
    }
    if (map.filled[i] &&
        (wall == map.probability.size() || map.probability[i] > map.probability[wall]))
      wall = i;
    if (free == map.probability.size() || map.probability[i] < map.probability[free]) free = i;
  }
  QVERIFY(free < map.probability.size());
  QVERIFY(untouched < map.probability.size());
  std::vector<std::pair<std::size_t, const char*>> cells{{free, "free cell"},
                                                         {untouched, "never-touched cell"}};
  // HIMM-model rules all see a filled cell; a rule on a cone may have none on 150 scans.
  if (wall < map.probability.size()) cells.emplace_back(wall, "wall cell");
  for (const auto& [p, what] : {std::pair{Position(3.0, 0.02), "south wall point"},
                                std::pair{Position(1.5, 2.0), "open floor point"},
                                std::pair{Position(3.2, 2.0), "box edge point"}})
    cells.emplace_back(grid.linear(grid.worldToCell(p)), what);

  for (const auto& [cell, what] : cells) {
    const CellTrace trace = traceCell(data, grid, settings, grid.fromLinear(cell));
    QVERIFY(trace.complete);
    QCOMPARE(trace.readings, data.readingCount());
    // A cell the map never observed is touched by no reading, and keeps the rule's unknown value.
    QCOMPARE(trace.steps.empty(), map.observed[cell] == 0);
    compareBits(trace.final(), mapValue(map, cell), what);
    for (std::size_t k = 1; k < trace.steps.size(); ++k)
      QVERIFY(trace.steps[k].reading > trace.steps[k - 1].reading);
  }
}

void TestCellTrace::handHimm() {
  // One sonar at the robot's centre facing +x, a 20 × 3 grid of 0.1 m cells from (0, 0): the
  // sensor at (0.05, 0.15) is the centre of cell (0, 1). A reading of r metres puts the echo in
  // cell (floor((0.05 + r) / 0.1), 1) and the cells from the sensor's up to it before the echo.
  Dataset d;
  d.ring.sonars = {SonarMount{Pose2D(0.0, 0.0, 0.0)}};
  d.ring.maxRange = 5.0;
  const double ranges[] = {0.9, 0.5, 0.5, 0.9, 0.2, 0.5, 0.5, 0.5, 0.5, 5.0};
  for (int k = 0; k < 10; ++k) {
    Scan s;
    s.time = 0.1 * k;
    s.odometry = Pose2D(0.05, 0.15, 0.0);
    s.readings.push_back(Reading{0, ranges[k], s.time});
    d.scans.push_back(s);
  }
  GridSpec grid;
  grid.origin = Position(0.0, 0.0);
  grid.cellSize = 0.1;
  grid.width = 20;
  grid.height = 3;
  MapperSettings settings;
  settings.model = "himm";
  settings.rule = "himm";
  const CellTrace trace = traceCell(d, grid, settings, CellIndex(5, 1));

  // Cell (5, 1) spans x 0.5..0.6. Paper 000 §2.2: the echo cell +I⁺ = +3, each cell before it
  // −I⁻ = −1, CV clamped to [0, 15]. The HIMM model gives the echo cell pO = 2 p_hit − 1 = 0.4 and
  // the cells before it pE = 1 − 2 p_miss = 0.2 (p_hit 0.7, p_miss 0.4: OctoMap's defaults).
  //   reading 0: 0.9 m, echo in cell 9, cell 5 before it: 0 − 1 clamped to 0
  //   reading 1, 2: 0.5 m, echo in cell 5: 3, 6
  //   reading 3: 0.9 m: 6 − 1 = 5
  //   reading 4: 0.2 m, echo in cell 2: cell 5 untouched (not listed)
  //   readings 5–8: 0.5 m: 8, 11, 14, then 17 clamped to 15
  //   reading 9: 5 m = max_range, no echo, writes nothing (no_echo off by default)
  struct Expected {
    std::size_t reading;
    bool echoCell;
    int cv;
  };
  const Expected expected[] = {{0, false, 0}, {1, true, 3},  {2, true, 6},  {3, false, 5},
                               {5, true, 8},  {6, true, 11}, {7, true, 14}, {8, true, 15}};
  QCOMPARE(trace.readings, std::size_t{10});
  QCOMPARE(trace.steps.size(), std::size(expected));
  QCOMPARE(trace.initial.native, 0.0);
  QCOMPARE(trace.nativeName, std::string("certainty value CV (0..15)"));
  for (std::size_t k = 0; k < trace.steps.size(); ++k) {
    const CellTraceStep& s = trace.steps[k];
    const Expected& e = expected[k];
    QCOMPARE(s.reading, e.reading);
    QCOMPARE(s.scan, e.reading);
    QCOMPARE(s.sonar, std::uint16_t{0});
    QCOMPARE(s.time, 0.1 * static_cast<double>(e.reading));
    QCOMPARE(s.range, ranges[e.reading]);
    QCOMPARE(s.occupied, e.echoCell ? 0.4f : 0.0f);
    QCOMPARE(s.empty, e.echoCell ? 0.0f : 0.2f);
    QCOMPARE(s.probability, e.echoCell ? 0.7f : 0.4f);
    QCOMPARE(s.after.native, double(e.cv));
    QCOMPARE(s.after.level, std::uint8_t(e.cv));
    QCOMPARE(s.after.probability, e.cv / 15.0);  // HIMM's p(occ) = CV / CV_max
    QCOMPARE(s.after.filled, e.cv > 0);
  }
  // And the map agrees.
  Mapper mapper(d.ring, grid, settings);
  QVERIFY(mapper.mapDataset(d));
  const OccupancyMap map = mapper.snapshot();
  QCOMPARE(map.native[grid.linear(CellIndex(5, 1))], 15.0);
}

void TestCellTrace::untilIsAPrefix() {
  // Up to time t, the trace is the whole trace's readings taken by t, and ends at the value of the
  // map made up to t.
  const Dataset& data = room();
  MapperSettings settings;
  settings.model = "parameterized";
  settings.rule = "bayes";
  const GridSpec grid = data.fittingGrid(settings.pose, 0.1);
  const CellIndex cell = grid.worldToCell(Position(3.0, 0.02));
  const double until = data.scans[80].time;
  const CellTrace whole = traceCell(data, grid, settings, cell);
  const CellTrace part = traceCell(data, grid, settings, cell, until);
  QVERIFY(part.steps.size() < whole.steps.size());
  QVERIFY(!part.steps.empty());
  for (std::size_t k = 0; k < part.steps.size(); ++k) {
    QCOMPARE(part.steps[k].reading, whole.steps[k].reading);
    QVERIFY(sameBits(part.steps[k].after.native, whole.steps[k].after.native));
  }
  QVERIFY(part.steps.back().time <= until);
  QVERIFY(whole.steps[part.steps.size()].time > until);
  Mapper mapper(data.ring, grid, settings);
  QVERIFY(mapper.mapDataset(data, until));
  compareBits(part.final(), mapValue(mapper.snapshot(), grid.linear(cell)), "until");
}

void TestCellTrace::errors() {
  const Dataset& data = room();
  MapperSettings settings;
  const GridSpec grid = data.fittingGrid(settings.pose, 0.1);
  QVERIFY_THROWS_EXCEPTION(CellTraceError,
                           traceCell(data, grid, settings, CellIndex(grid.width, 0)));
  QVERIFY_THROWS_EXCEPTION(CellTraceError, traceCell(data, grid, settings, CellIndex(0, -1)));
  settings.model = "no-such-model";
  QVERIFY_THROWS_EXCEPTION(MapperError, traceCell(data, grid, settings, CellIndex(0, 0)));
  // A reading naming a sonar the ring lacks is named, as the mapper names it.
  Dataset bad = data;
  bad.scans.resize(2);
  bad.scans[1].readings[0].sonar = 40;
  try {
    traceCell(bad, grid, MapperSettings{}, CellIndex(1, 1));
    QFAIL("no error");
  } catch (const MapperError& e) {
    QVERIFY2(std::string(e.what()).find("sonar 40") != std::string::npos, e.what());
  }
  // No true pose.
  Dataset odometryOnly = data;
  for (Scan& s : odometryOnly.scans) s.truth.reset();
  MapperSettings truth;
  truth.pose = PoseSource::Truth;
  QVERIFY_THROWS_EXCEPTION(MapperError, traceCell(odometryOnly, grid, truth, CellIndex(0, 0)));
}

void TestCellTrace::cancels() {
  const Dataset& data = room();
  const GridSpec grid = data.fittingGrid(PoseSource::Odometry, 0.1);
  const std::atomic<bool> cancel{true};
  const CellTrace t = traceCell(data, grid, MapperSettings{}, CellIndex(10, 10),
                                std::numeric_limits<double>::infinity(), &cancel);
  QVERIFY(!t.complete);
  QVERIFY(t.steps.empty());
}

QTEST_GUILESS_MAIN(TestCellTrace)
#include "tst_cell_trace.moc"
