// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: reference map JSON (tests/fuzz/README.md).
#include <cstdint>
#include <string_view>

#include "sonargrid/reference/reference_json.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    sg::parseReferenceJson(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz");
  } catch (const sg::LogError&) {
  }
  return 0;
}
