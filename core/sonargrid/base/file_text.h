// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Whole-file reading and line splitting for the readers of small files (reference maps, routes,
// ROS map YAML and images), and the quoting of offending text in their errors. Such files are
// small; the size cap keeps a wrong or hostile path (a device, a multi-gigabyte log) from being
// read whole before we can say anything about it.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace sg::file_text {

inline constexpr std::size_t kMaxReferenceBytes = 64u * 1024u * 1024u;

// The file's bytes. Throws LogError(path, 0, "", reason) when it cannot be opened or read, is not a
// regular file, or is larger than `maxBytes`.
std::string readFileBytes(const std::string& path, std::size_t maxBytes = kMaxReferenceBytes);

// The text split into lines (without their "\n" or "\r\n"), numbered from 1 by position.
std::vector<std::string_view> splitLines(std::string_view text);

// At most `max` bytes of `s` for an error message, with "..." when cut, control bytes escaped.
std::string shown(std::string_view s, std::size_t max = 40);

}  // namespace sg::file_text
