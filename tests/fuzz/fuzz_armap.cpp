// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: ArMap .map files (tests/fuzz/README.md).
#include <cstdint>
#include <string_view>

#include "sonargrid/reference/armap_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    sg::parseArMap(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz");
  } catch (const sg::LogError&) {
  }
  return 0;
}
