// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The reference map file (docs/metrics.md, "Reference map JSON"):
//   {"format": "sonargrid-reference", "version": 1, "units": "m",
//    "objects": [{"name": "box", "closed": true, "corners": [[1.0, 1.0], [1.5, 1.0], ...]}]}
// `units` is "m", "cm" or "mm"; corners are [x, y] in that unit. Names are unique within a file.
// Optional (docs/formats.md, "World properties"): a circle object {"name", "centre", "radius"},
// an object's "surface" ("specular" or "diffuse") and "specular_limit_deg", a top-level
// "start": {"x", "y", "heading_deg"}.

#include <string>
#include <string_view>

#include "sonargrid/base/log_error.h"
#include "sonargrid/reference/reference_map.h"

namespace sg {

inline constexpr const char* kReferenceFormat = "sonargrid-reference";
inline constexpr int kReferenceVersion = 1;

// Throws LogError naming the file, the line (when it is known) and the field, e.g.
// "room.json:7: objects[1].corners: a closed object needs at least 3 corners".
ReferenceMap readReferenceJson(const std::string& path);
ReferenceMap parseReferenceJson(std::string_view text, const std::string& displayName);

// The file text: the map's own unit, corners written back as read (shortest round-trip form,
// integers without a fraction), one object per line. Throws std::invalid_argument for a map the
// format cannot hold: an obstacle raster, an invalid object or a repeated name.
std::string referenceJsonText(const ReferenceMap& map);
// Atomic (base/atomic_file.h); throws FileWriteError naming the path when it cannot write,
// std::invalid_argument as referenceJsonText.
void writeReferenceJson(const ReferenceMap& map, const std::string& path);

}  // namespace sg
