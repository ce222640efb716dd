// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// ArMap `.map` files (MobileRobots / Adept ARIA, MobileSim, AMRISim) as reference maps
// (docs/formats.md, "ArMap"). Only the LINES section is used: each wall segment
// `x1 y1 x2 y2` (integer millimetres) becomes an open two-corner object named "line N" (N counts
// the segments from 1, in file order). DATA points are laser returns, not measured geometry, and
// are skipped. Header lines (`Key: values`) are not interpreted: the Num* counts are often wrong
// in the wild, so the segments are counted as they are read.

#include <string>
#include <string_view>

#include "sonargrid/base/log_error.h"
#include "sonargrid/reference/reference_map.h"

namespace sg {

// The map keeps millimetres as its unit, so saving it as reference JSON writes the integers back.
// Throws LogError naming the file, the line and the field.
ReferenceMap readArMap(const std::string& path);
ReferenceMap parseArMap(std::string_view text, const std::string& displayName);

}  // namespace sg
