// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The one error type of every log and map reader: it names the file, the line and the field, and
// says what was expected (docs/formats.md, "Errors"). It lives below io/ and reference/ because
// both kinds of reader throw it.

#include <cstddef>
#include <stdexcept>
#include <string>

namespace sg {

class LogError : public std::runtime_error {
 public:
  // line 0 means "the file as a whole" (cannot open, empty, truncated); field may be empty.
  LogError(std::string file, std::size_t line, std::string field, std::string message);

  const std::string& file() const { return file_; }
  std::size_t line() const { return line_; }
  const std::string& field() const { return field_; }
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  std::size_t line_;
  std::string field_;
  std::string message_;
};

}  // namespace sg
