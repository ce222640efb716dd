#pragma once
// Visits the cells whose centres lie in a sonar cone, using BeamTables for distance and bearing.
// Shared by every cone-shaped model; `Fn` is inlined per model, so the per-cell cost is a table
// load, two compares and the model's own arithmetic. Each row is walked only over the span where
// the horizontal line through its cell centres meets the cone (disk ∩ wedge), so few cells are
// looked at and rejected.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <type_traits>
#include <utility>
#include <vector>

#include "sonargrid/beam_tables.h"
#include "sonargrid/grid_spec.h"
#include "sonargrid/pose.h"

namespace sg {

namespace detail {

// Narrows [lo, hi] to the x with a * x <= b.
inline void clip(double a, double b, double& lo, double& hi) {
  if (a > 0.0)
    hi = std::min(hi, b / a);
  else if (a < 0.0)
    lo = std::max(lo, b / a);
  else if (b < 0.0)
    hi = -std::numeric_limits<double>::infinity();
}

}  // namespace detail

// The per-row spans of one cone, found before any cell is visited so that the caller can size its
// output once. Reused per thread.
struct ConeSpan {
  int dy, dx0, dx1;
};

// fn(std::uint32_t cell, double delta, double theta) for every cell whose centre is within
// `reach` metres of the sensor and within `halfAngle` radians of its axis (halfAngle < 90°).
// Cells are visited row by row from the lowest world y, each row from the lowest x: a fixed order.
// Before the first call, reserve(bound) is told how many calls there can be at most.
template <class Reserve, class Fn>
void forEachConeCell(const Pose2D& sensor, double reach, double halfAngle, const GridSpec& grid,
                     const BeamTables& tables, Reserve&& reserve, Fn&& fn) {
  const double c = grid.cellSize;
  const double u = (sensor.x() - grid.origin.x()) / c;
  const double v = (sensor.y() - grid.origin.y()) / c;
  const double fu = std::floor(u);
  const double fv = std::floor(v);
  const int q = tables.subdivisions();
  const int qx = std::min(q - 1, static_cast<int>((u - fu) * q));
  const int qy = std::min(q - 1, static_cast<int>((v - fv) * q));
  const int iu = static_cast<int>(fu);
  const int iv = static_cast<int>(fv);
  // The apex the tables assume: the centre of the sensor's sub-cell, in cell units of its cell.
  const double ax = (qx + 0.5) / q;
  const double ay = (qy + 0.5) / q;

  // The per-cell angle test corrects by 2π once, so the heading itself must be in [-π, π).
  const double h = wrapAngle(sensor.heading);
  const double R = reach / c;
  const double d1x = std::cos(h - halfAngle), d1y = std::sin(h - halfAngle);  // right edge
  const double d2x = std::cos(h + halfAngle), d2y = std::sin(h + halfAngle);  // left edge
  // Spans are computed for the region grown by kSlack cells (perpendicular distance), far more than
  // the float tables' error, so they hold every cell the per-cell test below accepts.
  constexpr double kSlack = 1e-3;

  const int r = tables.radius();
  const int dy0 = std::max({-r, static_cast<int>(std::floor(ay - 0.5 - R)) - 1, -iv});
  const int dy1 =
      std::min({r, static_cast<int>(std::ceil(ay - 0.5 + R)) + 1, grid.height - 1 - iv});
  // Per thread, so workers never share it; fn must not call forEachConeCell itself.
  thread_local std::vector<ConeSpan> spans;
  spans.clear();
  std::size_t bound = 0;
  for (int dy = dy0; dy <= dy1; ++dy) {
    const double y = dy + 0.5 - ay;  // row of cell centres, relative to the apex
    const double disk = (R + kSlack) * (R + kSlack) - y * y;
    if (disk < 0.0) continue;
    const double half = std::sqrt(disk);  // once per row, not per cell
    double lo = -half, hi = half;
    // The wedge: left of the right edge, cross(d1, p) >= -slack, and right of the left edge,
    // cross(p, d2) >= -slack (a wedge narrower than 180° is the meet of the two half-planes).
    detail::clip(d1y, d1x * y + kSlack, lo, hi);
    detail::clip(-d2y, -d2x * y + kSlack, lo, hi);
    if (!(lo <= hi)) continue;
    // Cell dx has its centre at x = dx + 0.5 - ax.
    const int dx0 = std::max({-r, static_cast<int>(std::ceil(lo - 0.5 + ax)), -iu});
    const int dx1 = std::min({r, static_cast<int>(std::floor(hi - 0.5 + ax)), grid.width - 1 - iu});
    if (dx0 > dx1) continue;
    spans.push_back(ConeSpan{dy, dx0, dx1});
    bound += static_cast<std::size_t>(dx1 - dx0 + 1);
  }
  reserve(bound);

  const BeamTables::Entry* t = tables.table(qx, qy);
  const int side = tables.side();
  const float reachF = static_cast<float>(reach);
  constexpr double kPi = std::numbers::pi;
  // Bearings are in [-π, π]: bearing − heading needs a 2π correction only in a cone that crosses
  // the ±π line. Elsewhere a raw difference beyond ±halfAngle is simply outside.
  const bool crossesPi = h + halfAngle >= kPi || h - halfAngle < -kPi;
  auto walk = [&](auto wrap) {
    for (const ConeSpan& span : spans) {
      const BeamTables::Entry* row = t + (span.dy + r) * side + r;
      const std::uint32_t rowBase = static_cast<std::uint32_t>((iv + span.dy) * grid.width + iu);
      for (int dx = span.dx0; dx <= span.dx1; ++dx) {
        const BeamTables::Entry e = row[dx];
        if (e.distance > reachF) continue;
        double theta = static_cast<double>(e.bearing) - h;
        if constexpr (decltype(wrap)::value) {
          if (theta > kPi)
            theta -= 2.0 * kPi;
          else if (theta < -kPi)
            theta += 2.0 * kPi;
        }
        if (std::abs(theta) > halfAngle) continue;
        fn(rowBase + static_cast<std::uint32_t>(dx), static_cast<double>(e.distance), theta);
      }
    }
  };
  if (crossesPi)
    walk(std::true_type{});
  else
    walk(std::false_type{});
}

// Without a bound: for callers that only count or collect cells.
template <class Fn>
void forEachConeCell(const Pose2D& sensor, double reach, double halfAngle, const GridSpec& grid,
                     const BeamTables& tables, Fn&& fn) {
  forEachConeCell(
      sensor, reach, halfAngle, grid, tables, [](std::size_t) {}, std::forward<Fn>(fn));
}

}  // namespace sg
