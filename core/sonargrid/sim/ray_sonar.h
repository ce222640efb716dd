// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A minimal, deterministic sonar simulator: the world is a set of line segments, each transducer's
// cone is sampled by a fan of rays, and every physical effect (cone, specular reflection, range
// noise, misreading, range resolution, range window) is its own small function so that the full
// simulator can add effects (multipath, drift, crosstalk) one at a time.
//
// Determinism: the bundled datasets must regenerate byte for byte on every platform, so the random
// numbers come from std::mt19937_64 (its output sequence is fixed by the standard) turned into
// uniform and Gaussian samples by our own code; the standard distributions are
// implementation-defined and are not used.

#include <cstdint>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "sonargrid/data/dataset.h"
#include "sonargrid/data/pose.h"
#include "sonargrid/data/sonar_ring.h"
#include "sonargrid/sim/physics_defaults.h"

namespace sg {

// The incidence limit a surface takes from SonarPhysics::maxIncidenceDeg.
inline constexpr double kPhysicsIncidenceLimit = -1.0;
// A diffuse (rough) surface scatters sound back at any angle of incidence.
inline constexpr double kDiffuseIncidenceLimit = 90.0;

// One wall, or one face of an obstacle. Sound reflects off either side.
struct Segment {
  Position a, b;
  // Specular limit in degrees from the surface normal: a ray meeting the surface more obliquely
  // is reflected away. kPhysicsIncidenceLimit (negative) takes the physics default.
  double maxIncidenceDeg = kPhysicsIncidenceLimit;
};

// A round pole. Whatever the direction of the sensor, the ray through the centre meets it head on.
struct Circle {
  Position centre;
  double radius = 0.0;
  double maxIncidenceDeg = kPhysicsIncidenceLimit;
};

// Everything sound can meet. Implicitly built from segments, as the first worlds were.
struct SonarWorld {
  std::vector<Segment> segments;
  std::vector<Circle> circles;

  SonarWorld() = default;
  SonarWorld(std::vector<Segment> s) : segments(std::move(s)) {}  // NOLINT(google-explicit-*)
  SonarWorld(std::vector<Segment> s, std::vector<Circle> c)
      : segments(std::move(s)), circles(std::move(c)) {}
};

// What a beam does when the surface it meets reflects it away (incidence beyond the limit).
enum class SpecularEcho {
  None,       // the sound is lost: no echo from that ray
  Multipath,  // the sound bounces on; an echo from a later surface returns the way it came, and
              // the sensor reports half the round trip: the whole folded path length
};

// The segments of a polygon given by its corners; `closed` adds the edge from the last corner back
// to the first (reference maps store obstacles the same way).
std::vector<Segment> polygonSegments(std::span<const Position> corners, bool closed);

// Member defaults are the declared ones (physics_parameters.h, docs/simulator.md): the `default`
// preset. The bundled room log and unit tests that need other values spell them out.
struct SonarPhysics {
  // Metres: zero-mean Gaussian noise added to every echo.
  double rangeNoiseSd = physics_default::kNoise;
  // Rays spread evenly from edge to edge of the aperture (>= 1).
  int raysPerCone = physics_default::kRaysPerCone;
  // Beyond this angle from the surface normal the sound reflects away (specular) and that ray
  // hears nothing from that surface.
  double maxIncidenceDeg = physics_default::kSpecularLimitDeg;
  // Probability that a reading is a phantom echo, uniform over [minRange, maxRange) whatever lies
  // in front of the sensor.
  double misreadRate = physics_default::kMisreadRate;
  // Readings are reported to 10^-rangeDecimals m (ARCOS sends whole millimetres); negative keeps
  // full precision.
  int rangeDecimals = 3;
  double firingInterval = 0.0025;  // seconds between successive transducers of one scan
  SpecularEcho specularEcho =
      physics_default::kMultipath ? SpecularEcho::Multipath : SpecularEcho::None;
  // Multipath: reflections followed before the ray is given up.
  int maxBounces = physics_default::kMaxBounces;
  // Multipath path loss: each specular reflection costs this many decibels, and an echo after k
  // reflections with folded range r is heard only if k * loss <= 20 log10(maxRange / r), the
  // margin that spherical spreading leaves over a direct echo from maxRange (docs/simulator.md).
  // 0 dB keeps every reflected echo shorter than maxRange.
  double reflectionLossDb = physics_default::kReflectionLossDb;
  // Probability that a sonar also hears a neighbour's echo (the ring neighbours i - 1 and i + 1,
  // one picked at random); the earlier of its own echo and the neighbour's is reported.
  double crosstalkRate = physics_default::kCrosstalkRate;
  std::uint64_t seed = 1;
};

// The engine every simulated reading draws from.
using SimRng = std::mt19937_64;

// Uniform in [0, 1) from the top 53 bits of one engine output: every double it returns is a
// multiple of 2^-53, exactly the same on every platform.
double uniform01(SimRng& rng);
// Standard normal sample by the Box-Muller transform (the cosine branch; the sine branch is
// dropped so that each sample costs exactly two engine outputs and no state is carried over).
double standardNormal(SimRng& rng);

// The nearest point where a ray meets the world.
struct RayHit {
  double distance = 0.0;      // metres along the ray
  double cosIncidence = 1.0;  // cosine of the angle between the ray and the surface normal
  Position normal{1.0, 0.0};  // unit surface normal at the hit
  double maxIncidenceDeg = kPhysicsIncidenceLimit;  // the surface's specular limit
};

// Exact ray-segment intersection against every segment; `direction` must be a unit vector. A ray
// parallel to a segment does not hit it (it would graze it at 90 degrees incidence anyway).
// Hits closer than `minDistance` are ignored (a reflected ray must not meet its own mirror).
std::optional<RayHit> castRay(std::span<const Segment> world, const Position& origin,
                              const Position& direction, double minDistance = 0.0);
// The same against segments and circles.
std::optional<RayHit> castRay(const SonarWorld& world, const Position& origin,
                              const Position& direction, double minDistance = 0.0);

// Specular reflection: a smooth surface hit too obliquely sends the sound away from the sensor.
// The limit is the surface's own, or physics.maxIncidenceDeg for a surface without one.
bool echoesBack(const RayHit& hit, const SonarPhysics& physics);

// Where an echo comes from: the folded path length (the noise-free range) and the point that sent
// the sound back.
struct Echo {
  double range = 0.0;
  Position point;
};

// One ray followed through the world: its first surface if that echoes back; otherwise nothing, or
// under SpecularEcho::Multipath the first later surface that does, up to physics.maxBounces
// reflections. Nothing when the path reaches maxRange first, or when the reflections' loss
// exceeds the spreading margin (SonarPhysics::reflectionLossDb).
std::optional<Echo> traceRay(const SonarWorld& world, const Position& origin,
                             const Position& direction, double maxRange,
                             const SonarPhysics& physics);

// The bearing of ray `i` of `physics.raysPerCone`, relative to the transducer axis.
double rayBearing(int i, double apertureRad, const SonarPhysics& physics);

// The shortest noise-free echo over the cone's rays, if any ray hears one before maxRange. A
// circle whose centre lies inside the cone also answers from its nearest point, head on, unless
// something nearer hides it: a pole thinner than the gap between two rays is not missed.
std::optional<Echo> coneEcho(const SonarWorld& world, const Pose2D& sensor, const SonarRing& ring,
                             const SonarPhysics& physics);
std::optional<double> coneRange(const SonarWorld& world, const Pose2D& sensor,
                                const SonarRing& ring, const SonarPhysics& physics);

// One reading of a transducer at world pose `sensor`: the cone's echo plus noise, clamped at the
// ring's minimum range and rounded to the sensor's resolution; Reading::kNoEcho when nothing
// answers before maxRange (including an echo pushed to maxRange or beyond by the noise).
double fireSonar(const SonarWorld& world, const Pose2D& sensor, const SonarRing& ring,
                 const SonarPhysics& physics, SimRng& rng);

// Sonar i of `ring` heard through neighbour j: j's echo point must lie inside i's cone, and the
// range is half of the path from j to the point and back to i.
std::optional<double> crosstalkRange(const Echo& neighbourEcho, const Pose2D& listener,
                                     const SonarRing& ring);

// Every sonar of the ring once, sonar i from world pose sensors[i]; the readings in sonar order.
// Random draws per sonar, in order: misreading (when the rate is positive), crosstalk (when its
// rate is positive: one draw, and one more to pick the neighbour when it happens), range noise.
std::vector<double> fireRing(const SonarWorld& world, std::span<const Pose2D> sensors,
                             const SonarRing& ring, const SonarPhysics& physics, SimRng& rng);

struct TimedPose {
  double time = 0.0;  // seconds
  Pose2D pose;        // robot pose in the world
};

// Fires every sonar of the ring at every route pose (sonar i at time + i * firingInterval, the
// robot taken as standing still meanwhile) with an engine seeded from physics.seed. Odometry and
// truth are both the route pose: odometry drift belongs to the full simulator.
Dataset simulateRoute(const SonarWorld& world, std::span<const TimedPose> route,
                      const SonarRing& ring, const SonarPhysics& physics, std::string name);

}  // namespace sg
