// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The one entry point for loading a sonar log of any supported format (docs/formats.md, "Choosing
// a reader"): .sglog, CARMEN, Player writelog or generic CSV, chosen by LogOptions::format or, for
// LogFormat::Auto, by the file's first bytes. openLog() gives the log as what every consumer reads
// scans from, a ScanSource (scan_source.h): complete, as a live link's source is when its robot
// has stopped.

#include <string>
#include <string_view>

#include <memory>

#include "sonargrid/data/dataset.h"
#include "sonargrid/engine/scan_source.h"
#include "sonargrid/io/log_options.h"

namespace sg {

// Throws LogError (file, line, field, what was expected) for malformed input, LoadCancelled when
// options.cancel turned true. Either way nothing is returned: a load is complete or it failed.
// `report` (optional) receives the format used and what was skipped.
Dataset readLog(const std::string& path, const LogOptions& options = {},
                LoadReport* report = nullptr);
// The log read by readLog(), as a complete source that shares it.
std::shared_ptr<ScanSource> openLog(const std::string& path, const LogOptions& options = {},
                                    LoadReport* report = nullptr);
Dataset parseLog(std::string_view bytes, const std::string& displayName,
                 const LogOptions& options = {}, LoadReport* report = nullptr);

// The format the first bytes of a log look like, or LogFormat::Auto when they say nothing clear.
LogFormat detectLogFormat(std::string_view head);

// How many bytes of a file detectLogFormat looks at.
inline constexpr std::size_t kDetectBytes = 8192;

}  // namespace sg
