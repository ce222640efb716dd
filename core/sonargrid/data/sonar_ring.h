// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Sonar mounting and rings. Presets follow the manufacturers' published geometry
// (docs/live-robot.md, docs/formats.md).

#include <string>
#include <string_view>
#include <vector>

#include "sonargrid/data/pose.h"

namespace sg {

struct SonarMount {
  Pose2D pose;  // robot frame: metres, radians
};

struct SonarRing {
  std::string robot = "custom";  // preset name, or "custom"
  std::vector<SonarMount> sonars;
  double apertureRad = degToRad(25.0);  // full cone angle of the transducer
  double minRange = 0.15;               // metres
  double maxRange = 5.0;                // metres; readings at or beyond it are "no echo"

  std::size_t size() const { return sonars.size(); }
  bool operator==(const SonarRing&) const = default;

  // Pioneer 3-DX front and rear arrays, 16 sonars.
  static SonarRing pioneer3dx();
  // AmigoBot, 8 sonars.
  static SonarRing amigobot();
  // Cybermation K2A (paper 000 §4.1): 24 sonars 15 degrees apart on a circle of `radius` metres.
  static SonarRing k2a(double radius = 0.3);
  // `count` sonars evenly spaced on a circle, the first one facing forward.
  static SonarRing circular(int count, double radius);

  // Looks up a preset by name ("p3dx", "amigobot", "k2a"); returns false when unknown.
  static bool preset(std::string_view name, SonarRing& out);
  static std::vector<std::string> presetNames();
};

inline bool operator==(const SonarMount& a, const SonarMount& b) {
  return a.pose == b.pose;
}

}  // namespace sg
