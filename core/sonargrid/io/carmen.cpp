// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/io/carmen.h"

#include <charconv>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <vector>

#include "sonargrid/base/atomic_file.h"
#include "sonargrid/io/text_lines.h"

namespace sg {
namespace {

using text::found;

// docs/formats.md ("CARMEN") is the specification of everything below; keep the two in step.

// Every message ends with these three fields.
constexpr std::size_t kTrailer = 3;        // ipc_timestamp ipc_hostname logger_timestamp
constexpr std::size_t kMaxSonars = 65536;  // Reading::sonar is 16 bits wide
constexpr std::string_view kHost = "sonargrid";

bool isMessageName(std::string_view s) {
  if (s.empty() || !((s[0] >= 'A' && s[0] <= 'Z') || (s[0] >= 'a' && s[0] <= 'z'))) return false;
  for (const char c : s) {
    if (!((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' ||
          c == '-')) {
      return false;
    }
  }
  return true;
}

class CarmenParser : text::LineParser {
 public:
  using LineParser::LineParser;

  Dataset run(const LogOptions& options) {
    ds_.ring = SonarRing{};
    ds_.name = "CARMEN log";
    if (options.ring) {
      // The SONAR messages carry the geometry; a preset only lends its ranges.
      ds_.ring.minRange = options.ring->minRange;
      ds_.ring.maxRange = options.ring->maxRange;
    }
    eachLine([this] { message(); });
    if (geometryLine_ == 0) {
      throw LogError(file_, 0, "SONAR", "expected at least one valid SONAR message, found none");
    }
    return std::move(ds_);
  }

 private:
  void message() {
    if (fields_.empty()) return;
    const std::string_view name = fields_[0];
    if (name == "ODOM") {
      odometry();
    } else if (name == "TRUEPOS") {
      truePose();
    } else if (name == "SONAR") {
      sonar();
    } else if (isMessageName(name)) {
      report_.ignore(name);
    } else {
      fail("", "expected a message name (ODOM, TRUEPOS, SONAR, PARAM...), " + found(name));
    }
  }

  // The fields after the name, at least `n` of them; extra fields before the trailer are allowed
  // (loggers of other CARMEN versions add some).
  void expectAtLeast(std::size_t n, std::string_view layout) const {
    const std::size_t got = fields_.size() - 1;
    if (got >= n) return;
    fail(std::string(fields_[0]), "expected " + std::to_string(n) + " fields after '" +
                                      std::string(fields_[0]) + "' (" + std::string(layout) +
                                      "), found " + std::to_string(got));
  }

  // The ipc timestamp (third field from the end); the logger timestamp must be a number too, so
  // that a line cut short is caught.
  double timestamp() const {
    const std::string name(fields_[0]);
    const std::size_t n = fields_.size();
    const double ts = finite(n - kTrailer, name + " ipc_timestamp", "a time in seconds");
    finite(n - 1, name + " logger_timestamp", "a time in seconds");
    return ts;
  }

  Pose2D pose(std::size_t first, const std::string& prefix) const {
    const std::string name(fields_[0]);
    const double x = finite(first, name + " " + prefix + "x", "a number of metres");
    const double y = finite(first + 1, name + " " + prefix + "y", "a number of metres");
    const double theta = finite(first + 2, name + " " + prefix + "theta", "an angle in radians");
    return Pose2D(x, y, theta);
  }

  void odometry() {
    expectAtLeast(6 + kTrailer,
                  "x y theta tv rv accel ipc_timestamp ipc_hostname logger_timestamp");
    const Pose2D p = pose(1, "");
    timestamp();
    odometry_ = p;
  }

  void truePose() {
    expectAtLeast(6 + kTrailer,
                  "true_x true_y true_theta odom_x odom_y odom_theta ipc_timestamp ipc_hostname "
                  "logger_timestamp");
    const Pose2D t = pose(1, "true_");
    const Pose2D o = pose(4, "odom_");
    timestamp();
    truth_ = t;
    truthOdometry_ = o;
  }

  void sonar() {
    expectAtLeast(2 + 4 + kTrailer,
                  "cone_angle num r[0..num-1] (x y theta)[0..num-1] ipc_timestamp ipc_hostname "
                  "logger_timestamp");
    const double cone = finite(1, "SONAR cone_angle", "a full cone angle in radians > 0 and <= pi");
    if (cone <= 0.0 || cone > std::numbers::pi) {
      fail("SONAR cone_angle",
           "expected a full cone angle in radians > 0 and <= pi, " + found(fields_[1]));
    }
    unsigned long num = 0;
    if (!text::parseUnsigned(fields_[2], num) || num == 0 || num > kMaxSonars) {
      fail("SONAR num",
           "expected a sonar count 1.." + std::to_string(kMaxSonars) + ", " + found(fields_[2]));
    }
    const std::size_t need = 2 + 4 * num + kTrailer;
    if (fields_.size() - 1 < need) {
      fail("SONAR", "expected " + std::to_string(need) + " fields after 'SONAR' for " +
                        std::to_string(num) +
                        " sonars (cone_angle num, the ranges, x y theta of each sonar, "
                        "ipc_timestamp ipc_hostname logger_timestamp), found " +
                        std::to_string(fields_.size() - 1));
    }
    if (geometryLine_ != 0 && num != ds_.ring.sonars.size()) {
      fail("SONAR num", "expected " + std::to_string(ds_.ring.sonars.size()) +
                            " sonars (as on line " + std::to_string(geometryLine_) + "), " +
                            found(fields_[2]));
    }
    ranges_.resize(num);
    for (std::size_t i = 0; i < num; ++i) {
      const std::string field = "SONAR r[" + std::to_string(i) + "]";
      ranges_[i] = finite(3 + i, field, "a range in metres >= 0");
      if (ranges_[i] < 0.0)
        fail(field, "expected a range in metres >= 0, " + found(fields_[3 + i]));
    }
    mounts_.resize(num);
    for (std::size_t i = 0; i < num; ++i) {
      const std::size_t at = 3 + num + 3 * i;
      const std::string index = "[" + std::to_string(i) + "]";
      const double x = finite(at, "SONAR x" + index, "a number of metres");
      const double y = finite(at + 1, "SONAR y" + index, "a number of metres");
      const double theta = finite(at + 2, "SONAR theta" + index, "an angle in radians");
      mounts_[i] = SonarMount{Pose2D(x, y, theta)};
    }
    const double time = timestamp();
    if (geometryLine_ != 0) {
      if (cone != ds_.ring.apertureRad) {
        fail("SONAR cone_angle", "expected " + text::number(ds_.ring.apertureRad) +
                                     " (as on line " + std::to_string(geometryLine_) + "), " +
                                     found(fields_[1]));
      }
      for (std::size_t i = 0; i < num; ++i) {
        if (!(mounts_[i] == ds_.ring.sonars[i])) {
          fail("SONAR x[" + std::to_string(i) + "]",
               "expected the sonar pose of line " + std::to_string(geometryLine_) +
                   " (the ring cannot change within a log), " + found(fields_[3 + num + 3 * i]));
        }
      }
    }
    if (time < lastTime_) {
      fail("SONAR ipc_timestamp", "expected a time >= " + text::number(lastTime_) +
                                      " (the previous SONAR's; scans are in time order), " +
                                      found(fields_[fields_.size() - kTrailer]));
    }
    if (!odometry_ && !truthOdometry_) {
      fail("SONAR", "expected an ODOM or TRUEPOS message before the first SONAR, found none");
    }
    // Every check passed: only now does the line change the dataset.
    if (geometryLine_ == 0) {
      ds_.ring.apertureRad = cone;
      ds_.ring.sonars = mounts_;
      geometryLine_ = lineNumber();
    }
    lastTime_ = time;
    Scan& scan = ds_.scans.emplace_back();
    scan.time = time;
    scan.odometry = odometry_ ? *odometry_ : *truthOdometry_;
    scan.truth = truth_;
    scan.readings.reserve(num);
    for (std::size_t i = 0; i < num; ++i) {
      const double r = ranges_[i] >= ds_.ring.maxRange ? Reading::kNoEcho : ranges_[i];
      scan.readings.push_back(Reading{static_cast<std::uint16_t>(i), r, time});
    }
  }

  Dataset ds_;
  std::optional<Pose2D> odometry_;
  std::optional<Pose2D> truth_;
  std::optional<Pose2D> truthOdometry_;
  std::size_t geometryLine_ = 0;
  double lastTime_ = -std::numeric_limits<double>::infinity();
  std::vector<double> ranges_;
  std::vector<SonarMount> mounts_;
};

// ---------------------------------------------------------------------------------------------
// Writing

void append(std::string& out, double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

void appendPose(std::string& out, const Pose2D& p) {
  append(out, p.x());
  out += ' ';
  append(out, p.y());
  out += ' ';
  append(out, p.heading);
}

void appendTrailer(std::string& out, double time) {
  out += ' ';
  append(out, time);
  out += ' ';
  out += kHost;
  out += ' ';
  append(out, time);
  out += '\n';
}

void checkWritable(const Dataset& d) {
  const SonarRing& ring = d.ring;
  if (ring.sonars.empty()) throw std::runtime_error("the ring has no sonars");
  if (ring.sonars.size() > kMaxSonars) throw std::runtime_error("the ring has over 65536 sonars");
  if (!(ring.apertureRad > 0.0 && ring.apertureRad <= std::numbers::pi)) {
    throw std::runtime_error("the aperture is not an angle > 0 and <= pi");
  }
  if (!std::isfinite(ring.maxRange)) throw std::runtime_error("the maximum range is not finite");
  auto finitePose = [](const Pose2D& p) {
    return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.heading);
  };
  for (const SonarMount& m : ring.sonars) {
    if (!finitePose(m.pose)) throw std::runtime_error("a sonar has a non-finite pose");
  }
  double last = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < d.scans.size(); ++i) {
    const Scan& s = d.scans[i];
    const std::string where = "scan " + std::to_string(i);
    if (!std::isfinite(s.time) || s.time < last) {
      throw std::runtime_error(where + " has a time that is not finite or not in order");
    }
    last = s.time;
    if (!finitePose(s.odometry) || (s.truth && !finitePose(*s.truth))) {
      throw std::runtime_error(where + " has a non-finite pose");
    }
    for (const Reading& r : s.readings) {
      if (r.sonar >= ring.sonars.size() || std::isnan(r.range) || r.range < 0.0) {
        throw std::runtime_error(where + " has a reading of no sonar or a negative range");
      }
    }
  }
}

void appendSonar(std::string& out, const SonarRing& ring, const std::vector<double>& ranges,
                 double time) {
  out += "SONAR ";
  append(out, ring.apertureRad);
  out += ' ';
  out += std::to_string(ranges.size());
  for (const double r : ranges) {
    out += ' ';
    append(out, r);
  }
  for (const SonarMount& m : ring.sonars) {
    out += ' ';
    appendPose(out, m.pose);
  }
  appendTrailer(out, time);
}

std::string carmenText(const Dataset& d) {
  checkWritable(d);
  std::string out;
  out +=
      "# CARMEN log written by SonarGrid (docs/formats.md); metres, radians, seconds\n"
      "# ODOM x y theta tv rv accel\n"
      "# TRUEPOS true_x true_y true_theta odom_x odom_y odom_theta\n"
      "# SONAR cone_angle num_sonars [range] [x y theta]\n";
  const SonarRing& ring = d.ring;
  std::vector<double> ranges(ring.sonars.size());
  std::vector<bool> seen(ring.sonars.size());
  for (const Scan& s : d.scans) {
    if (s.truth) {
      out += "TRUEPOS ";
      appendPose(out, *s.truth);
      out += ' ';
      appendPose(out, s.odometry);
      appendTrailer(out, s.time);
    }
    out += "ODOM ";
    appendPose(out, s.odometry);
    out += " 0 0 0";
    appendTrailer(out, s.time);
    std::fill(ranges.begin(), ranges.end(), ring.maxRange);
    std::fill(seen.begin(), seen.end(), false);
    for (const Reading& r : s.readings) {
      if (seen[r.sonar]) {
        appendSonar(out, ring, ranges, s.time);
        std::fill(ranges.begin(), ranges.end(), ring.maxRange);
        std::fill(seen.begin(), seen.end(), false);
      }
      seen[r.sonar] = true;
      ranges[r.sonar] = r.echo() ? r.range : ring.maxRange;
    }
    appendSonar(out, ring, ranges, s.time);
  }
  return out;
}

}  // namespace

Dataset readCarmen(text::ByteSource& source, const std::string& displayName,
                   const LogOptions& options, LoadReport& report) {
  report.format = LogFormat::Carmen;
  return CarmenParser(source, displayName, options, report).run(options);
}

void writeCarmen(const Dataset& dataset, std::ostream& out) {
  std::string text;
  try {
    text = carmenText(dataset);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(std::string("cannot write the CARMEN log: ") + e.what());
  }
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.flush();
  if (!out) throw std::runtime_error("cannot write the CARMEN log: the output stream failed");
}

void writeCarmen(const Dataset& dataset, const std::string& path) {
  std::string text;
  try {
    text = carmenText(dataset);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("cannot write '" + path + "': " + e.what());
  }
  writeFileAtomically(path, text);
}

}  // namespace sg
