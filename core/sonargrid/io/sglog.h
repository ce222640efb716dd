#pragma once
// The native `.sglog` log: text, versioned header, SI units, the robot and its sonar geometry in
// the header. docs/formats.md is the specification; write followed by read gives back an equal
// Dataset.

#include <iosfwd>
#include <string>

#include "sonargrid/base/log_error.h"
#include "sonargrid/dataset.h"
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

// Writes atomically (base/atomic_file.h: a unique temporary file, synced and renamed over `path`);
// throws std::runtime_error naming the path when it cannot (FileWriteError for a file system
// failure).
void writeSglog(const Dataset& dataset, const std::string& path);
void writeSglog(const Dataset& dataset, std::ostream& out);

}  // namespace sg
