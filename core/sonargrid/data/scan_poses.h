// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Scans without the pose a map is asked for. A recording from a simulator whose first SIP comes
// before its first SIMSTAT (AMRISim and MobileSim do this) stores that scan without a true pose;
// a bag's scans outside its true pose topic's span have none either. Mapped with PoseSource::Truth,
// such scans are left out (the mapper, the cell trace, the sweeps' beams and the fitting grid
// alike) and counted here, so that the CLI and the app can say how many; odometry is never put in
// their place, which would mix two frames in one map.

#include <algorithm>
#include <cstddef>

#include "sonargrid/data/dataset.h"

namespace sg {

// Whether `scan` has the pose of `source` (every scan has odometry).
inline bool hasPose(const Scan& scan, PoseSource source) {
  return source == PoseSource::Odometry || scan.truth.has_value();
}

// The scans of `d` without the pose of `source`: left out of a map made with it.
inline std::size_t scansWithoutPose(const Dataset& d, PoseSource source) {
  return static_cast<std::size_t>(std::count_if(
      d.scans.begin(), d.scans.end(), [&](const Scan& s) { return !hasPose(s, source); }));
}

// Whether a map made with `source` has any scan to map: false for a log without a single true pose
// (or without scans) and PoseSource::Truth.
inline bool anyScanHasPose(const Dataset& d, PoseSource source) {
  return std::any_of(d.scans.begin(), d.scans.end(),
                     [&](const Scan& s) { return hasPose(s, source); });
}

// The message of a map refused for want of any true pose; the caller says how to fix it ("map with
// odometry (--pose odom)").
inline constexpr const char* kNoTruePose = "the log has no true pose in any scan";

}  // namespace sg
