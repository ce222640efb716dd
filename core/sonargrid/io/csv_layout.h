// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The column mapping of a generic CSV or whitespace-separated sonar log (docs/formats.md, "CSV and
// text columns"): which column holds the time, the pose and each sonar, in which units, and which
// raw values mean "no echo". Written as a spec string, e.g.
//   time=1,x=2,y=3,theta=4,sonars=5-20,length=mm,angle=ddeg,noecho=5110

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "sonargrid/base/length_unit.h"

namespace sg {

enum class AngleUnit { Radian, Degree, TenthDegree };

struct CsvLayout {
  // 1-based column numbers; 0 = not given.
  std::size_t time = 0;
  std::size_t x = 0;
  std::size_t y = 0;
  std::size_t theta = 0;
  std::vector<std::size_t> sonars;  // sonars[i] is the column of sonar i

  LengthUnit length = LengthUnit::Metre;  // x and y
  LengthUnit range = LengthUnit::Metre;   // sonar ranges
  AngleUnit angle = AngleUnit::Radian;    // theta
  double secondsPerTimeUnit = 1.0;        // time=s 1, ms 0.001, us 1e-6
  // Raw values (in the file's range unit, compared exactly) that mean "no echo".
  std::vector<double> noEcho;
  std::size_t headerLines = 0;  // lines skipped before the data, comments aside
  // 0 = decide from the first data line: ',' when it has one, else ';', else blanks.
  char delimiter = 0;

  // The poses file (LogOptions::posesPath): its time, x, y and theta columns, same units.
  std::size_t poseTime = 1;
  std::size_t poseX = 2;
  std::size_t poseY = 3;
  std::size_t poseTheta = 4;

  bool operator==(const CsvLayout&) const = default;
};

// Parses `key=value,...` (keys: time x y theta sonars length range angle time_unit noecho header
// delimiter pose_time pose_x pose_y pose_theta; `sonars` and `noecho` may repeat). Throws
// std::invalid_argument naming the bad item and what was expected.
CsvLayout parseCsvLayout(std::string_view spec);

// The spec that parseCsvLayout reads back as `layout` (every key written, columns of sonars as
// ranges where they run on: "sonars=5-20"); a project file stores a CSV log's layout this way.
std::string formatCsvLayout(const CsvLayout& layout);

double radians(double value, AngleUnit unit);

}  // namespace sg
