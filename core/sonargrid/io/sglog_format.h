// SPDX-License-Identifier: BSD-3-Clause
// What the .sglog reader (sglog.cpp) and writer (sglog_writer.cpp) share: the record keywords and
// the validity rules. docs/formats.md is the specification of both.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <string_view>

namespace sg::sglog_format {

// Reading::sonar is 16 bits wide.
constexpr std::size_t kMaxSonars = 65536;
constexpr std::size_t kMaxRobotNameBytes = 64;

constexpr std::string_view kMagic = "sglog";
constexpr std::string_view kNone = "none";
constexpr std::string_view kEndHeader = "end_header";
constexpr std::string_view kScan = "scan";
constexpr std::string_view kReading = "r";
// The closing record: a log cut short exactly at a line ending would otherwise read as a valid,
// shorter log.
constexpr std::string_view kEnd = "end";
// The optional header record of a log written as it was recorded (docs/formats.md, "Streamed
// logs"): such a log may end without 'end', after any complete line.
constexpr std::string_view kStreamed = "streamed";
// The optional header record of the robot's pose at the first scan, in the map's frame
// (docs/formats.md, "Start pose"): the reader places the odometry there (start_pose.h).
constexpr std::string_view kStartPose = "start_pose";

// ---------------------------------------------------------------------------------------------
// Shared validity rules: the writer refuses exactly what the reader would reject, so that a file
// we write can always be read back.

inline bool validRobotName(std::string_view s) {
  if (s.empty() || s.size() > kMaxRobotNameBytes) return false;
  return std::all_of(s.begin(), s.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '.' || c == '-';
  });
}

inline bool validAperture(double a) {
  return std::isfinite(a) && a > 0.0 && a <= std::numbers::pi;
}

}  // namespace sg::sglog_format
