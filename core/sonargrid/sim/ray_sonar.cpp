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
                              const Position& direction) {
  std::optional<RayHit> nearest;
  for (const Segment& s : world) {
    // origin + t * direction = a + u * (b - a), solved with 2-D cross products.
    const Position edge = s.b - s.a;
    const double denom = cross(direction, edge);
    if (denom == 0.0) continue;
    const Position w = s.a - origin;
    const double t = cross(w, edge) / denom;
    const double u = cross(w, direction) / denom;
    if (t < 0.0 || u < 0.0 || u > 1.0) continue;
    if (!nearest || t < nearest->distance) {
      // |direction x edge| = |edge| * sin(angle to the surface) = |edge| * cos(incidence).
      nearest = RayHit{t, std::abs(denom) / edge.norm()};
    }
  }
  return nearest;
}

bool echoesBack(const RayHit& hit, const SonarPhysics& physics) {
  return hit.cosIncidence >= std::cos(degToRad(physics.maxIncidenceDeg));
}

double rayBearing(int i, double apertureRad, const SonarPhysics& physics) {
  if (physics.raysPerCone == 1) return 0.0;
  return -0.5 * apertureRad + apertureRad * i / (physics.raysPerCone - 1);
}

std::optional<double> coneRange(std::span<const Segment> world, const Pose2D& sensor,
                                const SonarRing& ring, const SonarPhysics& physics) {
  if (physics.raysPerCone < 1)
    throw std::invalid_argument("SonarPhysics: raysPerCone must be >= 1");
  std::optional<double> nearest;
  for (int i = 0; i < physics.raysPerCone; ++i) {
    const double bearing = sensor.heading + rayBearing(i, ring.apertureRad, physics);
    const Position direction(std::cos(bearing), std::sin(bearing));
    // A ray that glances off its nearest surface is lost: it does not go on to a farther one.
    const std::optional<RayHit> hit = castRay(world, sensor.position, direction);
    if (!hit || !echoesBack(*hit, physics) || hit->distance >= ring.maxRange) continue;
    if (!nearest || hit->distance < *nearest) nearest = hit->distance;
  }
  return nearest;
}

double fireSonar(std::span<const Segment> world, const Pose2D& sensor, const SonarRing& ring,
                 const SonarPhysics& physics, SimRng& rng) {
  double range = 0.0;
  if (misreads(physics, rng)) {
    range = phantomRange(ring, rng);
  } else {
    const std::optional<double> echo = coneRange(world, sensor, ring, physics);
    if (!echo) return Reading::kNoEcho;
    range = addRangeNoise(*echo, physics, rng);
  }
  range = quantize(std::max(range, ring.minRange), physics);
  // The ring's convention: a reading at or beyond maxRange is no echo.
  return range >= ring.maxRange ? Reading::kNoEcho : range;
}

Dataset simulateRoute(std::span<const Segment> world, std::span<const TimedPose> route,
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
    for (std::size_t i = 0; i < ring.size(); ++i) {
      Reading r;
      r.sonar = static_cast<std::uint16_t>(i);
      // Kept to the microsecond, a log's finest time unit: short, exact decimals in the text log.
      r.time =
          std::round((stop.time + static_cast<double>(i) * physics.firingInterval) * 1e6) / 1e6;
      r.range = fireSonar(world, stop.pose.compose(ring.sonars[i].pose), ring, physics, rng);
      scan.readings.push_back(r);
    }
    out.scans.push_back(std::move(scan));
  }
  return out;
}

}  // namespace sg
