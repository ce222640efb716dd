// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/metrics/ideal_map.h"

#include <algorithm>
#include <cmath>

namespace sg {
namespace {

// Even-odd test of a point against a polygon (crossing number, half-open in y so that a vertex
// on the ray is counted once).
bool insidePolygon(const std::vector<Position>& polygon, const Position& p) {
  bool inside = false;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Position& a = polygon[i];
    const Position& b = polygon[j];
    if ((a.y() > p.y()) != (b.y() > p.y())) {
      const double x = a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
      if (p.x() < x) inside = !inside;
    }
  }
  return inside;
}

std::vector<Position> polygonMetres(const ReferenceMap& reference, const ReferenceObject& o) {
  std::vector<Position> out;
  for (std::size_t k = 0; k < o.corners.size(); ++k) out.push_back(reference.cornerMetres(o, k));
  return out;
}

}  // namespace

std::size_t IdealMap::count(IdealCell kind) const {
  return static_cast<std::size_t>(std::count(cells.begin(), cells.end(), kind));
}

void markInterior(const GridSpec& spec, const std::vector<Position>& polygon,
                  std::vector<std::uint8_t>& inside) {
  if (polygon.size() < 3) return;
  const double c = spec.cellSize;
  // Only the rows whose centre lies within the polygon's extent in y.
  double ylo = polygon.front().y(), yhi = ylo;
  for (const Position& q : polygon) {
    ylo = std::min(ylo, q.y());
    yhi = std::max(yhi, q.y());
  }
  const double firstRow = std::max(0.0, std::floor((ylo - spec.origin.y()) / c - 0.5));
  const double lastRow =
      std::min(static_cast<double>(spec.height - 1), std::ceil((yhi - spec.origin.y()) / c - 0.5));
  if (!(firstRow <= lastRow)) return;
  std::vector<double> xs;
  for (int iy = static_cast<int>(firstRow); iy <= static_cast<int>(lastRow); ++iy) {
    const double y = spec.origin.y() + (iy + 0.5) * c;
    xs.clear();
    const std::size_t n = polygon.size();
    for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
      const Position& a = polygon[i];
      const Position& b = polygon[j];
      if ((a.y() > y) != (b.y() > y))
        xs.push_back(a.x() + (y - a.y()) * (b.x() - a.x()) / (b.y() - a.y()));
    }
    std::sort(xs.begin(), xs.end());
    for (std::size_t k = 0; k + 1 < xs.size(); k += 2) {
      // Cells whose centre x lies strictly between the two crossings.
      const double lo = (xs[k] - spec.origin.x()) / c - 0.5;
      const double hi = (xs[k + 1] - spec.origin.x()) / c - 0.5;
      const double first = std::max(0.0, std::floor(lo) + 1.0);
      const double last = std::min(static_cast<double>(spec.width - 1), std::ceil(hi) - 1.0);
      for (double ix = first; ix <= last; ix += 1.0) {
        inside[spec.linear(CellIndex(static_cast<int>(ix), iy))] = 1;
      }
    }
  }
}

IdealMap IdealMap::fromReference(const ReferenceMap& reference, const ActualPositionGrid& apg) {
  const GridSpec& spec = apg.spec;
  const std::size_t n = spec.cellCount();
  IdealMap ideal;
  ideal.spec = spec;
  ideal.cells.assign(n, IdealCell::Free);

  // Which closed objects are enclosures: those with a corner of another object strictly inside.
  // Corners sorted by x, so each object tests only the corners within its bounding box (a
  // reference of thousands of boxes stays fast).
  struct Corner {
    Position p;
    std::size_t object;
  };
  std::vector<Corner> corners;
  for (std::size_t j = 0; j < reference.objects.size(); ++j) {
    const ReferenceObject& o = reference.objects[j];
    for (std::size_t k = 0; k < o.corners.size(); ++k)
      corners.push_back({reference.cornerMetres(o, k), j});
  }
  std::sort(corners.begin(), corners.end(),
            [](const Corner& a, const Corner& b) { return a.p.x() < b.p.x(); });

  std::vector<std::uint8_t> insideSolid(n, 0);
  std::vector<std::uint8_t> insideEnclosure(n, 0);
  bool anyEnclosure = false;
  for (std::size_t i = 0; i < reference.objects.size(); ++i) {
    const ReferenceObject& o = reference.objects[i];
    if (!o.closed) continue;
    const std::vector<Position> polygon = polygonMetres(reference, o);
    Position lo = polygon.front(), hi = polygon.front();
    for (const Position& q : polygon) {
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
    auto it = std::lower_bound(corners.begin(), corners.end(), lo.x(),
                               [](const Corner& c, double x) { return c.p.x() < x; });
    bool enclosure = false;
    for (; it != corners.end() && it->p.x() <= hi.x() && !enclosure; ++it) {
      if (it->object == i || it->p.y() < lo.y() || it->p.y() > hi.y()) continue;
      enclosure = insidePolygon(polygon, it->p);
    }
    anyEnclosure = anyEnclosure || enclosure;
    markInterior(spec, polygon, enclosure ? insideEnclosure : insideSolid);
  }

  const ObstacleRaster* raster = reference.raster ? &*reference.raster : nullptr;
  for (std::size_t i = 0; i < n; ++i) {
    if (apg.cells[i] != 0) {
      ideal.cells[i] = IdealCell::Occupied;
      continue;
    }
    if (insideSolid[i] != 0 || (anyEnclosure && insideEnclosure[i] == 0)) {
      ideal.cells[i] = IdealCell::Unknown;
      continue;
    }
    if (raster) {
      const CellIndex r = raster->spec.worldToCell(spec.cellCentre(spec.fromLinear(i)));
      if (!raster->spec.contains(r) ||
          raster->cells[raster->spec.linear(r)] == RasterCell::Unknown) {
        ideal.cells[i] = IdealCell::Unknown;
      }
      // An obstacle pixel under a cell centre always overlaps the cell, so the APG has it.
    }
  }
  return ideal;
}

}  // namespace sg
