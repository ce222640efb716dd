// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// One entry point for every reference a user may hand to `score`: sonargrid-reference JSON, an
// ArMap `.map` (its LINES) or a ROS map_server `.yaml` (its occupied pixels).

#include <string>

#include "sonargrid/base/log_error.h"
#include "sonargrid/reference/reference_map.h"

namespace sg {

// Chooses the reader by extension (.json; .map; .yaml or .yml) and, for any other name, by the
// first bytes ('{' is JSON, "2D-Map" is ArMap). Throws LogError.
ReferenceMap readReference(const std::string& path);

}  // namespace sg
