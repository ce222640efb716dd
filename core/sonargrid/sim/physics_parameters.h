// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The simulator's physics, declared once like the model parameters (parameters.h): name, symbol,
// unit, range, default and source. SonarPhysics's member defaults, `sonargrid-cli simulate` and
// docs/simulator.md all come from here; tst_physics_parameters checks that they agree.
//
// Three named presets (docs/simulator.md, "Presets"):
//   clean    an ideal sonar: every surface echoes, no multipath, no misreadings, no crosstalk;
//   default  the declared defaults, each justified by a cited source or the mild end of its range;
//   harsh    the settings `simulate` used before the declaration existed (lossless multipath up to
//            3 reflections, a 20° specular limit, 1 % misreadings): it rewrites those logs byte for
//            byte.

#include <optional>
#include <string>
#include <vector>

#include "sonargrid/data/sonar_ring.h"
#include "sonargrid/params/parameters.h"
#include "sonargrid/sim/differential_drive.h"
#include "sonargrid/sim/physics_defaults.h"
#include "sonargrid/sim/ray_sonar.h"

namespace sg {

// Every declared physics parameter, in the order docs/simulator.md lists them.
const std::vector<ParameterSpec>& physicsParameterSpecs();

// The declared defaults (the `default` preset).
ParameterSet defaultPhysicsParameters();

// "clean", "default", "harsh".
const std::vector<std::string>& physicsPresetNames();
// The preset's values (ParameterSet over physicsParameterSpecs()); nothing for an unknown name.
std::optional<ParameterSet> physicsPreset(const std::string& name);

// The parameters written into the simulator's settings: sonar physics (the seed is left alone),
// the ring's range window, and the odometry errors used when drift is on.
void applyPhysics(const ParameterSet& values, SonarPhysics& physics, SonarRing& ring);
OdometryErrors driftErrors(const ParameterSet& values);

// The parameter values a SonarPhysics, ring window and drift stand for (the inverse of the two
// above), so that a test can compare SonarPhysics{} with the declaration.
ParameterSet physicsParameters(const SonarPhysics& physics, const SonarRing& ring,
                               const OdometryErrors& drift);

}  // namespace sg
