// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/io/log_options.h"

#include <algorithm>
#include <array>

namespace sg {
namespace {

constexpr std::array<std::pair<LogFormat, std::string_view>, 6> kNames{{
    {LogFormat::Auto, "auto"},
    {LogFormat::Sglog, "sglog"},
    {LogFormat::Carmen, "carmen"},
    {LogFormat::Player, "player"},
    {LogFormat::Csv, "csv"},
    {LogFormat::Bag, "bag"},
}};

// Distinct skip reasons (and ignored message types) kept; fields like "SONAR r[N]" could otherwise
// make one per index.
constexpr std::size_t kMaxReasons = 64;

}  // namespace

std::string_view logFormatName(LogFormat f) {
  for (const auto& [format, name] : kNames) {
    if (format == f) return name;
  }
  return "auto";
}

bool parseLogFormat(std::string_view name, LogFormat& out) {
  for (const auto& [format, n] : kNames) {
    if (n == name) {
      out = format;
      return true;
    }
  }
  return false;
}

void LoadReport::skip(const LogError& e) {
  ++skippedLines;
  auto it = std::find_if(skipped.begin(), skipped.end(),
                         [&e](const SkipReason& r) { return r.field == e.field(); });
  if (it == skipped.end() && skipped.size() + 1 >= kMaxReasons) {
    // One last reason collects the rest, so that a hostile log keeps the report small.
    if (skipped.size() + 1 == kMaxReasons) skipped.push_back(SkipReason{"*", "other errors", 0});
    it = skipped.end() - 1;
  }
  if (it == skipped.end()) {
    skipped.push_back(SkipReason{e.field(), e.what(), 1});
  } else {
    ++it->count;
  }
}

void LoadReport::ignore(std::string_view messageType) {
  auto it = std::find_if(ignoredMessages.begin(), ignoredMessages.end(),
                         [messageType](const auto& m) { return m.first == messageType; });
  if (it == ignoredMessages.end() && ignoredMessages.size() + 1 >= kMaxReasons) {
    if (ignoredMessages.size() + 1 == kMaxReasons) ignoredMessages.emplace_back("*", 0);
    it = ignoredMessages.end() - 1;
  }
  if (it == ignoredMessages.end()) {
    ignoredMessages.emplace_back(std::string(messageType), 1);
  } else {
    ++it->second;
  }
}

std::string LoadReport::summary() const {
  std::string out;
  for (const SkipReason& r : skipped) {
    out += std::to_string(r.count) + (r.count == 1 ? " line: " : " lines: ") + r.firstError;
    if (r.count > 1) out += " (the first of them)";
    out += '\n';
  }
  return out;
}

}  // namespace sg
