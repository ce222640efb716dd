// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/io/csv_layout.h"

#include <charconv>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "sonargrid/io/text_lines.h"

namespace sg {
namespace {

// More sonar columns than a Reading::sonar index can name is a typo ("sonars=5-50000").
constexpr std::size_t kMaxSonarColumns = 4096;
constexpr std::size_t kMaxColumn = 65536;

[[noreturn]] void bad(std::string_view item, const std::string& expected) {
  throw std::invalid_argument("--columns item '" + text::shown(item) + "': expected " + expected);
}

std::size_t column(std::string_view item, std::string_view value) {
  unsigned long c = 0;
  if (!text::parseUnsigned(value, c) || c == 0 || c > kMaxColumn) {
    bad(item, "a column number 1.." + std::to_string(kMaxColumn));
  }
  return static_cast<std::size_t>(c);
}

void addSonars(CsvLayout& layout, std::string_view item, std::string_view value) {
  const std::size_t dash = value.find('-');
  const std::size_t first = column(item, value.substr(0, dash));
  const std::size_t last =
      dash == std::string_view::npos ? first : column(item, value.substr(dash + 1));
  if (last < first) bad(item, "a column range FIRST-LAST with FIRST <= LAST");
  if (layout.sonars.size() + (last - first + 1) > kMaxSonarColumns) {
    bad(item, "at most " + std::to_string(kMaxSonarColumns) + " sonar columns");
  }
  for (std::size_t c = first; c <= last; ++c) layout.sonars.push_back(c);
}

LengthUnit lengthUnit(std::string_view item, std::string_view v) {
  const std::optional<LengthUnit> unit = lengthUnitFromName(std::string(v));
  if (!unit) bad(item, "m, cm or mm");
  return *unit;
}

}  // namespace

CsvLayout parseCsvLayout(std::string_view spec) {
  CsvLayout layout;
  bool rangeGiven = false;
  std::vector<std::string_view> items;
  text::splitDelimited(spec, ',', items);
  if (items.empty()) bad(spec, "key=value items separated by commas");
  for (const std::string_view item : items) {
    const std::size_t eq = item.find('=');
    if (eq == std::string_view::npos || eq == 0) bad(item, "KEY=VALUE");
    const std::string_view key = item.substr(0, eq);
    const std::string_view value = item.substr(eq + 1);
    if (key == "time") {
      layout.time = column(item, value);
    } else if (key == "x") {
      layout.x = column(item, value);
    } else if (key == "y") {
      layout.y = column(item, value);
    } else if (key == "theta") {
      layout.theta = column(item, value);
    } else if (key == "sonars") {
      addSonars(layout, item, value);
    } else if (key == "length") {
      layout.length = lengthUnit(item, value);
      if (!rangeGiven) layout.range = layout.length;
    } else if (key == "range") {
      layout.range = lengthUnit(item, value);
      rangeGiven = true;
    } else if (key == "angle") {
      if (value == "rad") {
        layout.angle = AngleUnit::Radian;
      } else if (value == "deg") {
        layout.angle = AngleUnit::Degree;
      } else if (value == "ddeg") {
        layout.angle = AngleUnit::TenthDegree;
      } else {
        bad(item, "rad, deg or ddeg (tenths of a degree)");
      }
    } else if (key == "time_unit") {
      if (value == "s") {
        layout.secondsPerTimeUnit = 1.0;
      } else if (value == "ms") {
        layout.secondsPerTimeUnit = 1e-3;
      } else if (value == "us") {
        layout.secondsPerTimeUnit = 1e-6;
      } else {
        bad(item, "s, ms or us");
      }
    } else if (key == "noecho") {
      double v = 0.0;
      if (!text::parseFinite(value, v)) bad(item, "a number (a raw range value)");
      layout.noEcho.push_back(v);
    } else if (key == "header") {
      unsigned long n = 0;
      if (!text::parseUnsigned(value, n) || n > 1000) bad(item, "a number of lines 0..1000");
      layout.headerLines = static_cast<std::size_t>(n);
    } else if (key == "delimiter") {
      if (value == "comma") {
        layout.delimiter = ',';
      } else if (value == "semicolon") {
        layout.delimiter = ';';
      } else if (value == "blank") {
        layout.delimiter = ' ';
      } else {
        bad(item, "comma, semicolon or blank");
      }
    } else if (key == "pose_time") {
      layout.poseTime = column(item, value);
    } else if (key == "pose_x") {
      layout.poseX = column(item, value);
    } else if (key == "pose_y") {
      layout.poseY = column(item, value);
    } else if (key == "pose_theta") {
      layout.poseTheta = column(item, value);
    } else {
      bad(item,
          "a key time, x, y, theta, sonars, length, range, angle, time_unit, noecho, header, "
          "delimiter, pose_time, pose_x, pose_y or pose_theta");
    }
  }
  if (layout.time == 0) bad(spec, "a time column (time=N)");
  if (layout.sonars.empty()) bad(spec, "sonar columns (sonars=FIRST-LAST)");
  return layout;
}

std::string formatCsvLayout(const CsvLayout& layout) {
  std::string out;
  auto item = [&](std::string_view key, const std::string& value) {
    if (!out.empty()) out += ',';
    out.append(key).append("=").append(value);
  };
  auto columnItem = [&](std::string_view key, std::size_t c) {
    if (c != 0) item(key, std::to_string(c));
  };
  columnItem("time", layout.time);
  columnItem("x", layout.x);
  columnItem("y", layout.y);
  columnItem("theta", layout.theta);
  for (std::size_t i = 0; i < layout.sonars.size();) {
    std::size_t j = i;
    while (j + 1 < layout.sonars.size() && layout.sonars[j + 1] == layout.sonars[j] + 1) ++j;
    item("sonars", j == i
                       ? std::to_string(layout.sonars[i])
                       : std::to_string(layout.sonars[i]) + "-" + std::to_string(layout.sonars[j]));
    i = j + 1;
  }
  item("length", lengthUnitName(layout.length));
  item("range", lengthUnitName(layout.range));
  item("angle", layout.angle == AngleUnit::Degree        ? "deg"
                : layout.angle == AngleUnit::TenthDegree ? "ddeg"
                                                         : "rad");
  item("time_unit", layout.secondsPerTimeUnit == 1e-3   ? "ms"
                    : layout.secondsPerTimeUnit == 1e-6 ? "us"
                                                        : "s");
  for (const double v : layout.noEcho) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);  // shortest: reads back exactly
    item("noecho", std::string(buf, r.ptr));
  }
  item("header", std::to_string(layout.headerLines));
  if (layout.delimiter != 0)
    item("delimiter", layout.delimiter == ','   ? "comma"
                      : layout.delimiter == ';' ? "semicolon"
                                                : "blank");
  item("pose_time", std::to_string(layout.poseTime));
  item("pose_x", std::to_string(layout.poseX));
  item("pose_y", std::to_string(layout.poseY));
  item("pose_theta", std::to_string(layout.poseTheta));
  return out;
}

double radians(double value, AngleUnit unit) {
  switch (unit) {
    case AngleUnit::Degree:
      return value * std::numbers::pi / 180.0;
    case AngleUnit::TenthDegree:
      return value * std::numbers::pi / 1800.0;
    case AngleUnit::Radian:
      break;
  }
  return value;
}

}  // namespace sg
