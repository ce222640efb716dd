// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/reference/read_reference.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "sonargrid/base/file_text.h"
#include "sonargrid/reference/armap_reader.h"
#include "sonargrid/reference/reference_json.h"
#include "sonargrid/reference/ros_map_reader.h"

namespace sg {

ReferenceMap readReference(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".yaml" || ext == ".yml") return rosMapAsReference(readRosMap(path));
  if (ext == ".map") return readArMap(path);
  if (ext == ".json") return readReferenceJson(path);

  const std::string bytes = file_text::readFileBytes(path);
  const auto first = bytes.find_first_not_of(" \t\r\n");
  if (first != std::string::npos && bytes[first] == '{') return parseReferenceJson(bytes, path);
  if (bytes.rfind("2D-Map", 0) == 0 || bytes.rfind("\xEF\xBB\xBF"
                                                   "2D-Map",
                                                   0) == 0) {
    return parseArMap(bytes, path);
  }
  throw LogError(
      path, 0, "",
      "unknown reference format: expected sonargrid-reference JSON (.json), an ArMap (.map) "
      "or a ROS map_server map (.yaml)");
}

}  // namespace sg
