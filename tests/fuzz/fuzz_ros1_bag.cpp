// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the ROS 1 bag reader (tests/fuzz/README.md). The input is a whole bag, opened
// from memory; its topics are listed and every topic read strictly and leniently. A result or a
// sg::bag::BagError are the only acceptable outcomes.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>
#include <utility>
#include <vector>

#include "sonargrid/io/bag/bag.h"
#include "sonargrid/io/bag/rosbag1.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  std::unique_ptr<sg::bag::Reader> reader;
  try {
    reader = sg::bag::openRos1(sg::bag::memorySource(bytes, "fuzz"));
  } catch (const sg::bag::BagError&) {
    return 0;
  }
  const std::vector<sg::bag::Topic>& topics = reader->topics();
  const std::vector<bool> all(topics.size(), true);
  std::vector<bool> some(topics.size(), false);  // every other topic: the chunk filter
  for (std::size_t i = 0; i < some.size(); i += 2) some[i] = true;
  for (const bool lenient : {false, true}) {
    for (const std::vector<bool>* wanted : {&all, &std::as_const(some)}) {
      sg::bag::ReadOptions options;
      options.lenient = lenient;
      try {
        reader->read(*wanted, options, [&](const sg::bag::Message& m) {
          if (m.topic >= topics.size() || !(*wanted)[m.topic]) std::abort();  // not asked for
          if (m.offset >= size) std::abort();  // a record that starts outside the file
          volatile char sink = 0;
          for (const char c : m.data) sink = static_cast<char>(sink ^ c);  // the bytes are there
        });
      } catch (const sg::bag::BagError&) {
        if (lenient) std::abort();  // a lenient read counts what is bad and goes on
      }
      if (!lenient && reader->skipped().count != 0) std::abort();  // strict reads skip nothing
    }
  }
  return 0;
}
