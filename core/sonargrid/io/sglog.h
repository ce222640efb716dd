// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The native `.sglog` log: text, versioned header, SI units, the robot and its sonar geometry in
// the header. docs/formats.md is the specification; write followed by read gives back an equal
// Dataset.

#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>

#include "sonargrid/base/log_error.h"
#include "sonargrid/data/dataset.h"
#include "sonargrid/io/log_options.h"

namespace sg {

inline constexpr int kSglogVersion = 1;

// Throws LogError (file, line, field, what was expected) on any malformed or truncated input.
Dataset readSglog(const std::string& path);
Dataset parseSglog(std::istream& in, const std::string& displayName);

namespace text {
class ByteSource;
}
// The reader behind readLog (log_reader.h): lenient skipping, progress and cancel.
Dataset readSglog(text::ByteSource& source, const std::string& displayName,
                  const LogOptions& options, LoadReport& report);

// The pieces of a log written as it is recorded (sglog_recorder.h), formatted by the same code as
// writeSglog. The header holds the name and ring of `header` (its scans are ignored) and, when
// `streamed`, the 'streamed' record that lets the log end without 'end' (docs/formats.md,
// "Streamed logs"), and `startPose` as the 'start_pose' record. appendSglogScan appends one scan's
// lines to `out`. Both throw std::runtime_error when the reader would reject what they write (a
// scan earlier than `previousTime`, a reading naming a sonar outside `ring`, a non-finite
// number...).
std::string sglogHeaderText(const Dataset& header, bool streamed,
                            const std::optional<Pose2D>& startPose = std::nullopt);
void appendSglogScan(std::string& out, const Scan& scan, const SonarRing& ring,
                     double previousTime);
inline constexpr std::string_view kSglogEndLine = "end\n";

// Writes atomically (base/atomic_file.h: a unique temporary file, synced and renamed over `path`);
// throws std::runtime_error naming the path when it cannot (FileWriteError for a file system
// failure).
void writeSglog(const Dataset& dataset, const std::string& path);
void writeSglog(const Dataset& dataset, std::ostream& out);

}  // namespace sg
