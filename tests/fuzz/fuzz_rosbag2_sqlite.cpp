// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the rosbag2 SQLite reader (tests/fuzz/README.md). The input is a whole .db3,
// opened from memory: its topics listed, and every message read strictly and leniently. A result
// or a sg::bag::BagError are the only acceptable outcomes.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "sonargrid/io/bag/rosbag2_sqlite.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    const auto reader = sg::bag::openSqliteBytes(bytes, "fuzz.db3");
    const auto& topics = reader->topics();
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
        // Lenient reads throw too when SQLite cannot run the query at all (a corrupt page).
      }
    }
  } catch (const sg::bag::BagError&) {
  }
  return 0;
}
