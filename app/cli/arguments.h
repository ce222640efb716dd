// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A small, strict command-line reader: every flag is consumed once, anything left over is an error
// that names it. Errors are UsageError, which main() turns into exit status 2.

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace sg::cli {

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Thrown for input the user must fix (unreadable log, incompatible pair): also exit status 2.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Arguments {
 public:
  explicit Arguments(std::vector<std::string> args) : args_(std::move(args)) {}

  // Removes "--name" and returns true when present.
  bool flag(const std::string& name);
  // Removes "--name VALUE" (or "--name=VALUE") and returns VALUE; a flag without a value throws.
  std::optional<std::string> value(const std::string& name);
  // Every occurrence of "--name VALUE", in order.
  std::vector<std::string> values(const std::string& name);
  std::string required(const std::string& name);
  double number(const std::string& name, double fallback, double min, double max);
  int integer(const std::string& name, int fallback, int min, int max);
  // Removes and returns every argument that is not a flag (does not start with "--"), in order:
  // call it after consuming the flags that take values.
  std::vector<std::string> positionals();
  // Throws naming the first argument nobody consumed.
  void finish() const;

 private:
  std::vector<std::string> args_;
};

double parseNumber(const std::string& text, const std::string& what);
// A --seed value: a whole number that fits 64 bits.
std::uint64_t parseSeed(const std::string& text);

}  // namespace sg::cli
