// SPDX-License-Identifier: BSD-3-Clause
// Generates the bundled "room" log (datasets/README.md):
//   make_room_dataset OUT.sglog [OUT.json]
// writes the simulated sonar log and, when asked, the room's reference map. Both come from the one
// world description below, so the log and its reference cannot drift apart. The output depends on
// nothing but this file and the library: tst_room_dataset regenerates it and compares bytes.

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iostream>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "sonargrid/io/sglog.h"
#include "sonargrid/sim/ray_sonar.h"

namespace {

using sg::Position;

struct Object {
  const char* name;
  std::vector<Position> corners;  // closed polygons, metres
};

// A 6 m x 4 m room with a 0.6 m x 0.4 m box inside the robot's loop and a 5 cm pole between the
// loop and the lower wall. The box is off-centre and the pole on one side, so that the map has no
// mirror symmetry.
std::vector<Object> roomObjects() {
  return {
      {"walls", {{0.0, 0.0}, {6.0, 0.0}, {6.0, 4.0}, {0.0, 4.0}}},
      {"box", {{3.2, 1.8}, {3.8, 1.8}, {3.8, 2.2}, {3.2, 2.2}}},
      {"pole", {{3.975, 0.475}, {4.025, 0.475}, {4.025, 0.525}, {3.975, 0.525}}},
  };
}

constexpr std::uint64_t kSeed = 1985;  // Moravec and Elfes's year
constexpr double kSpeed = 0.3;         // m/s
constexpr int kScanHz = 10;
constexpr int kLaps = 2;
// The loop: a rectangle 1 m inside the walls, x in [1, 5] and y in [1, 3], its corners rounded.
constexpr double kCornerRadius = 0.5;
constexpr double kLoopWidth = 4.0;
constexpr double kLoopHeight = 2.0;

// One piece of the loop: a straight (curvature 0) or a left-turning arc.
struct Piece {
  double length;
  double curvature;  // 1/m
};

std::array<Piece, 8> loopPieces() {
  const Piece arc{0.5 * std::numbers::pi * kCornerRadius, 1.0 / kCornerRadius};
  const Piece along{kLoopWidth - 2.0 * kCornerRadius, 0.0};
  const Piece across{kLoopHeight - 2.0 * kCornerRadius, 0.0};
  return {along, arc, across, arc, along, arc, across, arc};
}

double loopLength() {
  double length = 0.0;
  for (const Piece& p : loopPieces()) length += p.length;
  return length;
}

// Drives `distance` metres along `piece` from `pose`.
sg::Pose2D advance(const sg::Pose2D& pose, const Piece& piece, double distance) {
  const double h0 = pose.heading;
  if (piece.curvature == 0.0) {
    return {pose.x() + distance * std::cos(h0), pose.y() + distance * std::sin(h0), h0};
  }
  const double r = 1.0 / piece.curvature;
  const double h1 = h0 + distance * piece.curvature;
  return {pose.x() + r * (std::sin(h1) - std::sin(h0)),
          pose.y() + r * (std::cos(h0) - std::cos(h1)), h1};
}

double roundTo(double v, double scale) {
  return std::round(v * scale) / scale;
}

// The pose `s` metres along the loop, counter-clockwise from the start of the lower straight.
// Kept to 0.1 mm and 10 microradians: far below what a sonar map resolves, and short exact decimals
// keep the log small and independent of the last bit of the platform's sin and cos.
sg::Pose2D loopPose(double s) {
  s = std::fmod(s, loopLength());
  sg::Pose2D pose(1.0 + kCornerRadius, 1.0, 0.0);
  for (const Piece& piece : loopPieces()) {
    const double d = std::min(s, piece.length);
    pose = advance(pose, piece, d);
    s -= d;
    if (s <= 0.0) break;
  }
  return {roundTo(pose.x(), 1e4), roundTo(pose.y(), 1e4),
          roundTo(sg::wrapAngle(pose.heading), 1e5)};
}

std::vector<sg::TimedPose> route() {
  const double step = kSpeed / kScanHz;
  const int scans = static_cast<int>(std::floor(kLaps * loopLength() / step)) + 1;
  std::vector<sg::TimedPose> out;
  for (int k = 0; k < scans; ++k) {
    // k / 10 is the double nearest to the decimal time, so the log shows "0.3" rather than the
    // "0.30000000000000004" of k * 0.1 or of a running sum.
    const double time = static_cast<double>(k) / kScanHz;
    out.push_back({time, loopPose(static_cast<double>(k) * kSpeed / kScanHz)});
  }
  return out;
}

std::string number(double v) {
  std::array<char, 32> buf{};
  const auto result = std::to_chars(buf.data(), buf.data() + buf.size(), v);  // shortest round-trip
  return std::string(buf.data(), result.ptr);
}

// The reference map format: {"format": "sonargrid-reference", "version": 1, "units": "m",
// "objects": [{"name", "closed", "corners"}]}.
void writeReference(const std::vector<Object>& objects, const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  out << "{\n  \"format\": \"sonargrid-reference\",\n  \"version\": 1,\n  \"units\": \"m\",\n"
      << "  \"objects\": [\n";
  for (std::size_t i = 0; i < objects.size(); ++i) {
    out << "    {\"name\": \"" << objects[i].name << "\", \"closed\": true, \"corners\": [";
    for (std::size_t j = 0; j < objects[i].corners.size(); ++j) {
      const Position& c = objects[i].corners[j];
      out << (j ? ", " : "") << '[' << number(c.x()) << ", " << number(c.y()) << ']';
    }
    out << "]}" << (i + 1 < objects.size() ? "," : "") << '\n';
  }
  out << "  ]\n}\n";
  out.close();
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::cerr << "usage: make_room_dataset OUT.sglog [OUT.json]\n";
    return 2;
  }
  try {
    const std::vector<Object> objects = roomObjects();
    std::vector<sg::Segment> world;
    for (const Object& o : objects) {
      const std::vector<sg::Segment> faces = sg::polygonSegments(o.corners, true);
      world.insert(world.end(), faces.begin(), faces.end());
    }

    // Every setting spelled out, so that a change of default cannot silently change the bundled
    // log. The walls are smooth (painted plaster, a cardboard box): past 30 degrees of incidence
    // they reflect the sound away, which gives the log its specular no-echo readings. With the
    // 60-degree default a 25-degree cone in a closed room almost always has some ray that returns.
    sg::SonarPhysics physics;
    physics.rangeNoiseSd = 0.01;
    physics.raysPerCone = 9;
    physics.maxIncidenceDeg = 30.0;
    physics.misreadRate = 0.0;
    physics.specularEcho = sg::SpecularEcho::None;  // the reflected ray is lost: no multipath
    physics.crosstalkRate = 0.0;
    physics.rangeDecimals = 3;
    physics.firingInterval = 0.0025;
    physics.seed = kSeed;
    const std::vector<sg::TimedPose> poses = route();
    const sg::Dataset dataset = sg::simulateRoute(
        world, poses, sg::SonarRing::pioneer3dx(), physics,
        "room: simulated Pioneer 3-DX sonar in a 6 x 4 m room with a box and a pole, two laps of a "
        "rounded-rectangle loop at 0.3 m/s, 10 Hz scans, ray-cast sonar seed " +
            std::to_string(kSeed));
    sg::writeSglog(dataset, argv[1]);
    if (argc == 3) writeReference(objects, argv[2]);

    std::size_t echoes = 0;
    for (const sg::Scan& s : dataset.scans) {
      for (const sg::Reading& r : s.readings) echoes += r.echo() ? 1 : 0;
    }
    std::cout << argv[1] << ": " << dataset.scans.size() << " scans, " << dataset.readingCount()
              << " readings, " << echoes << " echoes\n";
  } catch (const std::exception& e) {
    std::cerr << "make_room_dataset: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
