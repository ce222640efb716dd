// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/base/log_error.h"

#include <utility>

namespace sg {
namespace {

// One formatting rule for every reader, so that editors and IDEs that understand compiler-style
// "file:line:" prefixes can jump straight to the offending line.
std::string formatWhat(const std::string& file, std::size_t line, const std::string& field,
                       const std::string& message) {
  std::string out = file;
  if (line != 0) {
    out += ':';
    out += std::to_string(line);
  }
  out += ": ";
  if (!field.empty()) {
    out += field;
    out += ": ";
  }
  out += message;
  return out;
}

}  // namespace

LogError::LogError(std::string file, std::size_t line, std::string field, std::string message)
    : std::runtime_error(formatWhat(file, line, field, message)),
      file_(std::move(file)),
      line_(line),
      field_(std::move(field)),
      message_(std::move(message)) {}

}  // namespace sg
