// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// CARMEN logs (docs/formats.md, "CARMEN"): one
// message a line, metres and radians. ODOM gives the odometry pose, TRUEPOS the true pose, and each
// SONAR message one scan of every sonar with its mounting pose, so the ring comes from the log
// itself. Every other message (PARAM, SYNC, FLASER...) is skipped and counted.

#include <iosfwd>
#include <string>

#include "sonargrid/data/dataset.h"
#include "sonargrid/io/log_options.h"

namespace sg {

namespace text {
class ByteSource;
}

// Throws LogError naming the file, line and field; with options.lenient a bad line is skipped and
// counted in `report` instead.
Dataset readCarmen(text::ByteSource& source, const std::string& displayName,
                   const LogOptions& options, LoadReport& report);

// One TRUEPOS (when the scan has a true pose), one ODOM and one SONAR line per scan. A sonar
// without a reading in a scan is written at the ring's maximum range (no echo); a sonar read twice
// in one scan starts a second SONAR line. Reading times become the scan's time. The file is written
// atomically (base/atomic_file.h); throws std::runtime_error naming the path when it cannot.
void writeCarmen(const Dataset& dataset, const std::string& path);
void writeCarmen(const Dataset& dataset, std::ostream& out);

}  // namespace sg
