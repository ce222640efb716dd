// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/data/sonar_ring.h"

#include <array>
#include <cmath>

namespace sg {
namespace {

struct MountMmDeg {
  double xMm, yMm, headingDeg;
};

SonarRing fromTable(std::string name, const MountMmDeg* table, std::size_t n) {
  SonarRing ring;
  ring.robot = std::move(name);
  ring.sonars.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    ring.sonars.push_back(SonarMount{
        Pose2D(table[i].xMm / 1000.0, table[i].yMm / 1000.0, degToRad(table[i].headingDeg))});
  }
  return ring;
}

}  // namespace

SonarRing SonarRing::pioneer3dx() {
  static constexpr std::array<MountMmDeg, 16> kTable{{
      {69, 136, 90},
      {114, 119, 50},
      {148, 78, 30},
      {166, 27, 10},
      {166, -27, -10},
      {148, -78, -30},
      {114, -119, -50},
      {69, -136, -90},
      {-157, -136, -90},
      {-203, -119, -130},
      {-237, -78, -150},
      {-255, -27, -170},
      {-255, 27, 170},
      {-237, 78, 150},
      {-203, 119, 130},
      {-157, 136, 90},
  }};
  return fromTable("p3dx", kTable.data(), kTable.size());
}

SonarRing SonarRing::amigobot() {
  static constexpr std::array<MountMmDeg, 8> kTable{{
      {76, 100, 90},
      {125, 75, 41},
      {150, 30, 15},
      {150, -30, -15},
      {125, -75, -41},
      {76, -100, -90},
      {-140, -58, -145},
      {-140, 58, 145},
  }};
  return fromTable("amigobot", kTable.data(), kTable.size());
}

SonarRing SonarRing::circular(int count, double radius) {
  SonarRing ring;
  ring.sonars.reserve(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    const double a = wrapAngle(2.0 * std::numbers::pi * i / count);
    ring.sonars.push_back(SonarMount{Pose2D(radius * std::cos(a), radius * std::sin(a), a)});
  }
  return ring;
}

SonarRing SonarRing::k2a(double radius) {
  SonarRing ring = circular(24, radius);
  ring.robot = "k2a";
  return ring;
}

bool SonarRing::preset(std::string_view name, SonarRing& out) {
  if (name == "p3dx") {
    out = pioneer3dx();
  } else if (name == "amigobot") {
    out = amigobot();
  } else if (name == "k2a") {
    out = k2a();
  } else {
    return false;
  }
  return true;
}

std::vector<std::string> SonarRing::presetNames() {
  return {"p3dx", "amigobot", "k2a"};
}

}  // namespace sg
