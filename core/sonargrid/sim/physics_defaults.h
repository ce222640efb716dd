// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The default of every simulator physics parameter, apart from their declaration
// (physics_parameters.h) so that SonarPhysics (ray_sonar.h) can take its member defaults from
// here. docs/simulator.md gives each value's source.

namespace sg {

namespace physics_default {
inline constexpr double kNoise = 0.01;               // m, Polaroid 6500: ±1 % of the reading
inline constexpr double kSpecularLimitDeg = 30.0;    // per ray; Cao & Borenstein 2002: ±42° walls
inline constexpr bool kMultipath = true;             // Kuc & Siegel 1987: smooth walls are mirrors
inline constexpr int kMaxBounces = 1;                // mild end
inline constexpr double kReflectionLossDb = 6.0;     // mild end, no measured source
inline constexpr double kMisreadRate = 0.0;          // mild end, no measured source
inline constexpr double kCrosstalkRate = 0.0;        // mild end, no measured source
inline constexpr int kRaysPerCone = 9;               // sampling of the 25° cone, 3.125° apart
inline constexpr double kMinRange = 0.15;            // m, Polaroid 6500: 6 inches
inline constexpr double kMaxRange = 10.0;            // m, Polaroid 6500: 35 ft, rounded down
inline constexpr double kDriftWheelScale = 0.00025;  // ±, UMBmark-type systematic error
inline constexpr double kDriftWheelbaseScale = 0.005;
inline constexpr double kDriftWheelNoise = 0.001;  // m per √m
}  // namespace physics_default

}  // namespace sg
