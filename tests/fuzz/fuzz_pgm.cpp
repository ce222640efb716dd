// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the PGM images of ROS map_server maps (tests/fuzz/README.md).
#include <cstdint>
#include <string_view>

#include "sonargrid/reference/grey_image.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    sg::parsePgm(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz");
  } catch (const sg::LogError&) {
  }
  return 0;
}
