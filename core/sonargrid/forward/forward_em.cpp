// SPDX-License-Identifier: BSD-3-Clause
// The forward model and its EM (forward_em.h; Thrun 2003; docs/forward-model.md).
#include "sonargrid/forward/forward_em.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "sonargrid/base/concurrency.h"
#include "sonargrid/data/scan_poses.h"

namespace sg::forward {

namespace {

// Readings per chunk: the unit of work and of the sums' order (forward_em.h, last paragraph).
constexpr std::size_t kChunk = 4096;

// Runs work(chunk) for every chunk of [0, chunks) on the thread policy's threads, each chunk once.
// Stops handing out chunks when `cancel` turns true. Returns false if it did.
bool forEachChunk(std::size_t chunks, const std::atomic<bool>* cancel,
                  const std::function<void(std::size_t)>& work,
                  const std::atomic<bool>* stop2 = nullptr) {
  const auto stopped = [&] {
    return (cancel && cancel->load(std::memory_order_relaxed)) ||
           (stop2 && stop2->load(std::memory_order_relaxed));
  };
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  const unsigned threads = static_cast<unsigned>(
      std::min<std::size_t>(parallelThreads(), std::max<std::size_t>(1, chunks)));
  runParallel(
      threads,
      [&](unsigned) {
        for (;;) {
          if (stop.load(std::memory_order_relaxed)) return;
          if (stopped()) {
            stop = true;
            return;
          }
          const std::size_t c = next.fetch_add(1);
          if (c >= chunks) return;
          work(c);
        }
      },
      [&] { stop = true; });
  return !stopped();
}

// A chunk's box of cells (inclusive), where its sums go.
struct Box {
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  std::size_t area() const {
    return x1 < x0 ? 0
                   : static_cast<std::size_t>(x1 - x0 + 1) * static_cast<std::size_t>(y1 - y0 + 1);
  }
};

void checkSettings(const ForwardSettings& s) {
  const auto bad = [](const std::string& what) { throw ForwardError("forward model: " + what); };
  if (!(s.omegaDeg > 0.0 && s.omegaDeg < 180.0)) bad("the aperture ω must lie in (0°, 180°)");
  if (!(s.sigma > 0.0 && std::isfinite(s.sigma))) bad("σ must be a positive length");
  if (!(s.pRandom > 0.0 && s.pRandom < 1.0)) bad("p_rand must lie in (0, 1)");
  if (!(s.pMax >= 0.0 && s.pRandom + s.pMax < 1.0)) bad("p_max must lie in [0, 1 − p_rand)");
  if (!(s.pInit > 0.0 && s.pInit < 1.0)) bad("p_init must lie in (0, 1)");
  if (s.iterations < 0) bad("the iteration cap must not be negative");
}

// A beam EM can use: ForwardError naming reading `index` otherwise.
void checkBeam(const ForwardBeam& b, std::size_t index) {
  const auto bad = [&](const std::string& what) {
    throw ForwardError("forward model: reading " + std::to_string(index) + ": " + what);
  };
  if (!(std::isfinite(b.maxRange) && b.maxRange > 0.0))
    bad("the maximum range must be a positive length, got " + std::to_string(b.maxRange));
  if (std::isnan(b.range) || b.range < 0.0)
    bad("the range must be a length or no echo, got " + std::to_string(b.range));
  if (!(std::isfinite(b.sensor.x()) && std::isfinite(b.sensor.y()) &&
        std::isfinite(b.sensor.heading)))
    bad("the transducer's pose is not finite");
}

double gaussian(double x, double sigma) {
  const double t = x / sigma;
  return std::exp(-0.5 * t * t) / (sigma * std::sqrt(2.0 * std::numbers::pi));
}

// The Gaussian as the model uses it: 0 past kCutoffSigmas, scaled to a total of 1 (forward_em.h).
const double kCutMass = std::erf(kCutoffSigmas / std::numbers::sqrt2);
double cutGaussian(double x, double sigma) {
  return std::abs(x) <= kCutoffSigmas * sigma ? gaussian(x, sigma) / kCutMass : 0.0;
}

}  // namespace

std::vector<ParameterSpec> forwardParameterSpecs() {
  const ForwardSettings d;
  return {
      {"omega", "ω", "deg", 5.0, 90.0, d.omegaDeg,
       "Thrun 2003, forward model (the cone of cells a reading meets)",
       "Full aperture of the sonar cone: the cells a reading can meet."},
      {"sigma", "σ", "m", 0.005, 0.5, d.sigma,
       "Thrun 2003, forward model (Gaussian around the cause)",
       "Standard deviation of a range around the distance of the cell that caused it."},
      {"p_rand", "p_rand", "", 0.001, 0.5, d.pRandom,
       "Thrun 2003, forward model (random measurements)",
       "Share of readings that are random, uniform over the sonar's range."},
      {"p_max", "p_max", "", 0.0, 0.5, d.pMax, "Probabilistic Robotics §6.3.1 (max-range failures)",
       "Share of readings that come back without an echo whatever the cone meets (specular "
       "walls)."},
      {"p_init", "p₀", "", 0.01, 0.9, d.pInit, "docs/forward-model.md (EM's start)",
       "Every cell's occupancy where EM starts."},
      {"iterations", "n", "", 1, 500, static_cast<double>(d.iterations),
       "docs/forward-model.md (EM's cap)", "The most EM iterations a map takes.", true},
  };
}

ParameterSet defaultForwardParameters() {
  return ParameterSet(forwardParameterSpecs());
}

ForwardSettings settingsOf(const ParameterSet& params) {
  ForwardSettings s;
  s.omegaDeg = params.get("omega");
  s.sigma = params.get("sigma");
  s.pRandom = params.get("p_rand");
  s.pMax = params.get("p_max");
  s.pInit = params.get("p_init");
  s.iterations = static_cast<int>(std::lround(params.get("iterations")));
  return s;
}

std::vector<ForwardBeam> beamsOf(const Dataset& data, PoseSource source, double until) {
  std::vector<ForwardBeam> beams;
  beams.reserve(data.readingCount());
  for (const Scan& scan : data.scans) {
    if (!hasPose(scan, source)) continue;
    const Pose2D& robot = data.pose(scan, source);
    const Eigen::Matrix2d rotation = robot.rotation();
    for (const Reading& r : scan.readings) {
      if (r.time > until) continue;
      if (r.sonar >= data.ring.size()) {
        throw ForwardError("a reading names sonar " + std::to_string(r.sonar) +
                           " but the ring has " + std::to_string(data.ring.size()));
      }
      ForwardBeam b;
      b.sensor = robot.compose(data.ring.sonars[r.sonar].pose, rotation);
      b.maxRange = data.ring.maxRange;
      b.range = r.range < data.ring.maxRange ? r.range : Reading::kNoEcho;
      beams.push_back(b);
    }
  }
  return beams;
}

namespace {

// Sorts (distance, cell) pairs as std::sort would (by distance, then cell), in buckets of
// `width` metres up to `reach`: a counting sort by bucket, then an insertion sort in each (a
// bucket holds a few cells); a cone's cells come in row order, far from sorted.
void sortByDistance(std::vector<std::pair<float, std::uint32_t>>& v, double width, double reach) {
  if (v.size() < 64) {
    std::sort(v.begin(), v.end());
    return;
  }
  const std::size_t buckets = static_cast<std::size_t>(reach / width) + 2;
  thread_local std::vector<std::uint32_t> start;
  thread_local std::vector<std::pair<float, std::uint32_t>> sorted;
  start.assign(buckets + 1, 0);
  const auto key = [&](float d) {
    return std::min(buckets - 1, static_cast<std::size_t>(static_cast<double>(d) / width));
  };
  for (const auto& e : v) ++start[key(e.first) + 1];
  for (std::size_t b = 1; b <= buckets; ++b) start[b] += start[b - 1];
  sorted.resize(v.size());
  for (const auto& e : v) sorted[start[key(e.first)]++] = e;
  // start[b] is now the end of bucket b; sort within each.
  std::size_t begin = 0;
  for (std::size_t b = 0; b < buckets; ++b) {
    const std::size_t end = start[b];
    for (std::size_t i = begin + 1; i < end; ++i) {
      const auto e = sorted[i];
      std::size_t j = i;
      for (; j > begin && e < sorted[j - 1]; --j) sorted[j] = sorted[j - 1];
      sorted[j] = e;
    }
    begin = end;
  }
  v.swap(sorted);
}

// floor(v) as an int, clamped to [lo, hi] first: a cast of a double out of int's range is
// undefined (a beam far off the grid).
int clampedFloor(double v, int lo, int hi) {
  return static_cast<int>(
      std::clamp(std::floor(v), static_cast<double>(lo), static_cast<double>(hi)));
}

// The cone of one beam, appended as (distance, cell) pairs in detection order.
void coneOf(const ForwardBeam& beam, const GridSpec& grid, const ForwardSettings& s,
            std::vector<std::pair<float, std::uint32_t>>& out) {
  out.clear();
  const bool echo = beam.echo() && std::isfinite(beam.range) && beam.range >= 0.0;
  const double reach =
      echo ? std::min(beam.range + kCutoffSigmas * s.sigma, beam.maxRange) : beam.maxRange;
  if (!(reach > 0.0)) return;
  const double half = s.omegaDeg * std::numbers::pi / 360.0;
  const double cosHalf = std::cos(half);
  const double heading = beam.sensor.heading;
  const double ux = std::cos(heading), uy = std::sin(heading);
  const double sx = beam.sensor.x(), sy = beam.sensor.y();
  // The sector's box: the apex, both edges' ends, and the arc's extremes on the axes it spans.
  double lx = sx, hx = sx, ly = sy, hy = sy;
  const auto take = [&](double a) {
    const double px = sx + reach * std::cos(a), py = sy + reach * std::sin(a);
    lx = std::min(lx, px), hx = std::max(hx, px), ly = std::min(ly, py), hy = std::max(hy, py);
  };
  take(heading - half);
  take(heading + half);
  for (int q = 0; q < 4; ++q) {
    const double a = q * std::numbers::pi / 2.0;
    if (std::abs(wrapAngle(a - heading)) <= half) take(a);
  }
  const double c = grid.cellSize;
  const int x0 = clampedFloor((lx - grid.origin.x()) / c, 0, grid.width);
  const int x1 = clampedFloor((hx - grid.origin.x()) / c, -1, grid.width - 1);
  const int y0 = clampedFloor((ly - grid.origin.y()) / c, 0, grid.height);
  const int y1 = clampedFloor((hy - grid.origin.y()) / c, -1, grid.height - 1);
  const double reach2 = reach * reach;
  // Each row's cells between the cone's edges and inside its arc, from the half-planes
  // cross(right edge, p) >= 0 and cross(p, left edge) >= 0 (the wedge, for an aperture under
  // 180°) and |dx| <= √(reach² − dy²), widened by a cell; the exact test below decides.
  const double rx = std::cos(heading - half), ry = std::sin(heading - half);
  const double lxe = std::cos(heading + half), lye = std::sin(heading + half);
  const double ox = grid.origin.x();
  for (int y = y0; y <= y1; ++y) {
    const double dy = grid.origin.y() + (y + 0.5) * c - sy;
    if (dy * dy > reach2) continue;
    const double arc = std::sqrt(reach2 - dy * dy);
    double lo = -arc, hi = arc;
    const auto bound = [&](double a, double b) {  // a·dx >= b
      if (a > 0.0)
        lo = std::max(lo, b / a);
      else if (a < 0.0)
        hi = std::min(hi, b / a);
      else if (b > 0.0)
        hi = lo - 1.0;  // no dx
    };
    bound(-ry, -rx * dy);
    bound(lye, lxe * dy);
    if (hi < lo) continue;
    const int first = std::max(x0, clampedFloor((sx + lo - ox) / c - 0.5, -2, grid.width) - 1);
    const int last = std::min(x1, clampedFloor((sx + hi - ox) / c + 0.5, -2, grid.width) + 1);
    for (int x = first; x <= last; ++x) {
      const double dx = ox + (x + 0.5) * c - sx;
      const double d2 = dx * dx + dy * dy;
      if (d2 > reach2 || d2 == 0.0) continue;
      const double d = std::sqrt(d2);
      if (dx * ux + dy * uy < d * cosHalf) continue;
      out.emplace_back(static_cast<float>(d),
                       static_cast<std::uint32_t>(static_cast<std::size_t>(y) * grid.width + x));
    }
  }
  sortByDistance(out, c / 8.0, reach);
}

}  // namespace

namespace {

// A chunk of consecutive readings with its cones, as EM works on them: each cone's cells are slots
// of the chunk's box (a row-major window of the grid), so that the map's values and the sums of
// the chunk are arrays of the box alone.
struct Chunk {
  std::size_t begin = 0, end = 0;  // readings [begin, end)
  Box box;
  std::vector<std::uint64_t> first;  // reading begin + i owns entries [first[i], first[i + 1])
  std::vector<std::uint32_t> slot;
  std::vector<float> distance;
  std::vector<double> m, a, b;  // the map over the box, and the chunk's two sums
  double logL = 0.0;

  std::size_t slotOf(const GridSpec& grid, std::uint32_t cell) const {
    const int x = static_cast<int>(cell % static_cast<std::uint32_t>(grid.width));
    const int y = static_cast<int>(cell / static_cast<std::uint32_t>(grid.width));
    return static_cast<std::size_t>(y - box.y0) * static_cast<std::size_t>(box.x1 - box.x0 + 1) +
           static_cast<std::size_t>(x - box.x0);
  }
  // Calls f(slot, cell) for every cell of the box, row by row.
  template <class F>
  void forBox(const GridSpec& grid, F&& f) const {
    std::size_t i = 0;
    for (int y = box.y0; y <= box.y1 && box.area() != 0; ++y) {
      const std::size_t row = static_cast<std::size_t>(y) * static_cast<std::size_t>(grid.width);
      for (int x = box.x0; x <= box.x1; ++x) f(i++, row + static_cast<std::size_t>(x));
    }
  }
};

std::vector<Chunk> chunksOf(const std::vector<ForwardBeam>& beams, const GridSpec& grid,
                            const ForwardSettings& s) {
  const std::size_t count = (beams.size() + kChunk - 1) / kChunk;
  std::vector<Chunk> chunks(count);
  forEachChunk(count, nullptr, [&](std::size_t ch) {
    Chunk& c = chunks[ch];
    c.begin = ch * kChunk;
    c.end = std::min(beams.size(), c.begin + kChunk);
    c.first.assign(1, 0);
    c.box.x0 = grid.width, c.box.y0 = grid.height;
    std::vector<std::pair<float, std::uint32_t>> cone;
    for (std::size_t r = c.begin; r < c.end; ++r) {
      coneOf(beams[r], grid, s, cone);
      for (const auto& [d, cell] : cone) {
        c.distance.push_back(d);
        c.slot.push_back(cell);  // the grid's index until the box is known
        const int x = static_cast<int>(cell % static_cast<std::uint32_t>(grid.width));
        const int y = static_cast<int>(cell / static_cast<std::uint32_t>(grid.width));
        c.box.x0 = std::min(c.box.x0, x), c.box.x1 = std::max(c.box.x1, x);
        c.box.y0 = std::min(c.box.y0, y), c.box.y1 = std::max(c.box.y1, y);
      }
      c.first.push_back(c.slot.size());
    }
    for (std::uint32_t& v : c.slot) v = static_cast<std::uint32_t>(c.slotOf(grid, v));
    c.slot.shrink_to_fit();
    c.distance.shrink_to_fit();
  });
  return chunks;
}

// One reading's terms under the map `m` of its chunk's box: the distances' Gaussians N_k, T_k
// (what the cells after k contribute, given they are reached: T_{K−1} = [no echo], T_k = m_{k+1}
// N_{k+1} + (1 − m_{k+1}) T_{k+1}), and the reading's probability p (forward_em.h).
struct ReadingTerms {
  std::vector<double> n, t;
  double randomTerm = 0.0;  // p_rand Δ / z_max, and p_max for no echo
  double scale = 1.0;       // Δ for an echo's density, 1 for the no-echo event
  double weight = 0.0;      // 1 − p_rand − p_max
  double p = 0.0;
};

void termsOf(const Chunk& c, std::size_t i, const ForwardBeam& beam, const ForwardSettings& s,
             double cellSize, ReadingTerms& out) {
  const std::uint64_t b = c.first[i], e = c.first[i + 1];
  const std::size_t k = e - b;
  const bool echo = beam.echo();
  out.n.resize(k);
  out.t.resize(k);
  const double cut = kCutoffSigmas * s.sigma;
  for (std::size_t j = 0; j < k; ++j) {
    const double x = beam.range - static_cast<double>(c.distance[b + j]);
    out.n[j] = echo && std::abs(x) <= cut ? gaussian(x, s.sigma) / kCutMass : 0.0;  // cutGaussian
  }
  double after = echo ? 0.0 : 1.0;
  for (std::size_t j = k; j-- > 0;) {
    out.t[j] = after;
    const double mj = c.m[c.slot[b + j]];
    after = mj * out.n[j] + (1.0 - mj) * after;
  }
  out.randomTerm = s.pRandom * cellSize / beam.maxRange + (echo ? 0.0 : s.pMax);
  out.scale = echo ? cellSize : 1.0;
  out.weight = 1.0 - s.pRandom - s.pMax;
  out.p = out.randomTerm + out.weight * out.scale * after;
}

}  // namespace

Cones conesOf(const std::vector<ForwardBeam>& beams, const GridSpec& grid,
              const ForwardSettings& s) {
  checkSettings(s);
  for (std::size_t i = 0; i < beams.size(); ++i) checkBeam(beams[i], i);
  const std::vector<Chunk> chunks = chunksOf(beams, grid, s);
  Cones out;
  for (const Chunk& c : chunks) {
    const std::size_t boxWidth = static_cast<std::size_t>(c.box.x1 - c.box.x0 + 1);
    for (std::size_t i = 0; i + 1 < c.first.size(); ++i) {
      for (std::uint64_t e = c.first[i]; e < c.first[i + 1]; ++e) {
        const std::size_t x = c.box.x0 + c.slot[e] % boxWidth;
        const std::size_t y = c.box.y0 + c.slot[e] / boxWidth;
        out.cell.push_back(static_cast<std::uint32_t>(y * grid.width + x));
        out.distance.push_back(c.distance[e]);
      }
      out.first.push_back(out.cell.size());
    }
  }
  for (const ForwardBeam& b : beams) {
    out.range.push_back(b.echo() ? static_cast<float>(b.range)
                                 : std::numeric_limits<float>::infinity());
    out.maxRange.push_back(static_cast<float>(b.maxRange));
  }
  return out;
}

EmResult runEm(const std::vector<ForwardBeam>& beams, const GridSpec& grid,
               const ForwardSettings& s, const std::atomic<bool>* cancel,
               const std::function<void(const EmProgress&)>& progress,
               const std::atomic<bool>* stop) {
  checkSettings(s);
  for (std::size_t i = 0; i < beams.size(); ++i) checkBeam(beams[i], i);
  if (grid.cellCount() == 0) throw ForwardError("forward model: the grid has no cells");
  std::vector<Chunk> chunks = chunksOf(beams, grid, s);
  const std::size_t cells = grid.cellCount();
  const double cellSize = grid.cellSize;

  EmResult result;
  result.readings = beams.size();
  std::vector<std::uint8_t> observed(cells, 0);
  for (const Chunk& c : chunks) {
    result.coneCells += c.slot.size();
    std::vector<std::uint8_t> met(c.box.area(), 0);
    for (const std::uint32_t v : c.slot) met[v] = 1;
    c.forBox(grid, [&](std::size_t i, std::size_t cell) { observed[cell] |= met[i]; });
  }

  std::vector<double> m(cells, s.pInit);
  // Gives each chunk the map over its box.
  const auto gather = [&](Chunk& c) {
    c.m.resize(c.box.area());
    c.forBox(grid, [&](std::size_t i, std::size_t cell) { c.m[i] = m[cell]; });
  };
  // Adds each chunk's `part` into `total`, chunk after chunk (the order of the sums).
  const auto merge = [&](std::vector<double> Chunk::*part, std::vector<double>& total) {
    std::fill(total.begin(), total.end(), 0.0);
    for (const Chunk& c : chunks) {
      const std::vector<double>& v = c.*part;
      c.forBox(grid, [&](std::size_t i, std::size_t cell) { total[cell] += v[i]; });
    }
  };

  const auto eStep = [&]() -> bool {
    return forEachChunk(
        chunks.size(), cancel,
        [&](std::size_t ch) {
          Chunk& c = chunks[ch];
          gather(c);
          c.a.assign(c.box.area(), 0.0);
          c.b.assign(c.box.area(), 0.0);
          ReadingTerms t;
          double logL = 0.0;
          for (std::size_t i = 0; i + 1 < c.first.size(); ++i) {
            termsOf(c, i, beams[c.begin + i], s, cellSize, t);
            logL += std::log(t.p);
            const double f = t.weight * t.scale / t.p;
            double reached = 1.0;  // Π_{k'<k} (1 − m_k')
            const std::uint64_t b = c.first[i];
            for (std::size_t j = 0; j < t.n.size(); ++j) {
              const std::uint32_t at = c.slot[b + j];
              const double mj = c.m[at];
              c.a[at] += f * mj * reached * t.n[j];
              c.b[at] += f * reached * (1.0 - mj) * t.t[j];
              reached *= 1.0 - mj;
            }
          }
          c.logL = logL;
        },
        stop);
  };

  std::vector<double> hits(cells), passes(cells);
  for (int it = 0;; ++it) {
    if (!eStep()) {
      result.cancelled = true;
      return result;
    }
    double logL = 0.0;
    for (const Chunk& c : chunks) logL += c.logL;
    result.logLikelihood.push_back(logL);
    if (progress) progress({it, s.iterations, logL});
    if (it > 0) {
      const double gain = logL - result.logLikelihood[static_cast<std::size_t>(it) - 1];
      if (gain <= kRelativeTolerance * std::abs(logL)) {
        result.converged = true;
        break;
      }
    }
    if (it >= s.iterations) break;
    if ((cancel && cancel->load()) || (stop && stop->load())) {
      result.cancelled = true;
      return result;
    }
    // The M-step: m_j = A_j / (A_j + B_j), the maximum of A_j log m_j + B_j log(1 − m_j).
    merge(&Chunk::a, hits);
    merge(&Chunk::b, passes);
    for (std::size_t c = 0; c < cells; ++c) {
      const double n = hits[c] + passes[c];
      if (n > 0.0) m[c] = hits[c] / n;
    }
    result.iterations = it + 1;
  }

  // The expected hits and passes under m* (the last E-step's), for the posterior's prior.
  merge(&Chunk::a, hits);
  merge(&Chunk::b, passes);

  // The posterior: each cell's log-odds with the others held at m* (forward_em.h).
  const bool done = forEachChunk(
      chunks.size(), cancel,
      [&](std::size_t ch) {
        Chunk& c = chunks[ch];
        gather(c);
        c.a.assign(c.box.area(), 0.0);
        c.b.clear();
        c.b.shrink_to_fit();
        ReadingTerms t;
        for (std::size_t i = 0; i + 1 < c.first.size(); ++i) {
          termsOf(c, i, beams[c.begin + i], s, cellSize, t);
          const double g = t.weight * t.scale;
          double before = 0.0;   // Σ_{k'<k} m_k' Π_{k''<k'} (1 − m_k'') N_k'
          double reached = 1.0;  // Π_{k'<k} (1 − m_k')
          const std::uint64_t b = c.first[i];
          for (std::size_t j = 0; j < t.n.size(); ++j) {
            const std::uint32_t at = c.slot[b + j];
            const double mj = c.m[at];
            const double p1 = t.randomTerm + g * (before + reached * t.n[j]);
            const double p0 = t.randomTerm + g * (before + reached * t.t[j]);
            c.a[at] += std::log(p1 / p0);
            before += mj * reached * t.n[j];
            reached *= 1.0 - mj;
          }
        }
      },
      stop);
  if (!done) {
    result.cancelled = true;
    return result;
  }
  std::vector<double> logOdds(cells);
  merge(&Chunk::a, logOdds);
  chunks.clear();

  OccupancyMap& map = result.map;
  map.spec = grid;
  map.model = kModelName;
  map.rule = kRuleName;
  std::vector<double> probability(cells, 0.5), evidence(cells, 0.0);
  std::vector<std::uint8_t> filled(cells, 0);
  map.level.assign(cells, levelOfProbability(0.5));
  for (std::size_t c = 0; c < cells; ++c) {
    if (!observed[c]) continue;
    // The cell's prior: the Laplace estimate of its occupancy from EM's expected hits and passes,
    // (A + 1) / (A + B + 2), whose log-odds are log((A + 1) / (B + 1)).
    const double l = std::log((hits[c] + 1.0) / (passes[c] + 1.0)) + logOdds[c];
    const double p = 1.0 / (1.0 + std::exp(-l));
    probability[c] = p;
    evidence[c] = std::max(0.0, 2.0 * p - 1.0);
    filled[c] = p > 0.5 ? 1 : 0;
    map.level[c] = levelOfProbability(p);
  }
  map.probability = std::move(probability);
  map.native = m;  // EM's occupancy, every cell (p_init where no reading met it)
  map.evidence = std::move(evidence);
  map.filled = std::move(filled);
  map.observed = std::move(observed);
  result.occupancy = std::move(m);
  return result;
}

bool isForwardModelMap(const OccupancyMap& map) {
  return map.model == kModelName && map.rule == kRuleName;
}

RangePrediction predictRange(const ForwardBeam& beam, const GridSpec& grid,
                             const std::vector<double>& occupancy, const ForwardSettings& s,
                             const std::vector<double>& ranges) {
  checkSettings(s);
  checkBeam(beam, 0);
  if (occupancy.size() != grid.cellCount())
    throw ForwardError("forward model: the occupancy is not the grid's size");
  ForwardBeam whole = beam;
  whole.range = Reading::kNoEcho;  // the whole cone, to the transducer's reach
  std::vector<std::pair<float, std::uint32_t>> cone;
  coneOf(whole, grid, s, cone);
  const double w = 1.0 - s.pRandom - s.pMax;
  RangePrediction out;
  out.density.assign(ranges.size(), 0.0);
  double reached = 1.0;
  for (const auto& [d, c] : cone) {
    const double cause = w * occupancy[c] * reached;  // this cell is the first occupied one
    for (std::size_t i = 0; i < ranges.size(); ++i)
      out.density[i] += cause * cutGaussian(ranges[i] - static_cast<double>(d), s.sigma);
    reached *= 1.0 - occupancy[c];
  }
  for (std::size_t i = 0; i < ranges.size(); ++i)
    if (ranges[i] >= 0.0 && ranges[i] < beam.maxRange) out.density[i] += s.pRandom / beam.maxRange;
  // As the likelihood counts a no-echo reading: nothing met, a failure, or a random reading in the
  // last bin of width Δ.
  out.noEcho = w * reached + s.pMax + s.pRandom * grid.cellSize / beam.maxRange;
  return out;
}

}  // namespace sg::forward
