// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Finds the cells whose centres lie in a sonar cone, using BeamTables for distance and bearing,
// as one run of consecutive cells per grid row. Each row is looked at only over the span where the
// horizontal line through its cell centres meets the cone (disk ∩ wedge), and only the cells at
// the span's two ends are tested one by one: the models evaluate whole rows in vector lanes.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <span>
#include <utility>
#include <vector>

#include "sonargrid/data/pose.h"
#include "sonargrid/engine/beam_tables.h"
#include "sonargrid/engine/footprint.h"
#include "sonargrid/engine/grid_spec.h"

// The span of each row is computed inside forEachRow's loop: inlined (GCC left it out of line in
// one model's file, a call per row).
#if defined(__GNUC__) && !defined(__clang__)
#define SG_ROW_INLINE __attribute__((always_inline))
#else
#define SG_ROW_INLINE
#endif

namespace sg {

namespace detail {

// Narrows [lo, hi] to the x with a * x <= b, given inv = 1 / a: b * inv is b / a to an ulp or
// two, which the spans' slack (forEachConeRow) covers many times over, without a division per row.
inline void clip(double a, double inv, double b, double& lo, double& hi) {
  if (a > 0.0)
    hi = std::min(hi, b * inv);
  else if (a < 0.0)
    lo = std::max(lo, b * inv);
  else if (b < 0.0)
    hi = -std::numeric_limits<double>::infinity();
}

// floor and ceil to int for |x| < 2³¹. std::floor is a library call on baseline x86-64, so by
// default they correct a truncation; with kRound, for code built where the CPU rounds in one
// instruction (SSE4.1, as in coneRunsWide), they round. Both give the same integer.
template <bool kRound = false>
inline int floorToInt(double x) {
  if constexpr (kRound) return static_cast<int>(std::floor(x));
  const int i = static_cast<int>(x);
  return i - (static_cast<double>(i) > x ? 1 : 0);
}
template <bool kRound = false>
inline int ceilToInt(double x) {
  if constexpr (kRound) return static_cast<int>(std::ceil(x));
  const int i = static_cast<int>(x);
  return i + (static_cast<double>(i) < x ? 1 : 0);
}

// The whole turn that brings `raw` = bearing − heading into [-π, π], both being in [-π, π].
inline double turn(double raw) {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  return raw > std::numbers::pi ? -kTwoPi : raw < -std::numbers::pi ? kTwoPi : 0.0;
}

// A cell's angle off the axis, for a heading in [-π, π).
inline double offAxis(float bearing, double heading) {
  const double raw = static_cast<double>(bearing) - heading;
  return raw + turn(raw);
}

// What the rows' spans are computed from (forEachConeRow, which explains each value).
struct SpanGeometry {
  double ay, ax, reach2;
  double d1x, d1y, inv1, d2x, d2y, inv2;
  double slack;
  int minDx, maxDx;
};

}  // namespace detail

// The per-row spans of one cone, found before any cell is visited so that the caller can size its
// output once. Reused per thread.
struct ConeSpan {
  int dy, dx0, dx1;
};

namespace detail {

// forEachConeRow's spans of rows dy = first .. last, four rows at a time in double lanes (GCC's
// vector extensions), for code built for AVX2 or AVX-512: each lane does what the one-row loop
// does, operation for operation, with a select for each branch and min or max as std::min and
// std::max take them, so that every span has the same bits (the rounding to an integer as
// ceilToInt and floorToInt do it, which give std::ceil's and std::floor's integers). Four rows
// then share one square root, and the span pass took a fifth of the rasteriser's samples one row
// at a time (perf, docs/performance.md). Four lanes, not eight: GCC 12 made the eight-lane masks
// scalar code in the AVX-512 build. The one-row loop stays for the baseline build (the footprint
// path, the sweeps' batch maps, CPUs without AVX2), where these lanes, lowered to SSE2 without its
// rounding instructions, took 1.8–1.9 × the loop's time.
[[gnu::always_inline]] inline void spansInLanes(const SpanGeometry& g, int first, int last,
                                                ConeSpan* out, std::size_t& count,
                                                std::size_t& bound) {
  constexpr int kLanes = 4;
  using D = double __attribute__((vector_size(8 * kLanes)));
  using I = std::int32_t __attribute__((vector_size(4 * kLanes)));
  using M = decltype(D{} < D{});  // a lane mask of 64-bit lanes
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // clip() per lane, a's sign being the same for every row: hi = min(hi, b inv) or lo = max(lo,
  // b inv), or hi = −∞ where a is 0 and b negative.
  auto clipLanes = [](double a, double inv, D b, D& lo, D& hi) SG_ROW_INLINE {
    if (a > 0.0) {
      const D x = b * inv;
      hi = x < hi ? x : hi;  // std::min(hi, x)
    } else if (a < 0.0) {
      const D x = b * inv;
      lo = lo < x ? x : lo;  // std::max(lo, x)
    } else {
      hi = b < 0.0 ? D{} - kInf : hi;
    }
  };
  I lane;
  for (int j = 0; j < kLanes; ++j) lane[j] = j;
  for (int dy0 = first; dy0 <= last; dy0 += kLanes) {
    const I dyLanes = dy0 + lane;
    const D y = (__builtin_convertvector(dyLanes, D) + 0.5) - g.ay;
    const D disk = g.reach2 - y * y;
    M inside = disk >= 0.0;
    const D root = inside ? disk : D{};
    D half;
    for (int j = 0; j < kLanes; ++j) half[j] = std::sqrt(root[j]);
    D lo = -half, hi = half;
    clipLanes(g.d1y, g.inv1, g.d1x * y + g.slack, lo, hi);
    clipLanes(-g.d2y, g.inv2, -g.d2x * y + g.slack, lo, hi);
    inside = inside & (lo <= hi);
    // ceilToInt and floorToInt, as truncations corrected by one.
    const D left = inside ? (lo - 0.5) + g.ax : D{};
    const D right = inside ? (hi - 0.5) + g.ax : D{} - 1.0;
    const I tl = __builtin_convertvector(left, I), tr = __builtin_convertvector(right, I);
    I dx0 = tl - __builtin_convertvector(__builtin_convertvector(tl, D) < left, I);
    I dx1 = tr + __builtin_convertvector(__builtin_convertvector(tr, D) > right, I);
    dx0 = dx0 < g.minDx ? I{} + g.minDx : dx0;  // std::max(dx0, minDx)
    dx1 = g.maxDx < dx1 ? I{} + g.maxDx : dx1;  // std::min(dx1, maxDx)
    const I width = __builtin_convertvector(inside, I) != 0 ? dx1 - dx0 + 1 : I{};
    const int n = std::min(kLanes, last - dy0 + 1);
    for (int j = 0; j < n; ++j) {
      out[count] = ConeSpan{dy0 + j, dx0[j], dx1[j]};
      count += width[j] > 0 ? 1 : 0;
      bound += static_cast<std::size_t>(std::max(width[j], 0));
    }
  }
}

}  // namespace detail

// One row of a cone: `count` cells, consecutive in the grid from linear index `cell`, whose table
// entries are entries[0 .. count), every one of them within the reach and the half-angle.
// `heading` is the sensor's heading, moved by a whole turn in a row whose bearings lie across the
// ±π line from it: there bearing − heading is the angle off the axis with no wrap per cell. In a
// row of a mirrored table (BeamTables::View) the bearings are the true ones negated, and so are
// `heading` and `axis`: bearing − heading is then the angle off the axis negated, bit for bit, and
// its absolute value the same. `axis` is the sensor's heading wrapped to [-π, π) (negated there),
// which the row's bearings are compared with before the turn.
struct ConeRow {
  std::uint32_t cell;
  int count;
  const BeamTables::Entry* entries;
  double heading;
  double axis;
  bool mirrored;
};

// row(const ConeRow&) for every row of grid cells whose centres lie within `reach` metres of the
// sensor and within `halfAngle` radians of its axis (halfAngle < 90°), judged by the BeamTables
// entry of each cell: distance <= (float)reach and |bearing − heading| <= halfAngle after one 2π
// correction, and only rows inside `window`. Rows come from the lowest world y. Before the first
// row, reserve(bound) is told how many cells there can be at most. kRound and kSpanLanes are for
// code built for AVX2 or later: rounding in one instruction, and the spans four rows at a time
// (spansInLanes); every span is the same either way.
// Always inlined: coneRuns() builds it into a function for AVX2, where a call to a copy built
// for the baseline would evaluate the rows' eight lanes without AVX.
template <bool kRound = false, bool kSpanLanes = false, class Reserve, class RowFn>
[[gnu::always_inline]] inline void forEachConeRow(const Pose2D& sensor, double reach,
                                                  double halfAngle, const GridSpec& grid,
                                                  const BeamTables& tables, Reserve&& reserve,
                                                  RowFn&& row, RowWindow window = {}) {
  const double c = grid.cellSize;
  // Counted from the grid's base (GridSpec::base): the same bits however the grid grew.
  const GridSpec::Counted at = grid.counted(sensor.position);
  const double u = at.u;
  const double v = at.v;
  const double fu = std::floor(u);
  const double fv = std::floor(v);
  const int q = tables.subdivisions();
  const int qx = std::min(q - 1, static_cast<int>((u - fu) * q));
  const int qy = std::min(q - 1, static_cast<int>((v - fv) * q));
  const int iu = static_cast<int>(fu) + at.shiftX;
  const int iv = static_cast<int>(fv) + at.shiftY;
  // The apex the tables assume: the centre of the sensor's sub-cell, in cell units of its cell.
  const double ax = (qx + 0.5) / q;
  const double ay = (qy + 0.5) / q;

  // The per-cell angle test corrects by 2π once, so the heading itself must be in [-π, π).
  const double h = wrapAngle(sensor.heading);
  const double R = reach / c;
  // The edges' directions by the angle sums, from the heading's sine and cosine and the
  // half-angle's, kept per thread while it is the same (a model's setting): one sine and cosine a
  // reading where cos(h ∓ halfAngle) and sin(h ∓ halfAngle) took two. They are then off by an ulp
  // or two, far within kSlack below: the spans only bound the cells, which the per-cell test picks
  // exactly, so every row gets the same cells.
  thread_local double lastHalf = std::numeric_limits<double>::quiet_NaN(), cosHalf, sinHalf;
  if (!(halfAngle == lastHalf)) {
    lastHalf = halfAngle;
    cosHalf = std::cos(halfAngle);
    sinHalf = std::sin(halfAngle);
  }
  const double ch = std::cos(h), sh = std::sin(h);
  const double d1x = ch * cosHalf + sh * sinHalf, d1y = sh * cosHalf - ch * sinHalf;  // right edge
  const double d2x = ch * cosHalf - sh * sinHalf, d2y = sh * cosHalf + ch * sinHalf;  // left edge
  // Spans are computed for the region grown by kSlack cells (perpendicular distance), far more than
  // the float tables' error, so they hold every cell the per-cell test below accepts.
  constexpr double kSlack = 1e-3;

  // The rows the cone spans: its extent in y is that of the apex, the arc's two ends and, where
  // the arc passes straight up or down, its top or bottom (a row or more of margin each side).
  auto covers = [h, halfAngle](double direction) {
    const double raw = direction - h;
    return std::abs(raw + detail::turn(raw)) <= halfAngle;
  };
  constexpr double kHalfPi = std::numbers::pi / 2.0;
  const double top = covers(kHalfPi) ? R : std::max({0.0, R * d1y, R * d2y});
  const double bottom = covers(-kHalfPi) ? -R : std::min({0.0, R * d1y, R * d2y});
  const int r = tables.radius();
  const int dy0 =
      std::max({-r, detail::floorToInt(ay - 0.5 + bottom - kSlack) - 1, -iv, window.begin - iv});
  const int dy1 = std::min({r, detail::ceilToInt(ay - 0.5 + top + kSlack) + 1, grid.height - 1 - iv,
                            window.end - 1 - iv});
  const double inv1 = 1.0 / d1y, inv2 = 1.0 / -d2y;  // for clip(), unused where 0
  // Per thread, so workers never share it; row must not call forEachConeRow itself. Room for
  // every row of [dy0, dy1] and one more: each row's span is written, and kept (count) only where
  // the cone meets the row, without a branch per row (the rows just above and below the cone, and
  // those the wedge misses, made it mispredict; the one-thread re-map took 0.97 × the time).
  thread_local std::vector<ConeSpan> spans;
  const auto rowsAtMost = static_cast<std::size_t>(std::max(0, dy1 - dy0 + 1));
  if (spans.size() < rowsAtMost + 1) spans.resize(rowsAtMost + 1);
  ConeSpan* const out = spans.data();
  std::size_t count = 0;
  std::size_t bound = 0;
  const double reach2 = (R + kSlack) * (R + kSlack);
  const int minDx = std::max(-r, -iu), maxDx = std::min(r, grid.width - 1 - iu);
  if constexpr (kSpanLanes) {
    detail::spansInLanes(
        detail::SpanGeometry{ay, ax, reach2, d1x, d1y, inv1, d2x, d2y, inv2, kSlack, minDx, maxDx},
        window.firstRow(iv + dy0) - iv, window.lastRow(iv + dy1) - iv, out, count, bound);
  } else {
    window.forEachRow(iv + dy0, iv + dy1, [&](int gridRow) SG_ROW_INLINE {
      const int dy = gridRow - iv;
      const double y = dy + 0.5 - ay;  // row of cell centres, relative to the apex
      const double disk = reach2 - y * y;
      bool inside = disk >= 0.0;
      const double half = std::sqrt(inside ? disk : 0.0);  // once per row, not per cell
      double lo = -half, hi = half;
      // The wedge: left of the right edge, cross(d1, p) >= -slack, and right of the left edge,
      // cross(p, d2) >= -slack (a wedge narrower than 180° is the meet of the two half-planes).
      detail::clip(d1y, inv1, d1x * y + kSlack, lo, hi);
      detail::clip(-d2y, inv2, -d2x * y + kSlack, lo, hi);
      inside = inside && lo <= hi;
      // Cell dx has its centre at x = dx + 0.5 - ax; lo and hi are within ±(R + kSlack) where the
      // cone meets the row (elsewhere hi may be −∞, and 0 and −1 are rounded instead).
      const int dx0 = std::max(detail::ceilToInt<kRound>(inside ? lo - 0.5 + ax : 0.0), minDx);
      const int dx1 = std::min(detail::floorToInt<kRound>(inside ? hi - 0.5 + ax : -1.0), maxDx);
      const int width = inside ? dx1 - dx0 + 1 : 0;
      out[count] = ConeSpan{dy, dx0, dx1};
      count += width > 0 ? 1 : 0;
      bound += static_cast<std::size_t>(std::max(width, 0));
    });
  }
  reserve(bound);

  const BeamTables::View view = tables.view(qx, qy);
  // The heading the view's bearings are compared with: negated with them in a mirrored table, so
  // that every difference below is the true one negated, its absolute value and its turn's test
  // the same bits.
  const double hv = view.mirrored ? -h : h;
  const float reachF = static_cast<float>(reach);
  // The per-cell test. Where |bearing − heading| <= halfAngle already, the turn is 0 (and adding
  // 0.0 changes no bit that abs() keeps), so the test stands; only the other cells, most of them
  // rejected, pay for the turn.
  auto accepts = [&](const BeamTables::Entry& e) {
    if (!(e.distance <= reachF)) return false;
    const double raw = static_cast<double>(e.bearing) - hv;
    return std::abs(raw) <= halfAngle || std::abs(raw + detail::turn(raw)) <= halfAngle;
  };
  // The table is megabytes and a reading touches a few thousand bytes of it, scattered over its
  // rows: ask for all of them before the first is needed, so the misses overlap instead of
  // stalling the row loop one after another. With low locality (prefetcht2 on x86-64), not into
  // the first-level cache: the office log's hundred-odd lines a reading then no longer wait on
  // each other for the L1's few miss buffers, and its one-thread re-map took 0.93–0.94 × the time
  // (docs/performance.md). A row's first four lines and its last, without a loop: a loop of as
  // many lines as the row has left the branch at its end to be mispredicted row after row, and the
  // hardware's own prefetch follows a longer row's middle (the one-thread rasteriser and rows took
  // 0.95 × the time on the workload and on the office log). The addresses are integers, as the
  // lines after the first may lie past the row and past the table, which is harmless for a
  // prefetch but no pointer may point to.
  for (const ConeSpan& span : std::span(out, count)) {
    const BeamTables::Entry* entries = view.row(span.dy);
    const auto first = reinterpret_cast<std::uintptr_t>(entries + span.dx0);
    __builtin_prefetch(reinterpret_cast<const void*>(first), 0, 1);
    __builtin_prefetch(reinterpret_cast<const void*>(first + 64), 0, 1);
    __builtin_prefetch(reinterpret_cast<const void*>(first + 128), 0, 1);
    __builtin_prefetch(reinterpret_cast<const void*>(first + 192), 0, 1);
    __builtin_prefetch(entries + span.dx1, 0, 1);
  }
  for (const ConeSpan& span : std::span(out, count)) {
    const BeamTables::Entry* entries = view.row(span.dy);
    // The cone meets a row of cell centres in one interval: the accepted cells of the span are
    // contiguous (along a row the distance falls then rises, and the bearing is monotonic and on
    // one side of the ±π line, as no row of centres passes through the apex), so trimming the
    // span's ends leaves exactly them.
    int dx0 = span.dx0, dx1 = span.dx1;
    while (dx0 <= dx1 && !accepts(entries[dx0])) ++dx0;
    while (dx1 > dx0 && !accepts(entries[dx1])) --dx1;
    if (dx0 > dx1) continue;
    // The accepted cells of one row are all on one side of the ±π line: the same correction
    // serves them all.
    const double rowHeading = hv - detail::turn(static_cast<double>(entries[dx0].bearing) - hv);
    row(ConeRow{static_cast<std::uint32_t>((iv + span.dy) * grid.width + iu + dx0), dx1 - dx0 + 1,
                entries + dx0, rowHeading, hv, view.mirrored});
  }
}

// fn(std::uint32_t cell, double delta, double theta) for every cell of forEachConeRow, in its
// order (row by row from the lowest world y, each row from the lowest x), theta in [-π, π].
// Before the first call, reserve(bound) is told how many calls there can be at most.
template <class Reserve, class Fn>
void forEachConeCell(const Pose2D& sensor, double reach, double halfAngle, const GridSpec& grid,
                     const BeamTables& tables, Reserve&& reserve, Fn&& fn) {
  forEachConeRow(sensor, reach, halfAngle, grid, tables, std::forward<Reserve>(reserve),
                 [&](const ConeRow& row) {
                   for (int k = 0; k < row.count; ++k) {
                     const BeamTables::Entry e = row.entries[k];
                     const double theta = detail::offAxis(e.bearing, row.axis);
                     fn(row.cell + static_cast<std::uint32_t>(k), static_cast<double>(e.distance),
                        row.mirrored ? -theta : theta);
                   }
                 });
}

// Without a bound: for callers that only count or collect cells.
template <class Fn>
void forEachConeCell(const Pose2D& sensor, double reach, double halfAngle, const GridSpec& grid,
                     const BeamTables& tables, Fn&& fn) {
  forEachConeCell(
      sensor, reach, halfAngle, grid, tables, [](std::size_t) {}, std::forward<Fn>(fn));
}

}  // namespace sg
