// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/sweep/sweep_grid.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <sstream>

namespace sg {
namespace {

std::string trimmed(const std::string& s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string::npos) return {};
  const auto last = s.find_last_not_of(" \t");
  return s.substr(first, last - first + 1);
}

bool readNumber(const std::string& text, double& v) {
  const std::string t = trimmed(text);
  if (t.empty()) return false;
  const char* end = t.data() + t.size();
  const auto [ptr, ec] = std::from_chars(t.data(), end, v);
  return ec == std::errc() && ptr == end && std::isfinite(v);
}

// Digits after the point of a plain decimal ("-0.05" → 2), or -1 for any other form (1e-3).
int decimalsOf(const std::string& text) {
  const std::string t = trimmed(text);
  std::size_t i = (!t.empty() && (t[0] == '-' || t[0] == '+')) ? 1 : 0;
  int decimals = 0;
  bool point = false;
  bool digit = false;
  for (; i < t.size(); ++i) {
    if (t[i] >= '0' && t[i] <= '9') {
      digit = true;
      if (point) ++decimals;
    } else if (t[i] == '.' && !point) {
      point = true;
    } else {
      return -1;
    }
  }
  return digit ? decimals : -1;
}

std::string rangeText(const ParameterSpec& s) {
  std::ostringstream o;
  o << "[" << s.min << ", " << s.max << "]" << (s.unit.empty() ? "" : " " + s.unit);
  return o.str();
}

const ParameterSpec& specOf(const ParameterSet& base, const std::string& name,
                            const std::string& text) {
  for (const ParameterSpec& s : base.specs()) {
    if (s.name == name) return s;
  }
  std::string names;
  for (const ParameterSpec& s : base.specs()) names += (names.empty() ? "" : ", ") + s.name;
  throw SweepSpecError("'" + text + "': unknown parameter '" + name +
                       "'; this model and rule have " + names);
}

void checkInRange(const ParameterSpec& s, double v, const std::string& text) {
  if (!(v >= s.min && v <= s.max)) {
    throw SweepSpecError("'" + text + "': " + s.name + " = " + shortestText(v) +
                         " is outside its declared range " + rangeText(s));
  }
  if (s.integer && v != std::floor(v))
    throw SweepSpecError("'" + text + "': " + s.name + " takes whole numbers, got " +
                         shortestText(v));
}

// "name=rest" split at the first '='.
std::pair<std::string, std::string> nameAndValue(const std::string& text, const char* form) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || trimmed(text.substr(0, eq)).empty())
    throw SweepSpecError("'" + text + "': expected " + form);
  return {trimmed(text.substr(0, eq)), text.substr(eq + 1)};
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const auto at = s.find(sep, start);
    out.push_back(s.substr(start, at == std::string::npos ? std::string::npos : at - start));
    if (at == std::string::npos) return out;
    start = at + 1;
  }
}

}  // namespace

std::string shortestText(double v) {
  char buffer[64];
  const auto [ptr, ec] = std::to_chars(buffer, buffer + sizeof buffer, v);
  return ec == std::errc() ? std::string(buffer, ptr) : std::string("nan");
}

SweepAxis parseSweepAxis(const std::string& text, const ParameterSet& base) {
  const char* form = "NAME=FROM:STEP:TO or NAME=V1,V2,...";
  const auto [name, rest] = nameAndValue(text, form);
  const ParameterSpec& spec = specOf(base, name, text);
  SweepAxis axis;
  axis.parameter = name;
  const std::vector<std::string> colon = split(rest, ':');
  if (colon.size() == 3) {
    double a = 0, step = 0, b = 0;
    if (!readNumber(colon[0], a) || !readNumber(colon[1], step) || !readNumber(colon[2], b))
      throw SweepSpecError("'" + text + "': FROM, STEP and TO must be numbers (" + form + ")");
    if (!(step > 0.0)) throw SweepSpecError("'" + text + "': STEP must be greater than 0");
    if (b < a) throw SweepSpecError("'" + text + "': TO must not be below FROM");
    const double count = std::floor((b - a) / step + 1e-9) + 1.0;
    if (count > static_cast<double>(kMaxAxisValues))
      throw SweepSpecError("'" + text + "': more than " + std::to_string(kMaxAxisValues) +
                           " values");
    const int d = std::max({decimalsOf(colon[0]), decimalsOf(colon[1]), decimalsOf(colon[2])});
    const bool decimal = decimalsOf(colon[0]) >= 0 && decimalsOf(colon[1]) >= 0 &&
                         decimalsOf(colon[2]) >= 0 && d <= 15;
    const double scale = decimal ? std::pow(10.0, d) : 1.0;
    const double ia = std::round(a * scale), is = std::round(step * scale);
    const bool exactIntegers = decimal && std::abs(ia) + count * is < 9.0e15;
    for (std::int64_t k = 0; k < static_cast<std::int64_t>(count); ++k) {
      const auto kd = static_cast<double>(k);
      // Two integers below 2^53 divided by a power of ten: the double nearest the decimal.
      axis.values.push_back(exactIntegers ? (ia + kd * is) / scale : a + kd * step);
    }
  } else if (colon.size() == 1) {
    for (const std::string& item : split(rest, ',')) {
      double v = 0;
      if (!readNumber(item, v))
        throw SweepSpecError("'" + text + "': '" + trimmed(item) + "' is not a number (" + form +
                             ")");
      axis.values.push_back(v);
    }
    if (axis.values.size() > kMaxAxisValues)
      throw SweepSpecError("'" + text + "': more than " + std::to_string(kMaxAxisValues) +
                           " values");
  } else {
    throw SweepSpecError("'" + text + "': expected " + form);
  }
  for (std::size_t i = 0; i < axis.values.size(); ++i) {
    checkInRange(spec, axis.values[i], text);
    for (std::size_t j = 0; j < i; ++j) {
      if (axis.values[j] == axis.values[i])
        throw SweepSpecError("'" + text + "': the value " + shortestText(axis.values[i]) +
                             " is given twice");
    }
  }
  return axis;
}

SweepRange parseSweepRange(const std::string& text, const ParameterSet& base) {
  const auto [name, rest] = nameAndValue(text, "NAME=LO:HI");
  const ParameterSpec& spec = specOf(base, name, text);
  const std::vector<std::string> colon = split(rest, ':');
  SweepRange r;
  r.parameter = name;
  if (colon.size() != 2 || !readNumber(colon[0], r.lo) || !readNumber(colon[1], r.hi))
    throw SweepSpecError("'" + text + "': expected NAME=LO:HI with two numbers");
  if (!(r.lo < r.hi)) throw SweepSpecError("'" + text + "': LO must be below HI");
  checkInRange(spec, r.lo, text);
  checkInRange(spec, r.hi, text);
  return r;
}

SweepTie parseSweepTie(const std::string& text, const ParameterSet& base) {
  const char* form = "NAME=EXPR with EXPR one of C, P, C-P, C+P, C*P (C a number, P a parameter)";
  const auto [name, expression] = nameAndValue(text, form);
  specOf(base, name, text);
  SweepTie tie;
  tie.parameter = name;
  const std::string e = trimmed(expression);
  if (e.empty()) throw SweepSpecError("'" + text + "': expected " + form);
  auto refuse = [&] { throw SweepSpecError("'" + text + "': cannot read '" + e + "'; " + form); };
  double c = 0;
  if (readNumber(e, c)) {
    tie.constant = c;
  } else if (base.has(e)) {
    tie.source = e;
  } else {
    // NUMBER op NAME: the operator is the first of -, +, * after the number's first character
    // (so a leading sign stays with the number).
    const auto at = e.find_first_of("-+*", 1);
    if (at == std::string::npos) {
      // A lone word: an unknown parameter, named so.
      if (e.find_first_of("()/^ ") == std::string::npos && !std::isdigit(e[0]))
        specOf(base, e, text);
      refuse();
    }
    const std::string left = e.substr(0, at);
    const std::string right = trimmed(e.substr(at + 1));
    if (!readNumber(left, c)) refuse();
    if (right.empty() || right.find_first_of("-+*/() ") != std::string::npos) refuse();
    specOf(base, right, text);
    tie.constant = c;
    tie.source = right;
    tie.op = e[at];
  }
  if (tie.source == tie.parameter)
    throw SweepSpecError("'" + text + "': a parameter cannot be tied to itself");
  return tie;
}

double SweepTie::valueFor(const ParameterSet& set) const {
  if (source.empty()) return constant;
  const double x = set.get(source);
  switch (op) {
    case '-':
      return constant - x;
    case '+':
      return constant + x;
    case '*':
      return constant * x;
    default:
      return x;
  }
}

std::string SweepTie::text() const {
  if (source.empty()) return parameter + "=" + shortestText(constant);
  if (op == 0) return parameter + "=" + source;
  return parameter + "=" + shortestText(constant) + op + source;
}

void applyTies(ParameterSet& set, const std::vector<SweepTie>& ties) {
  for (const SweepTie& t : ties) {
    const double v = t.valueFor(set);
    try {
      set.set(t.parameter, v);
    } catch (const ParameterError& e) {
      throw SweepSpecError("--tie '" + t.text() + "' gives " + e.what());
    }
  }
}

std::vector<ParameterSet> sweepSets(const ParameterSet& base, const std::vector<SweepAxis>& axes,
                                    const std::vector<SweepTie>& ties) {
  std::vector<std::string> swept;
  double total = 1.0;
  for (const SweepAxis& a : axes) {
    if (std::find(swept.begin(), swept.end(), a.parameter) != swept.end())
      throw SweepSpecError("parameter '" + a.parameter + "' is swept twice");
    swept.push_back(a.parameter);
    total *= static_cast<double>(a.values.size());
  }
  if (total > static_cast<double>(kMaxSweepSets))
    throw SweepSpecError("the grid has " + shortestText(total) + " sets, more than " +
                         std::to_string(kMaxSweepSets));
  std::vector<std::string> tied;
  for (const SweepTie& t : ties) {
    if (std::find(swept.begin(), swept.end(), t.parameter) != swept.end())
      throw SweepSpecError("--tie '" + t.text() + "': " + t.parameter + " is already swept");
    if (std::find(tied.begin(), tied.end(), t.parameter) != tied.end())
      throw SweepSpecError("--tie '" + t.text() + "': " + t.parameter + " is tied twice");
    tied.push_back(t.parameter);
  }
  for (std::size_t i = 0; i < ties.size(); ++i) {
    for (std::size_t j = i + 1; j < ties.size(); ++j) {
      if (ties[i].source == ties[j].parameter)
        throw SweepSpecError("--tie '" + ties[i].text() + "' reads " + ties[j].parameter +
                             ", which a later --tie sets; give that --tie first");
    }
  }
  const auto n = static_cast<std::size_t>(total);
  std::vector<ParameterSet> sets;
  sets.reserve(n);
  std::vector<std::size_t> digit(axes.size(), 0);
  for (std::size_t i = 0; i < n; ++i) {
    ParameterSet s = base;
    for (std::size_t a = 0; a < axes.size(); ++a)
      s.set(axes[a].parameter, axes[a].values[digit[a]]);
    try {
      applyTies(s, ties);
    } catch (const SweepSpecError& e) {
      throw SweepSpecError(std::string(e.what()) + " (set " + std::to_string(i) + ")");
    }
    sets.push_back(std::move(s));
    for (std::size_t a = axes.size(); a-- > 0;) {
      if (++digit[a] < axes[a].values.size()) break;
      digit[a] = 0;
    }
  }
  return sets;
}

std::vector<std::string> splitCommas(const std::string& text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const auto at = text.find(',', start);
    out.push_back(text.substr(start, at == std::string::npos ? std::string::npos : at - start));
    if (at == std::string::npos) return out;
    start = at + 1;
  }
}

SweepSpace sweepSpace(const ParameterSet& base, const std::vector<std::string>& axisTexts,
                      const std::vector<SweepTie>& ties) {
  SweepSpace space;
  for (std::size_t i = 0; i < axisTexts.size(); ++i) {
    try {
      space.axes.push_back(parseSweepAxis(axisTexts[i], base));
    } catch (const SweepSpecError& e) {
      throw SweepSpaceError(e.what(), i);
    }
  }
  try {
    space.sets = sweepSets(base, space.axes, ties);
  } catch (const SweepSpecError& e) {
    throw SweepSpaceError(e.what(), std::nullopt);
  }
  for (const SweepAxis& a : space.axes) {
    std::string values;
    for (double v : a.values) values += (values.empty() ? "" : ",") + shortestText(v);
    space.fields.emplace_back("grid", a.parameter + "=" + values);
  }
  for (const SweepTie& t : ties) space.fields.emplace_back("tie", t.text());
  return space;
}

GridSpec gridOverRuns(const GridSpec& a, const GridSpec& b) {
  const Position lo = a.origin.cwiseMin(b.origin);
  const Position hi = (a.origin + Position(a.widthMetres(), a.heightMetres()))
                          .cwiseMax(b.origin + Position(b.widthMetres(), b.heightMetres()));
  return GridSpec::covering(lo, hi, a.cellSize, 0.0);
}

}  // namespace sg
