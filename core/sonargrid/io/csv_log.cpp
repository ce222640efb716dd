// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/io/csv_log.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "sonargrid/io/text_lines.h"

namespace sg {
namespace {

using text::found;

// docs/formats.md ("CSV and text columns", "Sonar geometry files") is the specification of
// everything below; keep the two in step.

constexpr std::size_t kMaxSonars = 65536;  // Reading::sonar is 16 bits wide

std::string column(std::size_t c) {
  return "column " + std::to_string(c);
}

// A table of rows: header lines skipped, the delimiter chosen from the first data row.
class Table : protected text::LineParser {
 public:
  Table(text::ByteSource& source, const std::string& file, const LogOptions& options,
        LoadReport& report, const CsvLayout& layout)
      : LineParser(source, file, options, report), layout_(layout) {}

 protected:
  template <class Row>
  void eachRow(std::size_t columnsNeeded, Row&& row) {
    char delimiter = layout_.delimiter;
    while (delimiter == 0) {
      // The first line after the header that holds data decides; blank and comment lines do not.
      if (!lines_.next(line_)) return;
      if (lineNumber() <= layout_.headerLines) continue;
      try {
        text::requireText(line_, file_, lineNumber());
        text::splitFields(line_, fields_);
        if (fields_.empty()) continue;
        delimiter = line_.find(',') != std::string_view::npos   ? ','
                    : line_.find(';') != std::string_view::npos ? ';'
                                                                : ' ';
        if (delimiter != ' ') text::splitDelimited(line_, delimiter, fields_);
        checkColumns(columnsNeeded);
        row();
      } catch (const LogError& e) {
        if (!lenient_) throw;
        report_.skip(e);
      }
    }
    eachLine(
        [&] {
          if (lineNumber() <= layout_.headerLines || fields_.empty()) return;
          checkColumns(columnsNeeded);
          row();
        },
        delimiter);
  }

  double time(std::size_t col) const {
    return finite(col - 1, "time (" + column(col) + ")", "a time") * layout_.secondsPerTimeUnit;
  }

  Pose2D pose(std::size_t xCol, std::size_t yCol, std::size_t thetaCol) const {
    const double x = finite(xCol - 1, "x (" + column(xCol) + ")", "a number");
    const double y = finite(yCol - 1, "y (" + column(yCol) + ")", "a number");
    const double t = finite(thetaCol - 1, "theta (" + column(thetaCol) + ")", "an angle");
    return Pose2D(x * metresPerUnit(layout_.length), y * metresPerUnit(layout_.length),
                  radians(t, layout_.angle));
  }

  const CsvLayout& layout_;

 private:
  void checkColumns(std::size_t needed) const {
    if (fields_.size() >= needed) return;
    fail("columns", "expected at least " + std::to_string(needed) + " columns, found " +
                        std::to_string(fields_.size()));
  }
};

struct TimedPose {
  double time;
  Pose2D pose;
};

class PosesParser : Table {
 public:
  using Table::Table;

  std::vector<TimedPose> run() {
    const CsvLayout& l = layout_;
    const std::size_t need = std::max({l.poseTime, l.poseX, l.poseY, l.poseTheta});
    double last = -std::numeric_limits<double>::infinity();
    eachRow(need, [&] {
      const double t = time(l.poseTime);
      const Pose2D p = pose(l.poseX, l.poseY, l.poseTheta);
      if (t < last) {
        fail("time (" + column(l.poseTime) + ")", "expected a time >= " + text::number(last) +
                                                      " (poses are in time order), " +
                                                      found(fields_[l.poseTime - 1]));
      }
      last = t;
      poses_.push_back(TimedPose{t, p});
    });
    if (poses_.empty()) throw LogError(file_, 0, "", "expected at least one pose row, found none");
    return std::move(poses_);
  }

 private:
  std::vector<TimedPose> poses_;
};

class CsvParser : Table {
 public:
  CsvParser(text::ByteSource& source, const std::string& file, const LogOptions& options,
            LoadReport& report, const CsvLayout& layout, const SonarRing& ring,
            std::vector<TimedPose> poses)
      : Table(source, file, options, report, layout), poses_(std::move(poses)) {
    ds_.ring = ring;
    ds_.name = "CSV log";
  }

  Dataset run() {
    const CsvLayout& l = layout_;
    std::size_t need = std::max(l.time, *std::max_element(l.sonars.begin(), l.sonars.end()));
    if (poses_.empty()) need = std::max({need, l.x, l.y, l.theta});
    eachRow(need, [this] { row(); });
    return std::move(ds_);
  }

 private:
  void row() {
    const CsvLayout& l = layout_;
    const double t = time(l.time);
    if (t < lastTime_) {
      fail("time (" + column(l.time) + ")", "expected a time >= " + text::number(lastTime_) +
                                                " (rows are in time order), " +
                                                found(fields_[l.time - 1]));
    }
    const Pose2D odometry = poses_.empty() ? pose(l.x, l.y, l.theta) : joinedPose(t);
    readings_.clear();
    for (std::size_t i = 0; i < l.sonars.size(); ++i) {
      const std::size_t c = l.sonars[i];
      const std::string_view raw = fields_[c - 1];
      const std::string field = "sonar " + std::to_string(i) + " (" + column(c) + ")";
      double v = 0.0;
      if (!text::parseFinite(raw, v)) {
        fail(field, "expected a range >= 0 or a no-echo value, " + text::foundNumber(raw));
      }
      double range = Reading::kNoEcho;
      if (std::find(l.noEcho.begin(), l.noEcho.end(), v) == l.noEcho.end()) {
        if (v < 0.0) fail(field, "expected a range >= 0 or a no-echo value, " + found(raw));
        range = v * metresPerUnit(l.range);
        if (range >= ds_.ring.maxRange) range = Reading::kNoEcho;
      }
      readings_.push_back(Reading{static_cast<std::uint16_t>(i), range, t});
    }
    lastTime_ = t;
    Scan& scan = ds_.scans.emplace_back();
    scan.time = t;
    scan.odometry = odometry;
    scan.readings = readings_;
  }

  // The pose at time t, linear between the two poses around it (the heading along the shorter
  // arc). Rows are in time order, so the search only moves forward.
  Pose2D joinedPose(double t) {
    const double first = poses_.front().time;
    const double last = poses_.back().time;
    if (t < first || t > last) {
      fail("time (" + column(layout_.time) + ")",
           "expected a time within the poses file's span " + text::number(first) + ".." +
               text::number(last) + ", " + found(fields_[layout_.time - 1]));
    }
    while (next_ + 1 < poses_.size() && poses_[next_ + 1].time <= t) ++next_;
    const TimedPose& a = poses_[next_];
    if (next_ + 1 == poses_.size() || a.time == t) return a.pose;
    const TimedPose& b = poses_[next_ + 1];
    const double f = (t - a.time) / (b.time - a.time);
    const Position p = a.pose.position + f * (b.pose.position - a.pose.position);
    const double heading =
        wrapAngle(a.pose.heading + f * wrapAngle(b.pose.heading - a.pose.heading));
    return Pose2D(p.x(), p.y(), heading);
  }

  Dataset ds_;
  std::vector<TimedPose> poses_;
  std::size_t next_ = 0;
  std::vector<Reading> readings_;
  double lastTime_ = -std::numeric_limits<double>::infinity();
};

class GeometryParser : text::LineParser {
 public:
  GeometryParser(text::ByteSource& source, const std::string& file, LoadReport& report)
      : LineParser(source, file, LogOptions{}, report) {}

  SonarRing run() {
    ring_.robot = "custom";
    eachLine([this] { record(); });
    if (ring_.sonars.empty()) {
      throw LogError(file_, 0, "sonar",
                     "expected at least one 'sonar X Y HEADING' line, found none");
    }
    if (ring_.maxRange <= ring_.minRange) {
      throw LogError(file_, 0, "max_range",
                     "expected max_range " + text::number(ring_.maxRange) + " > min_range " +
                         text::number(ring_.minRange));
    }
    return std::move(ring_);
  }

 private:
  void expectCount(std::size_t n, std::string_view layout) const {
    if (fields_.size() - 1 == n) return;
    fail(std::string(fields_[0]), "expected " + std::to_string(n) + " fields after '" +
                                      std::string(fields_[0]) + "' (" + std::string(layout) +
                                      "), found " + std::to_string(fields_.size() - 1));
  }

  double length(std::size_t i, const std::string& field) const {
    return finite(i, field, "a length") * metresPerUnit(length_);
  }

  void record() {
    if (fields_.empty()) return;
    const std::string_view key = fields_[0];
    if (key == "units") {
      expectCount(2, "m, cm or mm, then rad, deg or ddeg");
      if (records_ != 0) fail("units", "expected 'units' before any other record, found it later");
      const std::optional<LengthUnit> unit = lengthUnitFromName(std::string(fields_[1]));
      if (!unit) fail("units", "expected a length unit m, cm or mm, " + found(fields_[1]));
      length_ = *unit;
      if (fields_[2] == "rad") {
        angle_ = AngleUnit::Radian;
      } else if (fields_[2] == "deg") {
        angle_ = AngleUnit::Degree;
      } else if (fields_[2] == "ddeg") {
        angle_ = AngleUnit::TenthDegree;
      } else {
        fail("units", "expected an angle unit rad, deg or ddeg, " + found(fields_[2]));
      }
    } else if (key == "aperture") {
      expectCount(1, "the full cone angle");
      const double a = radians(finite(1, "aperture", "an angle"), angle_);
      if (!(a > 0.0 && a <= std::numbers::pi)) {
        fail("aperture", "expected an angle > 0 and <= 180 degrees, " + found(fields_[1]));
      }
      ring_.apertureRad = a;
    } else if (key == "min_range" || key == "max_range") {
      expectCount(1, "a length");
      const double v = length(1, std::string(key));
      if (v < 0.0 || (key == "max_range" && v == 0.0)) {
        fail(std::string(key), "expected a length > 0, " + found(fields_[1]));
      }
      (key == "min_range" ? ring_.minRange : ring_.maxRange) = v;
    } else if (key == "sonar") {
      expectCount(3, "x y heading in the robot frame");
      if (ring_.sonars.size() >= kMaxSonars) {
        fail("sonar", "expected at most " + std::to_string(kMaxSonars) + " sonars, found more");
      }
      const double x = length(1, "sonar x");
      const double y = length(2, "sonar y");
      const double h = radians(finite(3, "sonar heading", "an angle"), angle_);
      ring_.sonars.push_back(SonarMount{Pose2D(x, y, h)});
    } else {
      fail("", "expected a record units, aperture, min_range, max_range or sonar, " + found(key));
    }
    ++records_;
  }

  SonarRing ring_;
  LengthUnit length_ = LengthUnit::Metre;
  AngleUnit angle_ = AngleUnit::Radian;
  std::size_t records_ = 0;
};

}  // namespace

Dataset readCsvLog(text::ByteSource& source, const std::string& displayName,
                   const LogOptions& options, LoadReport& report) {
  report.format = LogFormat::Csv;
  if (!options.csv) {
    throw LogError(displayName, 0, "columns",
                   "expected a column layout (--columns) for a CSV log, found none");
  }
  const CsvLayout& layout = *options.csv;
  if (!options.ring) {
    throw LogError(displayName, 0, "geometry",
                   "expected a robot preset or a geometry file (--robot), found neither");
  }
  if (options.ring->sonars.size() != layout.sonars.size()) {
    throw LogError(displayName, 0, "sonars",
                   "expected one sonar column per sonar of the ring (" +
                       std::to_string(options.ring->sonars.size()) + "), found " +
                       std::to_string(layout.sonars.size()) + " columns");
  }
  std::vector<TimedPose> poses;
  if (!options.posesPath.empty()) {
    text::FileSource posesSource(options.posesPath);
    poses = PosesParser(posesSource, options.posesPath, options, report, layout).run();
  } else if (layout.x == 0 || layout.y == 0 || layout.theta == 0) {
    throw LogError(displayName, 0, "columns",
                   "expected x, y and theta columns (x=N,y=N,theta=N) or a poses file (--poses), "
                   "found neither");
  }
  return CsvParser(source, displayName, options, report, layout, *options.ring, std::move(poses))
      .run();
}

SonarRing readSonarGeometry(text::ByteSource& source, const std::string& displayName) {
  LoadReport report;
  return GeometryParser(source, displayName, report).run();
}

SonarRing readSonarGeometry(const std::string& path) {
  text::FileSource source(path);
  return readSonarGeometry(source, path);
}

}  // namespace sg
