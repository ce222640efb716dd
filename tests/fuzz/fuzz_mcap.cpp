// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the MCAP reader (tests/fuzz/README.md). The input is a whole file: it is
// opened, its topics listed, and every message read strictly and leniently. A result or a
// sg::bag::BagError are the only acceptable outcomes.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "sonargrid/io/bag/mcap.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    const auto reader = sg::bag::openMcap(sg::bag::memorySource(bytes, "fuzz.mcap"));
    const auto& topics = reader->topics();
    std::size_t names = 0;
    for (const sg::bag::Topic& t : topics) names += t.name.size() + t.type.size();
    (void)names;
    const std::vector<bool> wanted(topics.size(), true);
    for (const bool lenient : {false, true}) {
      sg::bag::ReadOptions options;
      options.lenient = lenient;
      try {
        reader->read(wanted, options, [&](const sg::bag::Message& m) {
          if (m.topic >= topics.size()) std::abort();  // a message that names no topic
          volatile char sink = m.data.empty() ? 0 : m.data.back();
          (void)sink;
        });
      } catch (const sg::bag::BagError&) {
        if (lenient) std::abort();  // a lenient read skips what it cannot read
      }
    }
  } catch (const sg::bag::BagError&) {
  }
  return 0;
}
