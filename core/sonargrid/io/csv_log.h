// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Generic CSV or whitespace-separated sonar logs (docs/formats.md, "CSV and text columns"): one row
// per scan, the columns named by a CsvLayout, the pose in the same rows or in a second file joined
// on time, and the ring from LogOptions::ring (a preset or a geometry file).

#include <string>

#include "sonargrid/data/dataset.h"
#include "sonargrid/io/log_options.h"

namespace sg {

namespace text {
class ByteSource;
}

// Needs options.csv and options.ring. Throws LogError naming the file, line and field; with
// options.lenient a bad row is skipped and counted in `report` instead.
Dataset readCsvLog(text::ByteSource& source, const std::string& displayName,
                   const LogOptions& options, LoadReport& report);

// A sonar geometry file (docs/formats.md, "Sonar geometry files"): `units`, `aperture`,
// `min_range`, `max_range` and one `sonar X Y HEADING` line per transducer. Throws LogError.
SonarRing readSonarGeometry(const std::string& path);
SonarRing readSonarGeometry(text::ByteSource& source, const std::string& displayName);

}  // namespace sg
