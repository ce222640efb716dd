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

#include "sonargrid/dataset.h"
#include "sonargrid/pose.h"
#include "sonargrid/sonar_ring.h"

namespace sg {

// One wall, or one face of an obstacle. Sound reflects off either side.
struct Segment {
  Position a, b;
};

// The segments of a polygon given by its corners; `closed` adds the edge from the last corner back
// to the first (reference maps store obstacles the same way).
std::vector<Segment> polygonSegments(std::span<const Position> corners, bool closed);

struct SonarPhysics {
  double rangeNoiseSd = 0.01;     // metres; zero-mean Gaussian added to every echo
  int raysPerCone = 9;            // rays spread evenly from edge to edge of the aperture (>= 1)
  double maxIncidenceDeg = 60.0;  // beyond this angle from the surface normal the sound reflects
                                  // away (specular) and that ray hears nothing
  double misreadRate = 0.0;       // probability that a reading is a phantom echo, uniform over
                                  // [minRange, maxRange) whatever lies in front of the sensor
  int rangeDecimals = 3;          // readings are reported to 10^-rangeDecimals m (ARCOS sends whole
                                  // millimetres); negative keeps full precision
  double firingInterval = 0.0025;  // seconds between successive transducers of one scan
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
};

// Exact ray-segment intersection against every segment; `direction` must be a unit vector. A ray
// parallel to a segment does not hit it (it would graze it at 90 degrees incidence anyway).
std::optional<RayHit> castRay(std::span<const Segment> world, const Position& origin,
                              const Position& direction);

// Specular reflection: a smooth surface hit too obliquely sends the sound away from the sensor.
bool echoesBack(const RayHit& hit, const SonarPhysics& physics);

// The bearing of ray `i` of `physics.raysPerCone`, relative to the transducer axis.
double rayBearing(int i, double apertureRad, const SonarPhysics& physics);

// The shortest noise-free echo over the cone's rays, if any ray hears one before maxRange.
std::optional<double> coneRange(std::span<const Segment> world, const Pose2D& sensor,
                                const SonarRing& ring, const SonarPhysics& physics);

// One reading of a transducer at world pose `sensor`: the cone's echo plus noise, clamped at the
// ring's minimum range and rounded to the sensor's resolution; Reading::kNoEcho when nothing
// answers before maxRange (including an echo pushed to maxRange or beyond by the noise).
double fireSonar(std::span<const Segment> world, const Pose2D& sensor, const SonarRing& ring,
                 const SonarPhysics& physics, SimRng& rng);

struct TimedPose {
  double time = 0.0;  // seconds
  Pose2D pose;        // robot pose in the world
};

// Fires every sonar of the ring at every route pose (sonar i at time + i * firingInterval, the
// robot taken as standing still meanwhile) with an engine seeded from physics.seed. Odometry and
// truth are both the route pose: odometry drift belongs to the full simulator.
Dataset simulateRoute(std::span<const Segment> world, std::span<const TimedPose> route,
                      const SonarRing& ring, const SonarPhysics& physics, std::string name);

}  // namespace sg
