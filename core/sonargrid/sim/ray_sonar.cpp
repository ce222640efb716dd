// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/sim/ray_sonar.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace sg {
namespace {

double cross(const Position& u, const Position& v) {
  return u.x() * v.y() - u.y() * v.x();
}

// Phantom echo (crosstalk, a misfire): a range that has nothing to do with the world.
bool misreads(const SonarPhysics& physics, SimRng& rng) {
  // No draw when the effect is off, so that the noise sequence of existing datasets stays the same.
  return physics.misreadRate > 0.0 && uniform01(rng) < physics.misreadRate;
}

double phantomRange(const SonarRing& ring, SimRng& rng) {
  return ring.minRange + (ring.maxRange - ring.minRange) * uniform01(rng);
}

double addRangeNoise(double range, const SonarPhysics& physics, SimRng& rng) {
  if (physics.rangeNoiseSd <= 0.0) return range;
  return range + physics.rangeNoiseSd * standardNormal(rng);
}

// Rounds to the reported resolution. Dividing the rounded integer by a power of ten gives the
// double nearest to that decimal, so the log shows short numbers; and a last-bit difference in a
// platform's sin/cos/log changes what is written only if it straddles a rounding boundary.
double quantize(double range, const SonarPhysics& physics) {
  if (physics.rangeDecimals < 0) return range;
  double scale = 1.0;  // exact for any sensible number of decimals, unlike a libm pow()
  for (int i = 0; i < physics.rangeDecimals; ++i) scale *= 10.0;
  return std::round(range * scale) / scale;
}

// Path loss of a multipath echo (docs/simulator.md, "Multipath"): spherical spreading from the
// image source leaves a margin of 20 log10(maxRange / range) dB over a direct echo from maxRange,
// the weakest the sensor detects; each reflection costs reflectionLossDb of it. Without loss (or
// without a reflection) every echo shorter than maxRange is heard, as before the loss existed.
bool heardAfterReflections(int reflections, double range, double maxRange,
                           const SonarPhysics& physics) {
  if (reflections == 0 || physics.reflectionLossDb <= 0.0) return true;
  return static_cast<double>(reflections) * physics.reflectionLossDb <=
         20.0 * std::log10(maxRange / range);
}

}  // namespace

std::vector<Segment> polygonSegments(std::span<const Position> corners, bool closed) {
  std::vector<Segment> out;
  for (std::size_t i = 1; i < corners.size(); ++i) out.push_back({corners[i - 1], corners[i]});
  if (closed && corners.size() > 2) out.push_back({corners.back(), corners.front()});
  return out;
}

double uniform01(SimRng& rng) {
  static_assert(SimRng::word_size == 64);
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

double standardNormal(SimRng& rng) {
  // 1 - u lies in (0, 1], so the logarithm is finite.
  const double u1 = 1.0 - uniform01(rng);
  const double u2 = uniform01(rng);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

std::optional<RayHit> castRay(std::span<const Segment> world, const Position& origin,
                              const Position& direction, double minDistance) {
  std::optional<RayHit> nearest;
  for (const Segment& s : world) {
    // origin + t * direction = a + u * (b - a), solved with 2-D cross products.
    const Position edge = s.b - s.a;
    const double denom = cross(direction, edge);
    if (denom == 0.0) continue;
    const Position w = s.a - origin;
    const double t = cross(w, edge) / denom;
    const double u = cross(w, direction) / denom;
    if (t < minDistance || u < 0.0 || u > 1.0) continue;
    if (!nearest || t < nearest->distance) {
      // |direction x edge| = |edge| * sin(angle to the surface) = |edge| * cos(incidence).
      const double length = edge.norm();
      nearest = RayHit{t, std::abs(denom) / length, Position(-edge.y(), edge.x()) / length,
                       s.maxIncidenceDeg};
    }
  }
  return nearest;
}

std::optional<RayHit> castRay(const SonarWorld& world, const Position& origin,
                              const Position& direction, double minDistance) {
  std::optional<RayHit> nearest =
      castRay(std::span<const Segment>(world.segments), origin, direction, minDistance);
  for (const Circle& c : world.circles) {
    // |origin + t * direction - centre|^2 = r^2 with |direction| = 1.
    const Position oc = origin - c.centre;
    const double b = direction.dot(oc);
    const double disc = b * b - (oc.squaredNorm() - c.radius * c.radius);
    if (disc < 0.0) continue;
    const double root = std::sqrt(disc);
    double t = -b - root;                // entering the circle
    if (t < minDistance) t = -b + root;  // the ray starts inside: it meets the far side
    if (t < minDistance || (nearest && t >= nearest->distance)) continue;
    const Position normal = (oc + t * direction) / c.radius;
    nearest = RayHit{t, std::min(1.0, std::abs(direction.dot(normal))), normal, c.maxIncidenceDeg};
  }
  return nearest;
}

bool echoesBack(const RayHit& hit, const SonarPhysics& physics) {
  const double limit = hit.maxIncidenceDeg >= 0.0 ? hit.maxIncidenceDeg : physics.maxIncidenceDeg;
  return hit.cosIncidence >= std::cos(degToRad(limit));
}

std::optional<Echo> traceRay(const SonarWorld& world, const Position& origin,
                             const Position& direction, double maxRange,
                             const SonarPhysics& physics) {
  // Far below any range the sensor resolves, far above the rounding error of a hit point.
  constexpr double kSelfHit = 1e-9;
  Position from = origin;
  Position dir = direction;
  double travelled = 0.0;
  const int bounces = physics.specularEcho == SpecularEcho::Multipath ? physics.maxBounces : 0;
  for (int bounce = 0; bounce <= bounces; ++bounce) {
    const std::optional<RayHit> hit = castRay(world, from, dir, bounce == 0 ? 0.0 : kSelfHit);
    if (!hit) return std::nullopt;
    travelled += hit->distance;
    if (travelled >= maxRange) return std::nullopt;
    const Position point = from + hit->distance * dir;
    if (echoesBack(*hit, physics)) {
      if (!heardAfterReflections(bounce, travelled, maxRange, physics)) return std::nullopt;
      return Echo{travelled, point};
    }
    // Mirror reflection: the normal component of the direction changes sign.
    dir = dir - 2.0 * dir.dot(hit->normal) * hit->normal;
    from = point;
  }
  return std::nullopt;
}

double rayBearing(int i, double apertureRad, const SonarPhysics& physics) {
  if (physics.raysPerCone == 1) return 0.0;
  return -0.5 * apertureRad + apertureRad * i / (physics.raysPerCone - 1);
}

std::optional<Echo> coneEcho(const SonarWorld& world, const Pose2D& sensor, const SonarRing& ring,
                             const SonarPhysics& physics) {
  if (physics.raysPerCone < 1)
    throw std::invalid_argument("SonarPhysics: raysPerCone must be >= 1");
  std::optional<Echo> nearest;
  for (int i = 0; i < physics.raysPerCone; ++i) {
    const double bearing = sensor.heading + rayBearing(i, ring.apertureRad, physics);
    const Position direction(std::cos(bearing), std::sin(bearing));
    const std::optional<Echo> echo =
        traceRay(world, sensor.position, direction, ring.maxRange, physics);
    if (echo && (!nearest || echo->range < nearest->range)) nearest = echo;
  }
  // Poles: the ray through the centre meets the surface head on, wherever the sensor stands.
  for (const Circle& c : world.circles) {
    const Position toCentre = c.centre - sensor.position;
    const double distance = toCentre.norm();
    if (distance <= c.radius) continue;
    const double off = wrapAngle(std::atan2(toCentre.y(), toCentre.x()) - sensor.heading);
    if (std::abs(off) > 0.5 * ring.apertureRad) continue;
    const Position direction = toCentre / distance;
    const std::optional<Echo> echo =
        traceRay(world, sensor.position, direction, ring.maxRange, physics);
    if (echo && (!nearest || echo->range < nearest->range)) nearest = echo;
  }
  return nearest;
}

std::optional<double> coneRange(const SonarWorld& world, const Pose2D& sensor,
                                const SonarRing& ring, const SonarPhysics& physics) {
  const std::optional<Echo> echo = coneEcho(world, sensor, ring, physics);
  if (!echo) return std::nullopt;
  return echo->range;
}

std::optional<double> crosstalkRange(const Echo& neighbourEcho, const Pose2D& listener,
                                     const SonarRing& ring) {
  const Position back = neighbourEcho.point - listener.position;
  const double off = wrapAngle(std::atan2(back.y(), back.x()) - listener.heading);
  if (std::abs(off) > 0.5 * ring.apertureRad) return std::nullopt;
  const double range = 0.5 * (neighbourEcho.range + back.norm());
  if (range >= ring.maxRange) return std::nullopt;
  return range;
}

namespace {

// The reported number for a noise-free echo (or none): misreading, noise, range window, rounding.
double reading(std::optional<double> echo, const SonarRing& ring, const SonarPhysics& physics,
               SimRng& rng, bool misread) {
  double range = 0.0;
  if (misread) {
    range = phantomRange(ring, rng);
  } else {
    if (!echo) return Reading::kNoEcho;
    range = addRangeNoise(*echo, physics, rng);
  }
  range = quantize(std::max(range, ring.minRange), physics);
  // The ring's convention: a reading at or beyond maxRange is no echo.
  return range >= ring.maxRange ? Reading::kNoEcho : range;
}

}  // namespace

double fireSonar(const SonarWorld& world, const Pose2D& sensor, const SonarRing& ring,
                 const SonarPhysics& physics, SimRng& rng) {
  if (misreads(physics, rng)) return reading(std::nullopt, ring, physics, rng, true);
  return reading(coneRange(world, sensor, ring, physics), ring, physics, rng, false);
}

std::vector<double> fireRing(const SonarWorld& world, std::span<const Pose2D> sensors,
                             const SonarRing& ring, const SonarPhysics& physics, SimRng& rng) {
  const std::size_t n = ring.size();
  if (sensors.size() != n)
    throw std::invalid_argument("fireRing: one sensor pose per sonar of the ring is needed");
  std::vector<std::optional<Echo>> echoes(n);
  for (std::size_t i = 0; i < n; ++i) echoes[i] = coneEcho(world, sensors[i], ring, physics);
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (misreads(physics, rng)) {
      out[i] = reading(std::nullopt, ring, physics, rng, true);
      continue;
    }
    std::optional<double> range;
    if (echoes[i]) range = echoes[i]->range;
    if (physics.crosstalkRate > 0.0 && n > 1 && uniform01(rng) < physics.crosstalkRate) {
      const std::size_t j = uniform01(rng) < 0.5 ? (i + n - 1) % n : (i + 1) % n;
      if (echoes[j]) {
        const std::optional<double> heard = crosstalkRange(*echoes[j], sensors[i], ring);
        if (heard && (!range || *heard < *range)) range = heard;
      }
    }
    out[i] = reading(range, ring, physics, rng, false);
  }
  return out;
}

Dataset simulateRoute(const SonarWorld& world, std::span<const TimedPose> route,
                      const SonarRing& ring, const SonarPhysics& physics, std::string name) {
  Dataset out;
  out.name = std::move(name);
  out.ring = ring;
  out.scans.reserve(route.size());
  SimRng rng(physics.seed);
  for (const TimedPose& stop : route) {
    Scan scan;
    scan.time = stop.time;
    scan.odometry = stop.pose;
    scan.truth = stop.pose;
    scan.readings.reserve(ring.size());
    std::vector<Pose2D> sensors;
    sensors.reserve(ring.size());
    for (const SonarMount& m : ring.sonars) sensors.push_back(stop.pose.compose(m.pose));
    const std::vector<double> ranges = fireRing(world, sensors, ring, physics, rng);
    for (std::size_t i = 0; i < ring.size(); ++i) {
      Reading r;
      r.sonar = static_cast<std::uint16_t>(i);
      // Kept to the microsecond, a log's finest time unit: short, exact decimals in the text log.
      r.time =
          std::round((stop.time + static_cast<double>(i) * physics.firingInterval) * 1e6) / 1e6;
      r.range = ranges[i];
      scan.readings.push_back(r);
    }
    out.scans.push_back(std::move(scan));
  }
  return out;
}

}  // namespace sg
