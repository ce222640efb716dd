// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the YAML of ROS map_server maps. readRosMap takes a path, so each input is
// written to a private temporary folder beside a small valid image, box.pgm, that the YAML may
// name (tests/fuzz/README.md).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "sonargrid/reference/ros_map_reader.h"

namespace {

std::string folder() {
  static const std::string dir = [] {
    char pattern[] = "/tmp/fuzz_ros_yaml.XXXXXX";
    if (mkdtemp(pattern) == nullptr) std::abort();
    std::ofstream image(std::string(pattern) + "/box.pgm", std::ios::binary);
    image << "P2\n3 2\n255\n0 205 254\n254 0 205\n";
    return std::string(pattern);
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string yaml = folder() + "/map.yaml";
  {
    std::ofstream out(yaml, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    const sg::RosMap map = sg::readRosMap(yaml);
    sg::rosMapAsReference(map);
    sg::rosMapAsBuiltMap(map);
  } catch (const sg::LogError&) {
  }
  return 0;
}
