// SPDX-License-Identifier: BSD-3-Clause
// Writing .sglog: whole logs (atomically, streamed to disk in blocks) and the header and scan
// lines a recorder appends as it goes. The reader is sglog.cpp; docs/formats.md specifies both.
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>

#include "sonargrid/base/atomic_file.h"
#include "sonargrid/io/sglog.h"
#include "sonargrid/io/sglog_format.h"
#include "sonargrid/io/text_lines.h"

namespace sg {
namespace {

using namespace sglog_format;  // the keywords and validity rules the reader shares
using text::hexDigit;
using text::isControl;
using text::number;
using text::utf8Sequence;

// ---------------------------------------------------------------------------------------------
// Writing

// Throws std::runtime_error (without a path; callers add it) when the reader would reject the file.
void checkRing(const SonarRing& ring) {
  auto bad = [](const std::string& why) { throw std::runtime_error(why); };
  if (!validRobotName(ring.robot)) {
    bad("robot name '" + ring.robot + "' is not 1 to 64 characters from A-Z a-z 0-9 _ . -");
  }
  if (!validAperture(ring.apertureRad)) bad("aperture is not an angle > 0 and <= pi");
  if (!std::isfinite(ring.minRange) || ring.minRange < 0.0) bad("min range is not a number >= 0");
  if (!std::isfinite(ring.maxRange) || ring.maxRange <= ring.minRange) {
    bad("max range is not a number > min range");
  }
  if (ring.sonars.empty()) bad("the ring has no sonars");
  if (ring.sonars.size() > kMaxSonars) bad("the ring has more than 65536 sonars");
  for (std::size_t i = 0; i < ring.sonars.size(); ++i) {
    const Pose2D& p = ring.sonars[i].pose;
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.heading))
      bad("sonar " + std::to_string(i) + " has a non-finite pose");
  }
}

// `where` names the scan in messages; `lastTime` is the time of the scan before it.
void checkScan(const Scan& s, std::size_t sonars, double lastTime, const std::string& where) {
  auto bad = [](const std::string& why) { throw std::runtime_error(why); };
  auto finitePose = [](const Pose2D& p) {
    return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.heading);
  };
  if (!std::isfinite(s.time)) bad(where + " has a non-finite time");
  if (s.time < lastTime) bad(where + " is earlier than the scan before it");
  if (!finitePose(s.odometry)) bad(where + " has a non-finite odometry pose");
  if (s.truth && !finitePose(*s.truth)) bad(where + " has a non-finite true pose");
  for (std::size_t k = 0; k < s.readings.size(); ++k) {
    const Reading& r = s.readings[k];
    const std::string what = where + " reading " + std::to_string(k);
    if (r.sonar >= sonars)
      bad(what + " names sonar " + std::to_string(r.sonar) + ", not in the ring");
    if (std::isnan(r.range) || r.range < 0.0) bad(what + " has a range that is not >= 0");
    if (!std::isfinite(r.time)) bad(what + " has a non-finite time");
  }
}

void checkWritable(const Dataset& d) {
  checkRing(d.ring);
  double lastTime = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < d.scans.size(); ++i) {
    checkScan(d.scans[i], d.ring.sonars.size(), lastTime, "scan " + std::to_string(i));
    lastTime = d.scans[i].time;
  }
}

// Where formatted text goes: an ostream, or the temporary file of an atomic write.
class ByteSink {
 public:
  virtual ~ByteSink() = default;
  virtual void write(const char* data, std::size_t n) = 0;  // throws std::runtime_error
};

class StringSink : public ByteSink {
 public:
  explicit StringSink(std::string& out) : out_(out) {}
  void write(const char* data, std::size_t n) override { out_.append(data, n); }

 private:
  std::string& out_;
};

class StreamSink : public ByteSink {
 public:
  explicit StreamSink(std::ostream& out) : out_(out) {}
  void write(const char* data, std::size_t n) override {
    out_.write(data, static_cast<std::streamsize>(n));
    if (!out_) throw std::runtime_error("the output stream failed");
  }

 private:
  std::ostream& out_;
};

class AtomicFileSink : public ByteSink {
 public:
  explicit AtomicFileSink(FileSink& file) : file_(file) {}
  void write(const char* data, std::size_t n) override { file_.write(std::string_view(data, n)); }

 private:
  FileSink& file_;
};

// Formats into a buffer and hands it to the sink in large blocks.
class TextWriter {
 public:
  explicit TextWriter(ByteSink& sink, std::size_t reserve = kFlushBytes + 256) : sink_(sink) {
    buf_.reserve(reserve);
  }

  TextWriter& operator<<(std::string_view s) {
    buf_ += s;
    return *this;
  }
  TextWriter& operator<<(char c) {
    buf_ += c;
    return *this;
  }
  // Shortest text that reads back to the same double.
  TextWriter& operator<<(double v) {
    std::array<char, 32> tmp{};
    const auto r = std::to_chars(tmp.data(), tmp.data() + tmp.size(), v);
    buf_.append(tmp.data(), r.ptr);
    return *this;
  }
  TextWriter& operator<<(std::size_t v) {
    std::array<char, 24> tmp{};
    const auto r = std::to_chars(tmp.data(), tmp.data() + tmp.size(), v);
    buf_.append(tmp.data(), r.ptr);
    return *this;
  }
  void endLine() {
    buf_ += '\n';
    if (buf_.size() >= kFlushBytes) flush();
  }
  void flush() {
    if (!buf_.empty()) sink_.write(buf_.data(), buf_.size());
    buf_.clear();
  }

 private:
  static constexpr std::size_t kFlushBytes = 64 * 1024;
  ByteSink& sink_;
  std::string buf_;
};

// The name between quotes: valid UTF-8 stays readable, everything else is escaped so that any
// byte string comes back unchanged.
void writeQuoted(TextWriter& w, const std::string& s) {
  w << '"';
  const auto* p = reinterpret_cast<const unsigned char*>(s.data());
  const std::size_t n = s.size();
  std::size_t i = 0;
  while (i < n) {
    const unsigned char c = p[i];
    if (c == '"' || c == '\\') {
      w << '\\' << static_cast<char>(c);
    } else if (c == '\n') {
      w << "\\n";
    } else if (c == '\r') {
      w << "\\r";
    } else if (c == '\t') {
      w << "\\t";
    } else if (c < 0x80 && !isControl(c)) {
      w << static_cast<char>(c);
    } else {
      const std::size_t len = c < 0x80 ? 0 : utf8Sequence(p + i, n - i);
      if (len == 0) {
        w << "\\x" << hexDigit(c >> 4U) << hexDigit(c);
      } else {
        w << std::string_view(s.data() + i, len);
        i += len;
        continue;
      }
    }
    ++i;
  }
  w << '"';
}

void writeHeader(TextWriter& w, const Dataset& d, bool streamed,
                 const std::optional<Pose2D>& startPose = std::nullopt) {
  w << kMagic << ' ' << static_cast<std::size_t>(kSglogVersion);
  w.endLine();
  w << "# SonarGrid log; units: metres, radians, seconds; see docs/formats.md";
  w.endLine();
  w << "name ";
  writeQuoted(w, d.name);
  w.endLine();
  w << "robot " << d.ring.robot;
  w.endLine();
  w << "aperture " << d.ring.apertureRad;
  w.endLine();
  w << "min_range " << d.ring.minRange;
  w.endLine();
  w << "max_range " << d.ring.maxRange;
  w.endLine();
  for (std::size_t i = 0; i < d.ring.sonars.size(); ++i) {
    const Pose2D& p = d.ring.sonars[i].pose;
    w << "sonar " << i << ' ' << p.x() << ' ' << p.y() << ' ' << p.heading;
    w.endLine();
  }
  if (startPose) {
    w << kStartPose << ' ' << startPose->x() << ' ' << startPose->y() << ' ' << startPose->heading;
    w.endLine();
  }
  if (streamed) {
    w << kStreamed;
    w.endLine();
  }
  w << kEndHeader;
  w.endLine();
}

// The one formatter of a scan's lines: its 'scan' line and its 'r' lines.
void writeScan(TextWriter& w, const Scan& s) {
  w << kScan << ' ' << s.time << ' ' << s.odometry.x() << ' ' << s.odometry.y() << ' '
    << s.odometry.heading << ' ';
  if (s.truth) {
    w << s.truth->x() << ' ' << s.truth->y() << ' ' << s.truth->heading;
  } else {
    w << kNone;
  }
  w.endLine();
  for (const Reading& r : s.readings) {
    w << kReading << ' ' << static_cast<std::size_t>(r.sonar) << ' ';
    if (r.echo()) {
      w << r.range;
    } else {
      w << kNone;
    }
    w << ' ' << r.time;
    w.endLine();
  }
}

void writeText(const Dataset& d, ByteSink& sink) {
  TextWriter w(sink);
  writeHeader(w, d, false);
  for (const Scan& s : d.scans) writeScan(w, s);
  w << kEnd;
  w.endLine();
  w.flush();
}

}  // namespace

std::string sglogHeaderText(const Dataset& header, bool streamed,
                            const std::optional<Pose2D>& startPose) {
  try {
    checkRing(header.ring);
    if (startPose && !(startPose->position.allFinite() && std::isfinite(startPose->heading)))
      throw std::runtime_error("the start pose is not finite");
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(std::string("cannot write the sglog header: ") + e.what());
  }
  std::string out;
  StringSink sink(out);
  TextWriter w(sink, 0);
  writeHeader(w, header, streamed, startPose);
  w.flush();
  return out;
}

void appendSglogScan(std::string& out, const Scan& scan, const SonarRing& ring,
                     double previousTime) {
  try {
    checkScan(scan, ring.sonars.size(), previousTime, "the scan at time " + number(scan.time));
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(std::string("cannot write the sglog scan: ") + e.what());
  }
  StringSink sink(out);
  TextWriter w(sink, 0);
  writeScan(w, scan);
  w.flush();
}

void writeSglog(const Dataset& dataset, std::ostream& out) {
  try {
    checkWritable(dataset);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(std::string("cannot write the sglog: ") + e.what());
  }
  StreamSink sink(out);
  try {
    writeText(dataset, sink);
    out.flush();
    if (!out) throw std::runtime_error("the output stream failed");
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(std::string("cannot write the sglog: ") + e.what());
  }
}

void writeSglog(const Dataset& dataset, const std::string& path) {
  try {
    checkWritable(dataset);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("cannot write '" + path + "': " + e.what());
  }

  // The text goes straight into the temporary file in 64 KiB blocks: a long log is never held
  // whole in memory.
  writeFileAtomically(path, [&dataset](FileSink& file) {
    AtomicFileSink sink(file);
    writeText(dataset, sink);
  });
}

}  // namespace sg
