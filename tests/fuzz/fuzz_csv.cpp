// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the CSV reader and the --columns spec. The input's first line is the column
// spec, the rest the log (tests/fuzz/README.md).
#include <stdexcept>

#include "fuzz_log.h"
#include "sonargrid/io/csv_layout.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes = fuzz::view(data, size);
  const std::size_t nl = bytes.find('\n');
  if (nl == std::string_view::npos) return 0;
  sg::LogOptions o;
  o.format = sg::LogFormat::Csv;
  try {
    o.csv = sg::parseCsvLayout(bytes.substr(0, nl));
  } catch (const std::invalid_argument&) {
    return 0;
  }
  if (o.csv->sonars.size() > 256) return 0;  // a ring that large only slows the search down
  o.ring = sg::SonarRing::circular(static_cast<int>(o.csv->sonars.size()), 0.2);
  fuzz::readBothWays(bytes.substr(nl + 1), o);
  return 0;
}
