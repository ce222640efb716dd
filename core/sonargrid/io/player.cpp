// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/io/player.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "sonargrid/io/text_lines.h"

namespace sg {
namespace {

using text::found;

// docs/formats.md ("Player") is the specification of everything below; keep the two in step.

constexpr std::size_t kMaxSonars = 65536;  // Reading::sonar is 16 bits wide
constexpr std::size_t kHeaderFields = 5;   // time host robot interface index

// Player message types and subtypes (player.h and the interface definitions of Player 3):
// data 1, request-ack 4.
constexpr unsigned long kData = 1;
constexpr unsigned long kAck = 4;
constexpr unsigned long kSonarRanges = 1;    // PLAYER_SONAR_DATA_RANGES
constexpr unsigned long kSonarGeom = 2;      // PLAYER_SONAR_DATA_GEOM
constexpr unsigned long kSonarReqGeom = 1;   // PLAYER_SONAR_REQ_GET_GEOM
constexpr unsigned long kRangerRange = 1;    // PLAYER_RANGER_DATA_RANGE
constexpr unsigned long kRangerStamped = 2;  // PLAYER_RANGER_DATA_RANGESTAMPED
constexpr unsigned long kRangerReqGeom = 1;  // PLAYER_RANGER_REQ_GET_GEOM
constexpr unsigned long kPositionState = 1;  // PLAYER_POSITION2D_DATA_STATE
// Player 3's writelog writes a ranger geometry as the device pose and size (px py pz proll ppitch
// pyaw sw sl sh), then a count and x y z roll pitch yaw of each element, then a count and the
// w l h of each element; a stamped range scan may end with the 7 numbers of the configuration.
constexpr std::size_t kRangerDeviceFields = 9;
constexpr std::size_t kRangerElementFields = 6;
constexpr std::size_t kRangerSizeFields = 3;
constexpr std::size_t kRangerConfigFields = 7;

class PlayerParser : text::LineParser {
 public:
  using LineParser::LineParser;

  Dataset run(const LogOptions& options) {
    eachLine([this] { line(); });
    finish(options);
    return std::move(ds_);
  }

 private:
  void line() {
    if (fields_.empty()) {
      versionComment();
      return;
    }
    const std::size_t header = kHeaderFields + (legacy_ ? 0 : 2);
    if (fields_.size() < header) {
      fail("", std::string("expected ") +
                   (legacy_ ? "time host robot interface index (Player 1.x)"
                            : "time host robot interface index type subtype") +
                   " before the payload, found " + std::to_string(fields_.size()) + " fields");
    }
    const double time = finite(0, "time", "a time in seconds");
    unsigned long index = 0;
    if (!text::parseUnsigned(fields_[4], index)) {
      fail("index", "expected a device index, " + found(fields_[4]));
    }
    unsigned long type = kData;
    unsigned long subtype = 1;
    if (!legacy_) {
      if (!text::parseUnsigned(fields_[5], type)) {
        fail("type", "expected a message type number, " + found(fields_[5]));
      }
      if (!text::parseUnsigned(fields_[6], subtype)) {
        fail("subtype", "expected a message subtype number, " + found(fields_[6]));
      }
    }
    payload_ = header;
    const std::string_view iface = fields_[3];
    if (iface == "position2d" || (legacy_ && iface == "position")) {
      if (type == kData && subtype == kPositionState && sameDevice(positionDevice_)) {
        position();
        return;
      }
    } else if (iface == "sonar") {
      if (type == kData && subtype == kSonarRanges && sameDevice(rangeDevice_)) {
        ranges(time, "sonar", false);
        return;
      }
      if (((type == kData && subtype == kSonarGeom) ||
           (type == kAck && subtype == kSonarReqGeom)) &&
          !legacy_ && sameDevice(rangeDevice_)) {
        geometry("sonar", payload_);
        return;
      }
    } else if (iface == "ranger") {
      if (type == kData && (subtype == kRangerRange || subtype == kRangerStamped) &&
          sameDevice(rangeDevice_)) {
        ranges(time, "ranger", subtype == kRangerStamped);
        return;
      }
      if (type == kAck && subtype == kRangerReqGeom && sameDevice(rangeDevice_)) {
        const std::size_t end = rangerGeometry(payload_);
        needFields("ranger", end - payload_, kRangerGeometryLayout, true);
        return;
      }
    }
    std::string what(iface);
    if (!legacy_) what += " " + std::to_string(type) + ":" + std::to_string(subtype);
    report_.ignore(what);
  }

  // "## Player version 1.6.5": 1.x logs have no type and subtype fields.
  void versionComment() {
    constexpr std::string_view kVersion = "## Player version";
    std::string_view l = line_;
    if (l.substr(0, kVersion.size()) != kVersion) return;
    l.remove_prefix(kVersion.size());
    while (!l.empty() && (l.front() == ' ' || l.front() == '\t')) l.remove_prefix(1);
    legacy_ = !l.empty() && l.front() == '1' && (l.size() == 1 || l[1] == '.');
  }

  // The first device of an interface supplies its data; the others are counted as ignored.
  bool sameDevice(std::string& device) const {
    std::string key;
    for (std::size_t i = 1; i < kHeaderFields; ++i) {
      key += fields_[i];
      key += ' ';
    }
    if (device.empty()) device = key;
    return device == key;
  }

  unsigned long count(std::string_view iface) const {
    const std::string field = std::string(iface) + " count";
    if (fields_.size() <= payload_) fail(field, "expected a count after the header, found nothing");
    unsigned long n = 0;
    if (!text::parseUnsigned(fields_[payload_], n) || n > kMaxSonars) {
      fail(field,
           "expected a count 0.." + std::to_string(kMaxSonars) + ", " + found(fields_[payload_]));
    }
    return n;
  }

  // `exact`: a count says how many fields follow, so more than that is an error too.
  void needFields(std::string_view iface, std::size_t n, const std::string& layout,
                  bool exact) const {
    const std::size_t got = fields_.size() - payload_;
    if (got == n || (got > n && !exact)) return;
    fail(std::string(iface), "expected " + std::string(exact ? "" : "at least ") +
                                 std::to_string(n) + " payload fields (" + layout + "), found " +
                                 std::to_string(got));
  }

  void position() {
    needFields("position2d", 7, "px py pa vx vy va stall", false);
    const double x = finite(payload_, "position2d px", "a number of metres");
    const double y = finite(payload_ + 1, "position2d py", "a number of metres");
    const double a = finite(payload_ + 2, "position2d pa", "an angle in radians");
    pose_ = Pose2D(x, y, a);
  }

  // `count (x y yaw)...` starting at fields_[first].
  std::vector<SonarMount> poses(std::string_view iface, std::size_t first, unsigned long n) const {
    std::vector<SonarMount> out(n);
    for (std::size_t i = 0; i < n; ++i) {
      const std::string index = "[" + std::to_string(i) + "]";
      const std::string prefix = std::string(iface) + " ";
      const double x = finite(first + 3 * i, prefix + "x" + index, "a number of metres");
      const double y = finite(first + 3 * i + 1, prefix + "y" + index, "a number of metres");
      const double yaw = finite(first + 3 * i + 2, prefix + "yaw" + index, "an angle in radians");
      out[i] = SonarMount{Pose2D(x, y, yaw)};
    }
    return out;
  }

  void geometry(std::string_view iface, std::size_t at) {
    const unsigned long n = count(iface);
    needFields(iface, 1 + 3 * n, "count, then x y yaw of each sonar", true);
    std::vector<SonarMount> mounts = poses(iface, at + 1, n);
    setGeometry(std::move(mounts), iface);
  }

  void setGeometry(std::vector<SonarMount> mounts, std::string_view iface) {
    if (geometryLine_ == 0) {
      geometry_ = std::move(mounts);
      geometryLine_ = lineNumber();
    } else if (mounts != geometry_) {
      fail(std::string(iface) + " geometry",
           "expected the geometry of line " + std::to_string(geometryLine_) +
               " (the ring cannot change within a log), found a different one");
    }
  }

  static constexpr const char* kRangerGeometryLayout =
      "px py pz proll ppitch pyaw sw sl sh, a count, x y z roll pitch yaw of each element, a "
      "count, w l h of each element";

  // A ranger geometry starting at fields_[at]; sets the ring and returns the index after it. The
  // elements are the sonars, their poses in the device's frame: the ring gets device pose composed
  // with element pose, in the plane (z, roll and pitch are read as numbers and not used).
  std::size_t rangerGeometry(std::size_t at) {
    const std::size_t before = at - payload_;
    needFields("ranger", before + kRangerDeviceFields + 1, kRangerGeometryLayout, false);
    const double dx = finite(at, "ranger px", "a number of metres");
    const double dy = finite(at + 1, "ranger py", "a number of metres");
    finite(at + 2, "ranger pz", "a number of metres");
    finite(at + 3, "ranger proll", "an angle in radians");
    finite(at + 4, "ranger ppitch", "an angle in radians");
    const double dyaw = finite(at + 5, "ranger pyaw", "an angle in radians");
    finite(at + 6, "ranger sw", "a size in metres");
    finite(at + 7, "ranger sl", "a size in metres");
    finite(at + 8, "ranger sh", "a size in metres");
    at += kRangerDeviceFields;
    const unsigned long n = elementCount(at, "ranger element count");
    needFields("ranger", at - payload_ + 1 + n * kRangerElementFields + 1, kRangerGeometryLayout,
               false);
    const double c = std::cos(dyaw);
    const double s = std::sin(dyaw);
    std::vector<SonarMount> mounts(n);
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t e = at + 1 + kRangerElementFields * i;
      const std::string index = "[" + std::to_string(i) + "]";
      const double x = finite(e, "ranger x" + index, "a number of metres");
      const double y = finite(e + 1, "ranger y" + index, "a number of metres");
      finite(e + 2, "ranger z" + index, "a number of metres");
      finite(e + 3, "ranger roll" + index, "an angle in radians");
      finite(e + 4, "ranger pitch" + index, "an angle in radians");
      const double yaw = finite(e + 5, "ranger yaw" + index, "an angle in radians");
      // Not Pose2D::compose: that wraps the heading, and a device at the robot's origin (the usual
      // case) must give the element poses exactly as logged.
      mounts[i] = SonarMount{Pose2D(dx + c * x - s * y, dy + s * x + c * y, dyaw + yaw)};
    }
    at += 1 + n * kRangerElementFields;
    const unsigned long m = elementCount(at, "ranger size count");
    needFields("ranger", at - payload_ + 1 + m * kRangerSizeFields, kRangerGeometryLayout, false);
    for (std::size_t i = 0; i < m * kRangerSizeFields; ++i) {
      finite(at + 1 + i, "ranger size[" + std::to_string(i / kRangerSizeFields) + "]",
             "a size in metres");
    }
    setGeometry(std::move(mounts), "ranger");
    return at + 1 + m * kRangerSizeFields;
  }

  unsigned long elementCount(std::size_t at, const std::string& field) const {
    unsigned long n = 0;
    if (!text::parseUnsigned(fields_[at], n) || n > kMaxSonars) {
      fail(field, "expected a count 0.." + std::to_string(kMaxSonars) + ", " + found(fields_[at]));
    }
    return n;
  }

  // After the ranges of a stamped ranger scan: have_geom, the geometry when it is not 0, and the
  // configuration or nothing (Player 3's writelog writes no have_config flag, so the number of
  // fields left tells).
  void rangerStampedTail(std::size_t at) {
    const std::string layout =
        "count, the ranges, have_geom, the geometry when have_geom is not 0, then nothing or the "
        "7 configuration numbers";
    unsigned long haveGeometry = 0;
    if (!text::parseUnsigned(fields_[at], haveGeometry)) {
      fail("ranger have_geom", "expected 0 or 1, " + found(fields_[at]));
    }
    ++at;
    if (haveGeometry != 0) at = rangerGeometry(at);
    const std::size_t left = fields_.size() - at;
    if (left != 0 && left != kRangerConfigFields) {
      fail("ranger", "expected " + std::to_string(at - payload_) + " or " +
                         std::to_string(at - payload_ + kRangerConfigFields) + " payload fields (" +
                         layout + "), found " + std::to_string(fields_.size() - payload_));
    }
    for (std::size_t i = 0; i < left; ++i) {
      finite(at + i, "ranger config[" + std::to_string(i) + "]", "a number");
    }
  }

  void ranges(double time, std::string_view iface, bool stamped) {
    const unsigned long n = count(iface);
    if (stamped) {
      needFields(iface, 2 + n, "count, the ranges, have_geom...", false);
    } else {
      needFields(iface, 1 + n, "count, the ranges", true);
    }
    readings_.clear();
    for (std::size_t i = 0; i < n; ++i) {
      const std::string field = std::string(iface) + " r[" + std::to_string(i) + "]";
      const double r = finite(payload_ + 1 + i, field, "a range in metres >= 0");
      if (r < 0.0)
        fail(field, "expected a range in metres >= 0, " + found(fields_[payload_ + 1 + i]));
      readings_.push_back(Reading{static_cast<std::uint16_t>(i), r, time});
    }
    if (stamped) rangerStampedTail(payload_ + 1 + n);
    if (time < lastTime_) {
      fail("time", "expected a time >= " + text::number(lastTime_) +
                       " (the previous scan's; scans are in time order), " + found(fields_[0]));
    }
    if (!pose_) {
      // Devices start at slightly different times; readings before the first pose have no place.
      report_.ignore(std::string(iface) + " data before the first position2d");
      return;
    }
    lastTime_ = time;
    Scan& scan = ds_.scans.emplace_back();
    scan.time = time;
    scan.odometry = *pose_;
    scan.readings = readings_;
    scanLines_.push_back(lineNumber());
    maxCount_ = std::max<std::size_t>(maxCount_, n);
  }

  void finish(const LogOptions& options) {
    if (geometryLine_ != 0) {
      if (options.ring) ds_.ring = *options.ring;  // its aperture and ranges
      ds_.ring.robot = "custom";
      ds_.ring.sonars = geometry_;
    } else if (options.ring) {
      ds_.ring = *options.ring;
    } else {
      throw LogError(file_, 0, "geometry",
                     "expected sonar geometry messages or a robot preset (--robot), found neither");
    }
    if (rangeDevice_.empty()) {
      throw LogError(file_, 0, "sonar", "expected sonar or ranger data messages, found none");
    }
    const std::size_t size = ds_.ring.sonars.size();
    if (maxCount_ > size) dropScansBeyondRing(size);
    const double maxRange = ds_.ring.maxRange;
    for (Scan& s : ds_.scans) {
      for (Reading& r : s.readings) {
        if (r.range >= maxRange) r.range = Reading::kNoEcho;
      }
    }
    ds_.name = "Player log";
  }

  // Scans with more ranges than the ring has sonars: the first is an error, or with lenient
  // loading each is skipped.
  void dropScansBeyondRing(std::size_t size) {
    const std::string where = geometryLine_ != 0
                                  ? "the geometry of line " + std::to_string(geometryLine_)
                                  : std::string("the robot preset");
    std::size_t kept = 0;
    for (std::size_t i = 0; i < ds_.scans.size(); ++i) {
      const std::size_t n = ds_.scans[i].readings.size();
      if (n > size) {
        const LogError e(file_, scanLines_[i], "sonar count",
                         "expected at most " + std::to_string(size) + " ranges (the sonars of " +
                             where + "), found " + std::to_string(n));
        if (!lenient_) throw e;
        report_.skip(e);
        continue;
      }
      if (kept != i) ds_.scans[kept] = std::move(ds_.scans[i]);
      ++kept;
    }
    ds_.scans.resize(kept);
  }

  Dataset ds_;
  bool legacy_ = false;  // Player 1.x
  std::size_t payload_ = 0;
  std::string positionDevice_;
  std::string rangeDevice_;
  std::optional<Pose2D> pose_;
  std::vector<SonarMount> geometry_;
  std::size_t geometryLine_ = 0;
  std::vector<Reading> readings_;
  std::vector<std::size_t> scanLines_;
  std::size_t maxCount_ = 0;
  double lastTime_ = -std::numeric_limits<double>::infinity();
};

}  // namespace

Dataset readPlayer(text::ByteSource& source, const std::string& displayName,
                   const LogOptions& options, LoadReport& report) {
  report.format = LogFormat::Player;
  return PlayerParser(source, displayName, options, report).run(options);
}

}  // namespace sg
