// SPDX-License-Identifier: BSD-3-Clause
// The grid's storage: planes of a rule's cells, growth that keeps every cell at its world
// position, slack that keeps a slowly growing grid from reallocating per scan, the cell limit, and
// dirty rows that are exactly the rows written.

#include <QtTest>
#include <cmath>
#include <cstring>
#include <set>

#include "sonargrid/engine/grid.h"

using namespace sg;

namespace {

// A 16-byte cell whose unknown value is not zero bytes, and a second plane of another type: the
// shape of the rules' layouts (addition's two planes, Dempster–Shafer's pair).
struct Pair {
  double a, b;
};
struct Count {
  std::uint8_t n;
};
const Pair kUnknownPair{0.5, -1.0};
const Count kUnknownCount{7};

GridSpec spec(double ox, double oy, int width, int height, double cell = 0.05) {
  GridSpec g;
  g.origin = Position(ox, oy);
  g.cellSize = cell;
  g.width = width;
  g.height = height;
  return g;
}

Grid twoPlanes(const GridSpec& s) {
  return Grid(s, CellLayout::of(kUnknownPair, kUnknownCount));
}

// Writes a value that names the cell into every cell of both planes, and marks every third
// observed.
void fillDistinct(Grid& g) {
  Pair* pairs = g.cells<Pair>(0);
  Count* counts = g.cells<Count>(1);
  Footprint fp;
  for (std::size_t i = 0; i < g.cellCount(); ++i) {
    pairs[i] = Pair{static_cast<double>(i), 1.0 / (1.0 + static_cast<double>(i))};
    counts[i] = Count{static_cast<std::uint8_t>(i % 251)};
    if (i % 3 == 0) fp.cells.push_back(CellEvidence(static_cast<std::uint32_t>(i), 0, 0, 0.5));
  }
  g.markWritten(fp);
}

bool sameBytes(const void* a, const void* b, std::size_t n) {
  return std::memcmp(a, b, n) == 0;
}

}  // namespace

class TstGrid : public QObject {
  Q_OBJECT

 private slots:
  void newGridIsUnknown();
  void growthKeepsEveryCell_data();
  void growthKeepsEveryCell();
  void slackIsGeometric();
  void growthLimit();
  void observedCells();
  void runsMarkExactlyTheirCells();
  void dirtyRowsAreTheRowsWritten();
  void clearMakesEveryRowDirty();
  void wrongCellTypeIsRefused();
  void sharedCellsStayAsTheyWere();
};

void TstGrid::newGridIsUnknown() {
  const Grid g = twoPlanes(spec(0, 0, 7, 3));
  for (std::size_t i = 0; i < g.cellCount(); ++i) {
    QVERIFY(sameBytes(&g.cells<Pair>(0)[i], &kUnknownPair, sizeof(Pair)));
    QCOMPARE(g.cells<Count>(1)[i].n, kUnknownCount.n);
    QCOMPARE(std::uint8_t(g.observed(i)), std::uint8_t{0});
  }
  QCOMPARE(g.dirtyRows(), (std::vector<int>{0, 1, 2}));  // a new grid is all news
  QVERIFY_THROWS_EXCEPTION(GridError, twoPlanes(spec(0, 0, 0, 3)));
}

void TstGrid::growthKeepsEveryCell_data() {
  QTest::addColumn<double>("lox");
  QTest::addColumn<double>("loy");
  QTest::addColumn<double>("hix");
  QTest::addColumn<double>("hiy");
  // The grid is 10 x 6 cells of 5 cm from (-0.5, 0.25): x in [-0.5, 0), y in [0.25, 0.55).
  QTest::newRow("left") << -0.73 << 0.3 << -0.4 << 0.3;
  QTest::newRow("right") << 0.0 << 0.3 << 0.31 << 0.3;
  QTest::newRow("below") << -0.3 << -1.0 << -0.3 << 0.3;
  QTest::newRow("above") << -0.3 << 0.3 << -0.3 << 0.9;
  QTest::newRow("every side") << -3.0 << -2.0 << 4.0 << 5.0;
  QTest::newRow("a far corner") << 40.0 << 30.0 << 41.0 << 31.0;
}

void TstGrid::growthKeepsEveryCell() {
  QFETCH(double, lox);
  QFETCH(double, loy);
  QFETCH(double, hix);
  QFETCH(double, hiy);
  const GridSpec before = spec(-0.5, 0.25, 10, 6);
  Grid g = twoPlanes(before);
  fillDistinct(g);
  Grid old = twoPlanes(before);
  fillDistinct(old);
  g.takeDirtyRuns();

  const Position lo(lox, loy), hi(hix, hiy);
  QVERIFY(!g.covers(lo, hi));
  QVERIFY(g.growToCover(lo, hi));
  const GridSpec& after = g.spec();
  QVERIFY(g.covers(lo, hi));
  QVERIFY(!g.growToCover(lo, hi));  // covered now: nothing to do
  QCOMPARE(after.cellSize, before.cellSize);
  // The origin moved by whole cells, down and left only.
  const double kx = (before.origin.x() - after.origin.x()) / before.cellSize;
  const double ky = (before.origin.y() - after.origin.y()) / before.cellSize;
  QVERIFY(std::abs(kx - std::round(kx)) < 1e-9 && kx > -0.5);
  QVERIFY(std::abs(ky - std::round(ky)) < 1e-9 && ky > -0.5);
  // Every old cell is in the new grid at the same world position, with the same bytes in every
  // plane and the same observed flag; every other cell is unknown and unobserved.
  std::vector<char> fromOld(g.cellCount(), 0);
  for (std::size_t i = 0; i < old.cellCount(); ++i) {
    const CellIndex c = after.worldToCell(before.cellCentre(before.fromLinear(i)));
    QVERIFY(after.contains(c));
    const std::size_t j = after.linear(c);
    fromOld[j] = 1;
    QVERIFY(sameBytes(&g.cells<Pair>(0)[j], &old.cells<Pair>(0)[i], sizeof(Pair)));
    QCOMPARE(g.cells<Count>(1)[j].n, old.cells<Count>(1)[i].n);
    QCOMPARE(std::uint8_t(g.observed(j)), std::uint8_t(old.observed(i)));
  }
  for (std::size_t j = 0; j < g.cellCount(); ++j) {
    if (fromOld[j]) continue;
    QVERIFY(sameBytes(&g.cells<Pair>(0)[j], &kUnknownPair, sizeof(Pair)));
    QCOMPARE(g.cells<Count>(1)[j].n, kUnknownCount.n);
    QCOMPARE(std::uint8_t(g.observed(j)), std::uint8_t{0});
  }
  // Growth moves every row: all of them are news to a snapshot.
  QCOMPARE(static_cast<int>(g.dirtyRows().size()), after.height);
}

void TstGrid::slackIsGeometric() {
  // A robot creeping right one cell at a time past the edge of a 100-cell-wide grid: each growth
  // adds at least half the width, so 2000 steps reallocate about log1.5(2100 / 100) ≈ 8 times,
  // not 2000.
  Grid g = twoPlanes(spec(0, 0, 100, 10, 1.0));
  int growths = 0;
  for (int step = 0; step < 2000; ++step) {
    const double x = 100.5 + step;
    const int widthBefore = g.spec().width;
    if (g.growToCover(Position(x, 5.0), Position(x, 5.0))) {
      ++growths;
      QVERIFY(g.spec().width >= widthBefore + (widthBefore + 1) / 2);
    }
    QVERIFY(g.covers(Position(x, 5.0), Position(x, 5.0)));
  }
  QVERIFY2(growths <= 9, qPrintable(QString::number(growths)));
  QCOMPARE(g.spec().height, 10);  // only the side that had to grow
  QCOMPARE(g.spec().origin, Position(0, 0));
}

void TstGrid::growthLimit() {
  // 1 mm cells: a box 20 km by 2 cm needs 2·10⁷ x 20 = 4·10⁸ cells, twice kMaxGridCells. The
  // grid stays as it was.
  Grid g(spec(0, 0, 10, 10, 0.001), CellLayout::of(Count{0}));
  const GridSpec before = g.spec();
  try {
    g.growToCover(Position(0, 0), Position(20000.0, 0.0195));
    QFAIL("a grid past the limit was grown");
  } catch (const GridLimitError& e) {
    QVERIFY2(
        std::string(e.what()).find("more than the limit of 200000000 cells") != std::string::npos,
        e.what());
  }
  QCOMPARE(g.spec(), before);
  QVERIFY_THROWS_EXCEPTION(GridLimitError,
                           g.growToCover(Position(0, 0), Position(std::nan(""), 0)));
  QVERIFY_THROWS_EXCEPTION(GridLimitError,
                           g.growToCover(Position(0, 0), Position(1e300, 0)));  // no overflow
  QCOMPARE(g.spec(), before);
}

void TstGrid::observedCells() {
  Grid g = twoPlanes(spec(0, 0, 5, 10));
  auto cell = [](int x, int y) {
    return CellEvidence(static_cast<std::uint32_t>(y * 5 + x), 0, 0, 0.5);
  };
  Footprint a, b;
  a.cells = {cell(0, 1), cell(4, 1), cell(0, 2), cell(3, 2), cell(2, 7), cell(1, 2)};
  b.cells = {cell(0, 4), cell(4, 9), cell(1, 4)};
  g.markWritten(a);
  g.markWritten(b);
  std::set<std::uint32_t> written;
  for (const Footprint* f : {&a, &b})
    for (const CellEvidence& c : f->cells) written.insert(c.cell);
  std::vector<std::uint8_t> copied(g.cellCount(), 9);
  g.copyObserved(0, g.cellCount(), copied.data());
  for (std::uint32_t i = 0; i < g.cellCount(); ++i) {
    QCOMPARE(std::uint8_t(g.observed(i)), std::uint8_t(written.count(i) ? 1 : 0));
    QCOMPARE(copied[i], std::uint8_t(written.count(i) ? 1 : 0));
  }
}

void TstGrid::runsMarkExactlyTheirCells() {
  // markWritten(cell, count), a run of consecutive cells (the batch path's runs), marks exactly
  // cells [cell, cell + count): every length from 0 to 40 (eight, four or one marks at a time, the
  // last ones overlapping), starting anywhere in a word, on a 50 × 2 grid.
  for (int count = 0; count <= 40; ++count) {
    for (const std::uint32_t first :
         {0u, 1u, 3u, 7u, 13u, 59u, 100u - static_cast<unsigned>(count)}) {
      Grid g = twoPlanes(spec(0, 0, 50, 2));
      g.takeDirtyRuns();  // every row is dirty after construction
      g.markWritten(first, count);
      for (std::uint32_t i = 0; i < g.cellCount(); ++i) {
        const bool inRun = i >= first && i < first + static_cast<std::uint32_t>(count);
        QVERIFY2(g.observed(i) == inRun,
                 qPrintable(QString("run of %1 from %2: cell %3").arg(count).arg(first).arg(i)));
      }
      QCOMPARE(g.dirtyRows().size(), count == 0                           ? std::size_t{0}
                                     : (first < 50 && first + count > 50) ? std::size_t{2}
                                                                          : std::size_t{1});
    }
  }
}

void TstGrid::dirtyRowsAreTheRowsWritten() {
  // Footprints that wander: rows 1, 2 (twice), then 7, back to 2, and one cell of row 9 between
  // two of row 4. Rows 0, 3, 5, 6 and 8 are never written.
  Grid g = twoPlanes(spec(0, 0, 5, 10));
  g.takeDirtyRuns();
  QVERIFY(g.dirtyRows().empty());
  auto cell = [](int x, int y) {
    return CellEvidence(static_cast<std::uint32_t>(y * 5 + x), 0, 0, 0.5);
  };
  Footprint a, b;
  a.cells = {cell(0, 1), cell(4, 1), cell(0, 2), cell(3, 2), cell(2, 7), cell(1, 2)};
  b.cells = {cell(0, 4), cell(4, 9), cell(1, 4)};
  g.markWritten(a);
  g.markWritten(b);
  QCOMPARE(g.dirtyRows(), (std::vector<int>{1, 2, 4, 7, 9}));
  const std::vector<RowBand> runs = g.takeDirtyRuns();
  QCOMPARE(runs.size(), std::size_t{4});
  QCOMPARE(runs[0], (RowBand{1, 3}));
  QCOMPARE(runs[3], (RowBand{9, 10}));
  std::set<std::uint32_t> written;
  for (const Footprint* f : {&a, &b})
    for (const CellEvidence& c : f->cells) written.insert(c.cell);
  for (std::uint32_t i = 0; i < g.cellCount(); ++i)
    QCOMPARE(std::uint8_t(g.observed(i)), std::uint8_t(written.count(i) ? 1 : 0));
  QVERIFY(g.dirtyRows().empty());                          // taken
  QCOMPARE(std::uint8_t(g.observed(5)), std::uint8_t{1});  // observed stays
  // A cell written before is news again when written again.
  Footprint again;
  again.cells = {cell(2, 7)};
  g.markWritten(again);
  QCOMPARE(g.dirtyRows(), (std::vector<int>{7}));
}

void TstGrid::clearMakesEveryRowDirty() {
  Grid g = twoPlanes(spec(0, 0, 4, 3));
  fillDistinct(g);
  g.takeDirtyRuns();
  g.clear();
  QCOMPARE(g.dirtyRows(), (std::vector<int>{0, 1, 2}));
  for (std::size_t i = 0; i < g.cellCount(); ++i) {
    QVERIFY(sameBytes(&g.cells<Pair>(0)[i], &kUnknownPair, sizeof(Pair)));
    QCOMPARE(std::uint8_t(g.observed(i)), std::uint8_t{0});
  }
}

void TstGrid::wrongCellTypeIsRefused() {
  Grid g = twoPlanes(spec(0, 0, 4, 3));
  QVERIFY_THROWS_EXCEPTION(std::logic_error, g.cells<Count>(0));
  QVERIFY_THROWS_EXCEPTION(std::logic_error, g.cells<Pair>(1));
  QVERIFY_THROWS_EXCEPTION(std::logic_error, g.cells<Pair>(2));  // no third plane
}

void TstGrid::sharedCellsStayAsTheyWere() {
  // What a snapshot reads (sharedCells()) keeps the values it was given while the grid is written
  // again, cleared and grown; a shared plane is not handed out for writing until unshare().
  Grid g = twoPlanes(spec(0, 0, 5, 4));
  fillDistinct(g);
  const Grid seen = g.sharedCells();
  QVERIFY(g.shared());
  QCOMPARE(seen.spec(), g.spec());
  QVERIFY_THROWS_EXCEPTION(std::logic_error, g.cells<Pair>(0));
  QVERIFY_THROWS_EXCEPTION(std::logic_error, g.cells<Count>(1));
  g.unshare();
  QVERIFY(!g.shared());
  g.cells<Pair>(0)[7] = Pair{-3.0, -4.0};
  g.cells<Count>(1)[7] = Count{200};
  const Grid& written = g;
  for (std::size_t i = 0; i < g.cellCount(); ++i) {
    // fillDistinct's values, in the shared cells and (but for cell 7) in the grid.
    const Pair p{static_cast<double>(i), 1.0 / (1.0 + static_cast<double>(i))};
    QVERIFY(sameBytes(&seen.cells<Pair>(0)[i], &p, sizeof(Pair)));
    QCOMPARE(seen.cells<Count>(1)[i].n, static_cast<std::uint8_t>(i % 251));
    if (i != 7) QVERIFY(sameBytes(&written.cells<Pair>(0)[i], &p, sizeof(Pair)));
  }
  QCOMPARE(written.cells<Pair>(0)[7].a, -3.0);
  QCOMPARE(written.cells<Count>(1)[7].n, std::uint8_t{200});

  // clear() while shared: the sharer keeps cell 7's write, the grid is unknown again and its own.
  const Grid beforeClear = g.sharedCells();
  g.clear();
  QVERIFY(!g.shared());
  QCOMPARE(beforeClear.cells<Pair>(0)[7].a, -3.0);
  QCOMPARE(written.cells<Pair>(0)[7].a, kUnknownPair.a);
  g.cells<Pair>(0)[7] = Pair{9.0, 9.0};  // writable without unshare(): clear() replaced it
  QCOMPARE(beforeClear.cells<Pair>(0)[7].a, -3.0);

  // Growth while shared: the sharer keeps its limits and values, the grown grid is its own.
  const Grid beforeGrowth = g.sharedCells();
  QVERIFY(g.growToCover(Position(-0.2, -0.2), Position(0.1, 0.1)));
  QVERIFY(!g.shared());
  QCOMPARE(beforeGrowth.spec(), spec(0, 0, 5, 4));
  QCOMPARE(beforeGrowth.cells<Pair>(0)[7].a, 9.0);
  g.cells<Pair>(0)[0] = Pair{1.0, 1.0};

  // A plane whose sharers are gone is the grid's again, kept rather than copied.
  const Pair* const storage = written.cells<Pair>(0);
  { const Grid brief = g.sharedCells(); }
  QVERIFY(!g.shared());
  g.unshare();
  QCOMPARE(static_cast<const Pair*>(g.cells<Pair>(0)), storage);
}

QTEST_GUILESS_MAIN(TstGrid)
#include "tst_grid.moc"
