// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Helpers shared by the log reader suites: fixture paths and loading with a report.

#include <cmath>
#include <string>

#include "sonargrid/data/dataset.h"
#include "sonargrid/io/log_reader.h"

namespace logtest {

inline std::string fixture(const std::string& name) {
  return std::string(SONARGRID_TEST_DATA) + "/logs/" + name;
}

// what() of the LogError that loading raises, or a description of what happened instead.
inline std::string errorOf(const std::string& path, const sg::LogOptions& options) {
  try {
    sg::readLog(path, options);
  } catch (const sg::LogError& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("unexpected exception: ") + e.what();
  }
  return "no error";
}

// Poses computed through unit conversions or interpolation, equal within rounding.
inline bool near(const sg::Pose2D& a, const sg::Pose2D& b) {
  return std::abs(a.x() - b.x()) < 1e-12 && std::abs(a.y() - b.y()) < 1e-12 &&
         std::abs(a.heading - b.heading) < 1e-12;
}

}  // namespace logtest
