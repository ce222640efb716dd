// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/io/sglog.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <istream>
#include <limits>
#include <numbers>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string_view>
#include <utility>
#include <vector>

#include "sonargrid/base/atomic_file.h"
#include "sonargrid/io/sglog_format.h"
#include "sonargrid/io/start_pose.h"
#include "sonargrid/io/text_lines.h"

namespace sg {
namespace {

// docs/formats.md is the specification of everything below; keep the two in step.

using text::firstBadByte;
using text::found;
using text::foundNumber;
using text::hexDigit;
using text::isControl;
using text::number;
using text::parseFinite;
using text::parseUnsigned;
using text::utf8Sequence;

using namespace sglog_format;  // the keywords and validity rules the writer shares

// ---------------------------------------------------------------------------------------------
// Reading

bool isBlank(char c) {
  return c == ' ' || c == '\t';
}

class Parser : text::LineParser {
 public:
  Parser(text::ByteSource& source, const std::string& file, const LogOptions& options,
         LoadReport& report)
      : LineParser(source, file, options, report), startPose_(options.startPose) {}

  Dataset run() {
    readMagic();
    readHeader();
    readBody();
    report_.lines = lines_.lineNumber();
    // LogOptions::startPose overrides the header's.
    if (startPose_) placeOdometryAt(ds_, *startPose_);
    return std::move(ds_);
  }

 private:
  enum HeaderKey { kName, kRobot, kAperture, kMinRange, kMaxRange, kKeyCount };
  static constexpr std::array<std::string_view, kKeyCount> kKeyNames{"name", "robot", "aperture",
                                                                     "min_range", "max_range"};

  [[noreturn]] void fail(std::string_view field, const std::string& message) const {
    throw LogError(file_, lines_.lineNumber(), std::string(field), message);
  }

  // Reads the next line, checks its bytes and splits it. False at the end.
  bool nextLine() {
    if (!lines_.next(line_)) return false;
    prepareLine();
    return true;
  }

  void prepareLine() {
    text::requireText(line_, file_, lines_.lineNumber());
    text::splitFields(line_, fields_);
  }

  void expectCount(std::size_t n, std::string_view what) const {
    const std::size_t got = fields_.size() - 1;
    if (got == n) return;
    std::string message = "expected " + std::to_string(n) + (n == 1 ? " field" : " fields") +
                          " after '" + std::string(fields_[0]) + "'";
    if (!what.empty()) message += " (" + std::string(what) + ")";
    fail(fields_[0], message + ", found " + std::to_string(got));
  }

  double finite(std::size_t i, std::string_view field, std::string_view expected) const {
    double v = 0.0;
    if (!parseFinite(fields_[i], v))
      fail(field, "expected " + std::string(expected) + ", " + foundNumber(fields_[i]));
    return v;
  }

  void readMagic() {
    const std::string expectedLine =
        "'" + std::string(kMagic) + " " + std::to_string(kSglogVersion) + "'";
    if (!nextLine())
      throw LogError(file_, 0, "", "empty file (expected " + expectedLine + " on the first line)");
    // Editors on some systems start UTF-8 files with a byte order mark; it carries no meaning.
    constexpr std::string_view kBom = "\xEF\xBB\xBF";
    if (line_.substr(0, kBom.size()) == kBom) {
      line_.remove_prefix(kBom.size());
      text::splitFields(line_, fields_);
    }
    if (fields_.size() == 0 || fields_[0] != kMagic) {
      fail("magic", "expected " + expectedLine + " as the first line, " +
                        (line_.empty() ? std::string("found an empty line") : found(line_)));
    }
    if (fields_.size() == 1)
      fail("version", "expected a version number after 'sglog', found nothing");
    unsigned long version = 0;
    if (!parseUnsigned(fields_[1], version)) {
      fail("version", "expected a version number after 'sglog', " + found(fields_[1]));
    }
    if (version != static_cast<unsigned long>(kSglogVersion)) {
      fail("version", "expected version " + std::to_string(kSglogVersion) +
                          " (the only version this reader supports), " + found(fields_[1]));
    }
    expectCount(1, "version");
  }

  void readHeader() {
    for (;;) {
      if (!nextLine()) {
        throw LogError(
            file_, 0, "",
            "truncated: the file ends inside the header (expected an 'end_header' line)");
      }
      if (fields_.size() == 0) continue;
      const std::string_view key = fields_[0];
      if (key == kEndHeader) {
        expectCount(0, "");
        finishHeader();
        return;
      }
      if (key == "sonar") {
        readSonar();
        continue;
      }
      if (key == kStreamed) {
        readStreamed();
        continue;
      }
      if (key == kStartPose) {
        readStartPose();
        continue;
      }
      const auto it = std::find(kKeyNames.begin(), kKeyNames.end(), key);
      if (it == kKeyNames.end()) {
        fail("",
             "expected a header record (name, robot, aperture, min_range, max_range, sonar, "
             "start_pose or end_header), " +
                 found(key));
      }
      const auto k = static_cast<std::size_t>(it - kKeyNames.begin());
      if (keyLine_[k] != 0) {
        fail(key, "expected one '" + std::string(key) +
                      "' line, found a second (the first is line " + std::to_string(keyLine_[k]) +
                      ")");
      }
      keyLine_[k] = lines_.lineNumber();
      switch (static_cast<HeaderKey>(k)) {
        case kName:
          readName();
          break;
        case kRobot:
          expectCount(1, "a preset name or 'custom'");
          if (!validRobotName(fields_[1])) {
            fail(
                "robot",
                "expected a preset name or 'custom' (1 to 64 characters from A-Z a-z 0-9 _ . -), " +
                    found(fields_[1]));
          }
          ds_.ring.robot = std::string(fields_[1]);
          break;
        case kAperture:
          expectCount(1, "full cone angle in radians");
          if (!parseFinite(fields_[1], ds_.ring.apertureRad) ||
              !validAperture(ds_.ring.apertureRad)) {
            fail("aperture",
                 "expected an angle in radians > 0 and <= pi, " + foundNumber(fields_[1]));
          }
          break;
        case kMinRange:
          readMinRange();
          break;
        case kMaxRange:
          readMaxRange();
          break;
        case kKeyCount:
          break;
      }
    }
  }

  void readName() {
    // The name is free text, so it is quoted rather than split into fields.
    const char* p = fields_[0].data() + fields_[0].size();
    const char* end = line_.data() + line_.size();
    while (p != end && isBlank(*p)) ++p;
    if (p == end || *p != '"') {
      fail("name", "expected a quoted string such as \"Room 3\", " +
                       (p == end ? std::string("found nothing")
                                 : found(std::string_view(p, static_cast<std::size_t>(end - p)))));
    }
    ++p;
    std::string name;
    for (;;) {
      if (p == end) fail("name", "expected a closing '\"', found the end of the line");
      const char c = *p++;
      if (c == '"') break;
      if (c != '\\') {
        name += c;
        continue;
      }
      if (p == end) fail("name", "expected an escape after '\\', found the end of the line");
      const char e = *p++;
      switch (e) {
        case '\\':
        case '"':
          name += e;
          break;
        case 'n':
          name += '\n';
          break;
        case 'r':
          name += '\r';
          break;
        case 't':
          name += '\t';
          break;
        case 'x': {
          unsigned value = 0;
          if (end - p < 2 || std::from_chars(p, p + 2, value, 16).ptr != p + 2) {
            const auto n = static_cast<std::size_t>(std::min<std::ptrdiff_t>(end - p, 2));
            fail("name", "expected two hex digits after '\\x', " + found(std::string_view(p, n)));
          }
          name += static_cast<char>(value);
          p += 2;
          break;
        }
        default:
          fail("name", "expected an escape \\\\, \\\", \\n, \\r, \\t or \\xHH after '\\', " +
                           found(std::string_view(p - 1, 1 + utf8Tail(p - 1, end))));
      }
    }
    while (p != end && isBlank(*p)) ++p;
    if (p != end && *p != '#') {
      fail("name", "expected nothing after the closing '\"', " +
                       found(std::string_view(p, static_cast<std::size_t>(end - p))));
    }
    ds_.name = std::move(name);
  }

  // How many continuation bytes follow the lead byte at p (so an error shows whole characters).
  static std::size_t utf8Tail(const char* p, const char* end) {
    std::size_t n = 0;
    while (p + 1 + n != end && (static_cast<unsigned char>(p[1 + n]) & 0xC0) == 0x80) ++n;
    return n;
  }

  void readStartPose() {
    if (startPoseLine_ != 0) {
      fail(kStartPose, "expected one 'start_pose' line, found a second (the first is line " +
                           std::to_string(startPoseLine_) + ")");
    }
    startPoseLine_ = lines_.lineNumber();
    expectCount(3, "x y theta: the robot's pose at the first scan");
    const double x = finite(1, "start_pose x", "a number of metres");
    const double y = finite(2, "start_pose y", "a number of metres");
    const double theta = finite(3, "start_pose theta", "an angle in radians");
    if (!startPose_) startPose_.emplace(x, y, theta);  // LogOptions::startPose overrides it
  }

  void readMinRange() {
    expectCount(1, "metres");
    double v = 0.0;
    const bool haveMax = keyLine_[kMaxRange] != 0;
    if (haveMax) {
      const std::string expected =
          "a number of metres >= 0 and < max_range " + number(ds_.ring.maxRange);
      if (!parseFinite(fields_[1], v) || v < 0.0 || v >= ds_.ring.maxRange) {
        fail("min_range", "expected " + expected + ", " + foundNumber(fields_[1]));
      }
    } else if (!parseFinite(fields_[1], v) || v < 0.0) {
      fail("min_range", "expected a number of metres >= 0, " + foundNumber(fields_[1]));
    }
    ds_.ring.minRange = v;
  }

  void readMaxRange() {
    expectCount(1, "metres");
    double v = 0.0;
    const bool haveMin = keyLine_[kMinRange] != 0;
    if (haveMin) {
      const std::string expected = "a number of metres > min_range " + number(ds_.ring.minRange);
      if (!parseFinite(fields_[1], v) || v <= ds_.ring.minRange) {
        fail("max_range", "expected " + expected + ", " + foundNumber(fields_[1]));
      }
    } else if (!parseFinite(fields_[1], v) || v <= 0.0) {
      fail("max_range", "expected a number of metres > 0, " + foundNumber(fields_[1]));
    }
    ds_.ring.maxRange = v;
  }

  void readSonar() {
    expectCount(4, "index x y heading");
    const std::size_t want = ds_.ring.sonars.size();
    unsigned long index = 0;
    const bool isIndex = parseUnsigned(fields_[1], index);
    if (isIndex && index < want) {
      fail("index", "expected sonar index " + std::to_string(want) + ", " + found(fields_[1]) +
                        ", a duplicate of line " + std::to_string(sonarLines_[index]));
    }
    if (!isIndex || index != want) {
      fail("index", "expected sonar index " + std::to_string(want) +
                        " (sonars are listed 0, 1, 2, ... in order), " + found(fields_[1]));
    }
    if (want >= kMaxSonars) {
      fail("index",
           "expected at most " + std::to_string(kMaxSonars) + " sonars, " + found(fields_[1]));
    }
    const double x = finite(2, "x", "a number of metres");
    const double y = finite(3, "y", "a number of metres");
    const double heading = finite(4, "heading", "an angle in radians");
    ds_.ring.sonars.push_back(SonarMount{Pose2D(x, y, heading)});
    sonarLines_.push_back(lines_.lineNumber());
  }

  void readStreamed() {
    expectCount(0, "");
    if (streamedLine_ != 0) {
      fail(kStreamed, "expected one 'streamed' line, found a second (the first is line " +
                          std::to_string(streamedLine_) + ")");
    }
    streamedLine_ = lines_.lineNumber();
  }

  void finishHeader() {
    for (std::size_t k = 0; k < kKeyCount; ++k) {
      if (keyLine_[k] == 0) {
        fail(kKeyNames[k], "expected one '" + std::string(kKeyNames[k]) +
                               "' line before 'end_header', found none");
      }
    }
    if (ds_.ring.sonars.empty())
      fail("sonar", "expected at least one 'sonar' line before 'end_header', found none");
    // Typical logs carry one reading per sonar per scan; the cap keeps a huge ring with sparse
    // scans from reserving memory it never uses.
    readingsPerScan_ = std::min<std::size_t>(ds_.ring.sonars.size(), 64);
  }

  // With LogOptions::lenient a bad body line is skipped and counted; the readings of a skipped
  // scan are skipped with it, so that none lands on the scan before.
  void readBody() {
    while (lines_.next(line_)) {
      // A streamed log ends wherever its recording stopped: a last line without its line ending
      // may have been cut anywhere, even where it would still read (a range or a time cut short),
      // so it is left out, and reported, unless it is the closing 'end'.
      if (streamedLine_ != 0 && !lines_.lineEnded()) {
        text::splitFields(line_, fields_);
        if (fields_.size() == 1 && fields_[0] == kEnd) return;
        report_.skip(LogError(file_, lines_.lineNumber(), "",
                              "the recording ends inside this line (cut short); it is left out"));
        return;
      }
      try {
        prepareLine();
        if (fields_.size() != 0 && readBodyRecord()) return;
      } catch (const LogError& e) {
        if (!lenient_) throw;
        report_.skip(e);
      }
    }
    if (streamedLine_ != 0) return;
    const LogError truncated(
        file_, 0, "", "truncated: the file ends inside the body (expected a closing 'end' line)");
    if (!lenient_) throw truncated;
    report_.skip(truncated);
  }

  // One record of the body; true after 'end' and the trailer.
  bool readBodyRecord() {
    const std::string_view key = fields_[0];
    if (key == kReading) {
      if (ds_.scans.empty()) fail("", "expected a 'scan' line before the first reading, found 'r'");
      if (skippedScanLine_ != 0) {
        fail("", "expected a reading of a valid scan, found one of the scan skipped on line " +
                     std::to_string(skippedScanLine_));
      }
      readReading();
    } else if (key == kScan) {
      skippedScanLine_ = lines_.lineNumber();
      readScan();
      skippedScanLine_ = 0;
    } else if (key == kEnd) {
      expectCount(0, "");
      readTrailer();
      return true;
    } else {
      fail("", "expected a body record ('scan', 'r' or 'end'), " + found(key));
    }
    return false;
  }

  void readReading() {
    expectCount(3, "sonar range time");
    const unsigned long sonarCount = ds_.ring.sonars.size();
    Reading r;
    unsigned long sonar = 0;
    if (!parseUnsigned(fields_[1], sonar) || sonar >= sonarCount) {
      fail("sonar", "expected a sonar index 0.." + std::to_string(sonarCount - 1) + ", " +
                        found(fields_[1]));
    }
    r.sonar = static_cast<std::uint16_t>(sonar);
    if (fields_[2] == kNone) {
      r.range = Reading::kNoEcho;
    } else {
      if (!parseFinite(fields_[2], r.range) || r.range < 0.0) {
        fail("range", "expected a number of metres >= 0 or 'none', " + foundNumber(fields_[2]));
      }
      // The header says the transducer hears nothing at or beyond max_range.
      if (r.range >= ds_.ring.maxRange) r.range = Reading::kNoEcho;
    }
    r.time = finite(3, "time", "a time in seconds");
    ds_.scans.back().readings.push_back(r);
  }

  void readScan() {
    if (fields_.size() != 6 && fields_.size() != 8) {
      fail("scan",
           "expected 5 fields after 'scan' (time x y theta none) or 7 (time x y theta "
           "true_x true_y true_theta), found " +
               std::to_string(fields_.size() - 1));
    }
    // Locals, not nested calls: argument order is unspecified and errors must be reported for the
    // leftmost bad field.
    const double time = finite(1, "time", "a time in seconds");
    if (time < lastTime_) {
      fail("time", "expected a time >= " + number(lastTime_) +
                       " (the previous scan's; scans are in time order), " + found(fields_[1]));
    }
    const double x = finite(2, "x", "a number of metres");
    const double y = finite(3, "y", "a number of metres");
    const double theta = finite(4, "theta", "an angle in radians");
    std::optional<Pose2D> truth;
    if (fields_.size() == 8) {
      const double tx = finite(5, "true_x", "a number of metres");
      const double ty = finite(6, "true_y", "a number of metres");
      const double ttheta = finite(7, "true_theta", "an angle in radians");
      truth.emplace(tx, ty, ttheta);
    } else if (fields_[5] != kNone) {
      fail("scan", "expected 'none' or a true pose (true_x true_y true_theta) after theta, " +
                       found(fields_[5]) + " alone");
    }
    lastTime_ = time;
    // Built in place: moving a Scan in trips a GCC 12 -Wmaybe-uninitialized false positive.
    Scan& scan = ds_.scans.emplace_back();
    scan.time = time;
    scan.odometry = Pose2D(x, y, theta);
    scan.truth = truth;
    scan.readings.reserve(readingsPerScan_);
  }

  // After 'end' only comments and blank lines may follow.
  void readTrailer() {
    const std::size_t endLine = lines_.lineNumber();
    while (lines_.next(line_)) {
      try {
        prepareLine();
        if (fields_.size() == 0) continue;
        fail("", "expected nothing but comments and blank lines after 'end' (line " +
                     std::to_string(endLine) + "), " + found(fields_[0]));
      } catch (const LogError& e) {
        if (!lenient_) throw;
        report_.skip(e);
      }
    }
  }

  Dataset ds_;
  std::array<std::size_t, kKeyCount> keyLine_{};  // 0 = not seen yet
  std::vector<std::size_t> sonarLines_;
  std::size_t readingsPerScan_ = 0;
  double lastTime_ = -std::numeric_limits<double>::infinity();
  std::size_t skippedScanLine_ = 0;  // the scan line being read or skipped; 0 when valid
  std::size_t streamedLine_ = 0;     // the 'streamed' header line; 0 when the log has none
  std::size_t startPoseLine_ = 0;    // the 'start_pose' header line; 0 when the log has none
  std::optional<Pose2D> startPose_;  // LogOptions::startPose, else the header's
};

}  // namespace

Dataset readSglog(text::ByteSource& source, const std::string& displayName,
                  const LogOptions& options, LoadReport& report) {
  report.format = LogFormat::Sglog;
  return Parser(source, displayName, options, report).run();
}

Dataset parseSglog(std::istream& in, const std::string& displayName) {
  text::StreamSource source(in, displayName);
  LoadReport report;
  return readSglog(source, displayName, LogOptions{}, report);
}

Dataset readSglog(const std::string& path) {
  text::FileSource source(path);
  LoadReport report;
  return readSglog(source, path, LogOptions{}, report);
}

}  // namespace sg
