// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: sonar geometry files (--robot FILE) (tests/fuzz/README.md).
#include "fuzz_log.h"
#include "sonargrid/io/csv_log.h"
#include "sonargrid/io/text_lines.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  sg::text::MemorySource source(fuzz::view(data, size));
  try {
    const sg::SonarRing ring = sg::readSonarGeometry(source, "fuzz");
    if (ring.sonars.empty() || !(ring.maxRange > ring.minRange)) std::abort();
  } catch (const sg::LogError&) {
  }
  return 0;
}
