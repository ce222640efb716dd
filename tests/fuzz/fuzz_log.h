// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The body of every log-reader fuzz target: the input is a whole log, read strictly and leniently.
// A Dataset or a LogError are the only acceptable outcomes; anything else (a crash, a sanitizer
// report, another exception escaping) is a finding.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "sonargrid/io/log_reader.h"

namespace fuzz {

inline void checkDataset(const sg::Dataset& d) {
  for (const sg::Scan& s : d.scans) {
    for (const sg::Reading& r : s.readings) {
      if (r.sonar >= d.ring.size()) std::abort();  // a reader let a reading name no sonar
    }
  }
}

inline void readBothWays(std::string_view bytes, sg::LogOptions options) {
  for (const bool lenient : {false, true}) {
    options.lenient = lenient;
    try {
      checkDataset(sg::parseLog(bytes, "fuzz", options));
    } catch (const sg::LogError&) {
    }
  }
}

inline std::string_view view(const std::uint8_t* data, std::size_t size) {
  return std::string_view(reinterpret_cast<const char*>(data), size);
}

}  // namespace fuzz
