// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the Player writelog reader, with and without a robot preset
// (tests/fuzz/README.md).
#include "fuzz_log.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  sg::LogOptions o;
  o.format = sg::LogFormat::Player;
  fuzz::readBothWays(fuzz::view(data, size), o);
  o.ring = sg::SonarRing::pioneer3dx();
  fuzz::readBothWays(fuzz::view(data, size), o);
  return 0;
}
