// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What a client must know about a robot to read its SIPs: the conversion factors from robot units
// to millimetres and radians, and its sonar ring. The values are those of the robots' published
// parameter files (ARIA's p3dx and amigo robot types; docs/live-robot.md, "Robots").

#include <numbers>
#include <optional>
#include <string>
#include <string_view>

#include "sonargrid/data/sonar_ring.h"

namespace sg::arcos {

struct RobotParameters {
  std::string preset = "custom";  // "p3dx", "amigobot" or "custom"
  double distConvFactor = 1.0;    // mm per XPOS/YPOS unit (DistConvFactor)
  double angleConvFactor = 2.0 * std::numbers::pi / 4096.0;  // rad per THPOS unit
  double velConvFactor = 1.0;    // mm/s per LVEL/RVEL unit (VelConvFactor)
  double rangeConvFactor = 1.0;  // mm per sonar range unit (RangeConvFactor)
  double vel2Divisor = 20.0;     // mm/s per VEL2 wheel unit (Vel2Divisor)
  double maxRangeMm = 5000.0;    // a sonar reading at or beyond it heard no echo
  double wheelbase = 0.33;       // metres between the drive wheels (for LVEL/RVEL)
  SonarRing ring;                // its maxRange is maxRangeMm / 1000

  bool operator==(const RobotParameters&) const = default;
};

// Pioneer 3-DX: DistConvFactor 0.485, RangeConvFactor 1, 16 sonars.
RobotParameters pioneer3dxParameters();
// AmigoBot: DistConvFactor 0.5083, VelConvFactor 0.6154, RangeConvFactor 1, 8 sonars.
RobotParameters amigobotParameters();

// "p3dx" or "amigobot"; nothing for another name.
std::optional<RobotParameters> robotPreset(std::string_view name);
std::string robotPresetNames();  // "p3dx, amigobot"

// The parameters of the subclass a robot reports in its handshake, case-insensitively: "p3dx" and
// its variants ("p3dx-sh", ...) are a Pioneer 3-DX, "amigo", "amigo-sh" and "amigobot" an
// AmigoBot. Nothing for any other subclass.
std::optional<RobotParameters> parametersForSubclass(std::string_view subclass);

}  // namespace sg::arcos
