// SPDX-License-Identifier: GPL-3.0-or-later
#include "arguments.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

namespace sg::cli {

double parseNumber(const std::string& text, const std::string& what) {
  double v = 0.0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, v);
  if (ec != std::errc() || ptr != end || !std::isfinite(v)) {
    throw UsageError(what + " expects a number, got '" + text + "'");
  }
  return v;
}

std::uint64_t parseSeed(const std::string& text) {
  std::uint64_t v = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, v);
  if (text.empty() || ec != std::errc() || ptr != end) {
    throw UsageError("--seed expects a whole number from 0 to 18446744073709551615, got '" + text +
                     "'");
  }
  return v;
}

bool Arguments::flag(const std::string& name) {
  const auto n = std::count(args_.begin(), args_.end(), name);
  if (n > 1) throw UsageError(name + " is given " + std::to_string(n) + " times");
  const auto it = std::find(args_.begin(), args_.end(), name);
  if (it == args_.end()) return false;
  args_.erase(it);
  return true;
}

std::optional<std::string> Arguments::value(const std::string& name) {
  std::vector<std::string> all = values(name);
  if (all.size() > 1) throw UsageError(name + " is given " + std::to_string(all.size()) + " times");
  if (all.empty()) return std::nullopt;
  return all.front();
}

std::vector<std::string> Arguments::values(const std::string& name) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < args_.size();) {
    if (args_[i] == name) {
      if (i + 1 >= args_.size() || args_[i + 1].rfind("--", 0) == 0)
        throw UsageError(name + " needs a value");
      out.push_back(args_[i + 1]);
      args_.erase(args_.begin() + static_cast<std::ptrdiff_t>(i),
                  args_.begin() + static_cast<std::ptrdiff_t>(i) + 2);
    } else if (args_[i].rfind(name + "=", 0) == 0) {
      out.push_back(args_[i].substr(name.size() + 1));
      args_.erase(args_.begin() + static_cast<std::ptrdiff_t>(i));
    } else {
      ++i;
    }
  }
  return out;
}

std::string Arguments::required(const std::string& name) {
  auto v = value(name);
  if (!v) throw UsageError("missing " + name);
  return *v;
}

double Arguments::number(const std::string& name, double fallback, double min, double max) {
  auto v = value(name);
  if (!v) return fallback;
  const double x = parseNumber(*v, name);
  if (x < min || x > max) {
    std::ostringstream msg;
    msg << name << " must be between " << min << " and " << max << ", got " << *v;
    throw UsageError(msg.str());
  }
  return x;
}

int Arguments::integer(const std::string& name, int fallback, int min, int max) {
  auto v = value(name);
  if (!v) return fallback;
  int x = 0;
  const char* end = v->data() + v->size();
  const auto [ptr, ec] = std::from_chars(v->data(), end, x);
  if (ec != std::errc() || ptr != end)
    throw UsageError(name + " expects a whole number, got '" + *v + "'");
  if (x < min || x > max) {
    throw UsageError(name + " must be between " + std::to_string(min) + " and " +
                     std::to_string(max) + ", got " + *v);
  }
  return x;
}

std::vector<std::string> Arguments::positionals() {
  std::vector<std::string> out;
  std::vector<std::string> rest;
  for (const std::string& a : args_) (a.rfind("--", 0) == 0 ? rest : out).push_back(a);
  args_ = std::move(rest);
  return out;
}

void Arguments::finish() const {
  if (!args_.empty()) throw UsageError("unexpected argument '" + args_.front() + "'");
}

}  // namespace sg::cli
