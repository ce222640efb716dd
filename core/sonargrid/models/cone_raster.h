#pragma once
// Visits the cells whose centres lie in a sonar cone, using BeamTables for distance and bearing.
// Shared by every cone-shaped model; `Fn` is inlined per model, so the per-cell cost is a table
// load, two compares and the model's own arithmetic.

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sonargrid/beam_tables.h"
#include "sonargrid/grid_spec.h"
#include "sonargrid/pose.h"

namespace sg {

// fn(std::uint32_t cell, double delta, double theta) for every cell whose centre is within
// `reach` metres of the sensor and within `halfAngle` radians of its axis. Cells are visited row by
// row from the lowest world y, each row from the lowest x: a fixed order.
template <class Fn>
void forEachConeCell(const Pose2D& sensor, double reach, double halfAngle, const GridSpec& grid,
                     const BeamTables& tables, Fn&& fn) {
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

  // Bounding box of the sector: the apex, both edge ends and every axis direction inside it.
  const double h = sensor.heading;
  double minX = 0.0, maxX = 0.0, minY = 0.0, maxY = 0.0;
  auto include = [&](double a) {
    const double x = reach * std::cos(a), y = reach * std::sin(a);
    minX = std::min(minX, x), maxX = std::max(maxX, x);
    minY = std::min(minY, y), maxY = std::max(maxY, y);
  };
  include(h - halfAngle);
  include(h + halfAngle);
  for (int k = -4; k <= 4; ++k) {
    const double a = k * std::numbers::pi / 2.0;
    if (std::abs(wrapAngle(a - h)) <= halfAngle) include(a);
  }
  const int r = tables.radius();
  const int dx0 = std::max({-r, static_cast<int>(std::floor(u + minX / c)) - 1 - iu, -iu});
  const int dx1 = std::min({r, static_cast<int>(std::floor(u + maxX / c)) + 1 - iu, grid.width - 1 - iu});
  const int dy0 = std::max({-r, static_cast<int>(std::floor(v + minY / c)) - 1 - iv, -iv});
  const int dy1 = std::min({r, static_cast<int>(std::floor(v + maxY / c)) + 1 - iv, grid.height - 1 - iv});
  if (dx0 > dx1 || dy0 > dy1) return;

  const BeamTables::Entry* t = tables.table(qx, qy);
  const int side = tables.side();
  const float reachF = static_cast<float>(reach);
  constexpr double kPi = std::numbers::pi;
  for (int dy = dy0; dy <= dy1; ++dy) {
    const BeamTables::Entry* row = t + (dy + r) * side + r;
    const std::uint32_t rowBase = static_cast<std::uint32_t>((iv + dy) * grid.width + iu);
    for (int dx = dx0; dx <= dx1; ++dx) {
      const BeamTables::Entry e = row[dx];
      if (e.distance > reachF) continue;
      double theta = static_cast<double>(e.bearing) - h;
      if (theta > kPi) theta -= 2.0 * kPi;
      else if (theta < -kPi) theta += 2.0 * kPi;
      if (std::abs(theta) > halfAngle) continue;
      fn(rowBase + static_cast<std::uint32_t>(dx), static_cast<double>(e.distance), theta);
    }
  }
}

}  // namespace sg
