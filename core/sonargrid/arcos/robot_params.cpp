// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/arcos/robot_params.h"

#include <algorithm>
#include <cctype>
#include <string>

namespace sg::arcos {
namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

void setRing(RobotParameters& p, SonarRing ring) {
  ring.maxRange = p.maxRangeMm / 1000.0;
  p.ring = std::move(ring);
}

}  // namespace

RobotParameters pioneer3dxParameters() {
  RobotParameters p;
  p.preset = "p3dx";
  p.distConvFactor = 0.485;
  p.velConvFactor = 1.0;
  p.rangeConvFactor = 1.0;
  p.wheelbase = 0.33;
  setRing(p, SonarRing::pioneer3dx());
  return p;
}

RobotParameters amigobotParameters() {
  RobotParameters p;
  p.preset = "amigobot";
  p.distConvFactor = 0.5083;
  p.velConvFactor = 0.6154;
  p.rangeConvFactor = 1.0;
  p.wheelbase = 0.28;
  setRing(p, SonarRing::amigobot());
  return p;
}

std::optional<RobotParameters> robotPreset(std::string_view name) {
  if (name == "p3dx") return pioneer3dxParameters();
  if (name == "amigobot") return amigobotParameters();
  return std::nullopt;
}

std::string robotPresetNames() {
  return "p3dx, amigobot";
}

std::optional<RobotParameters> parametersForSubclass(std::string_view subclass) {
  const std::string s = lower(subclass);
  if (s == "p3dx" || s.starts_with("p3dx-")) return pioneer3dxParameters();
  if (s == "amigo" || s == "amigobot" || s.starts_with("amigo-")) return amigobotParameters();
  return std::nullopt;
}

}  // namespace sg::arcos
