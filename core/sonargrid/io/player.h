// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Player writelog logs (docs/formats.md, "Player"): `time host robot interface index type subtype
// payload...` for Player 2.x/3.x and `time host robot interface index payload...` for 1.x (told
// apart by the `## Player version` comment; 2.x/3.x when there is none). Sonar ranges come from
// `sonar` or `ranger` data, the pose from `position2d` (1.x: `position`), the geometry from the
// sonar geometry messages or, when the log has none, from LogOptions::ring.

#include <string>

#include "sonargrid/data/dataset.h"
#include "sonargrid/io/log_options.h"

namespace sg {

namespace text {
class ByteSource;
}

// Throws LogError naming the file, line and field; with options.lenient a bad line is skipped and
// counted in `report` instead.
Dataset readPlayer(text::ByteSource& source, const std::string& displayName,
                   const LogOptions& options, LoadReport& report);

}  // namespace sg
