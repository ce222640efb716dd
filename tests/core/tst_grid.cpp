// SPDX-License-Identifier: BSD-3-Clause
// The grid's storage: planes of a rule's cells, each starting at the rule's unknown value, and the
// cells readings wrote.

#include <QtTest>
#include <cstring>
#include <set>

#include "sonargrid/grid.h"

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
  void observedCells();
  void clearMakesEveryCellUnknown();
  void wrongCellTypeIsRefused();
};

void TstGrid::newGridIsUnknown() {
  const Grid g = twoPlanes(spec(0, 0, 7, 3));
  for (std::size_t i = 0; i < g.cellCount(); ++i) {
    QVERIFY(sameBytes(&g.cells<Pair>(0)[i], &kUnknownPair, sizeof(Pair)));
    QCOMPARE(g.cells<Count>(1)[i].n, kUnknownCount.n);
    QCOMPARE(std::uint8_t(g.observed(i)), std::uint8_t{0});
  }
  QVERIFY_THROWS_EXCEPTION(GridError, twoPlanes(spec(0, 0, 0, 3)));
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

void TstGrid::clearMakesEveryCellUnknown() {
  Grid g = twoPlanes(spec(0, 0, 4, 3));
  fillDistinct(g);
  g.clear();
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

QTEST_GUILESS_MAIN(TstGrid)
#include "tst_grid.moc"
