// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: format detection and whichever reader it picks (tests/fuzz/README.md).
#include "fuzz_log.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  sg::LogOptions o;
  o.ring = sg::SonarRing::amigobot();
  fuzz::readBothWays(fuzz::view(data, size), o);
  return 0;
}
