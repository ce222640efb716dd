// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Log fixtures written the way the real loggers write them: each line comes from the printf
// format strings of the logger's own source, so a reader that refuses what they print (a leading
// '+', zero padding, "%lf") is caught. One table of scans feeds every format, so the readers can
// be checked against each other: the same ring, poses and ranges must load as the same readings.
//
// make_writer_fixtures writes these texts to tests/data/logs/ and the fuzz seed corpora; the reader
// tests regenerate them and compare bytes, so the committed files cannot drift from this source.
//
// Every value of the table has at most as many decimals as the coarsest format that prints it
// (CARMEN's "%.2lf" ranges, Player's "%+07.3f" poses and "%+07.4f" sonar yaws), so every format
// prints it exactly and reads back the same double. Each signed field takes negative, zero and
// positive values somewhere in a file; a range is never negative (no logger writes one).

#include <locale.h>
#include <array>
#include <cstdarg>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "sonargrid/data/dataset.h"
#include "sonargrid/io/sglog.h"

namespace writer_fixtures {

// The ring: x, y and yaw each negative, zero and positive across the four sonars.
struct Mount {
  double x, y, yaw;
};
inline constexpr std::array<Mount, 4> kRing{{
    {0.125, 0.000, 0.0000},
    {0.000, 0.150, 1.5708},
    {-0.125, 0.000, 3.1416},
    {0.000, -0.150, -1.5708},
}};
inline constexpr double kConeAngle = 0.4363;  // CARMEN's SONAR cone_angle; 25 degrees

struct Scan {
  double time;            // the sonar message's; the pose message comes kPoseLead earlier
  double x, y, theta;     // odometry
  double vx, vy, va;      // Player's velocities; CARMEN's tv is vx and rv is va
  double accel;           // CARMEN's ODOM accel
  int stall;              // Player's position2d stall flag
  double tx, ty, ttheta;  // CARMEN's TRUEPOS true pose
  std::array<double, 4> ranges;
};
// Ranges: 0, ordinary echoes, 4.99 just inside SonarRing's default maximum (5 m), 5.00 at it and
// 7.25 beyond it (both no echo).
// clang-format off
inline constexpr std::array<Scan, 4> kScans{{
  //  time          x       y       theta   vx      vy      va      accel  stall tx      ty      ttheta  ranges
    {1166644800.100, 0.000,  0.000,  0.000,  0.000,  0.000,  0.000,  0.000, 0,   0.000,  0.000,  0.000, {1.50, 2.00, 5.00, 0.80}},
    {1166644800.200, 1.250, -0.500, -0.785,  0.300, -0.050, -0.100,  0.100, 0,   1.275, -0.525, -0.800, {0.00, 4.99, 7.25, 2.50}},
    {1166644800.300,-2.125,  3.000,  2.356, -0.300,  0.050,  0.250, -0.200, 1,  -2.100,  2.950,  2.400, {3.33, 0.25, 1.00, 5.00}},
    {1166644800.400,-0.375, -1.750, -3.000, -0.0,    0.000, -0.250,  0.050, 0,  -0.400, -1.700, -2.950, {0.15, 1.75, 2.25, 4.50}},
}};
// clang-format on
inline constexpr double kPoseLead = 0.050;   // the pose message precedes its scan by this much
inline constexpr double kLoggerLag = 0.012;  // CARMEN: logger_timestamp - ipc_timestamp

// The Player ranger fixture's device pose in the robot frame (px py pz proll ppitch pyaw) and size:
// the element poses are the ring's minus this offset, so that device pose composed with element
// pose gives the ring back (within rounding).
inline constexpr std::array<double, 6> kRangerDevice{-0.050, 0.000, 0.250, 0.000, 0.000, 0.000};
inline constexpr std::array<double, 3> kRangerDeviceSize{0.440, 0.380, 0.000};

// snprintf onto a string. printf follows LC_NUMERIC, which a Qt application takes from the
// environment; the loggers write in the C locale, so the fixtures are too.
class CLocale {
 public:
  CLocale() : c_(newlocale(LC_NUMERIC_MASK, "C", nullptr)), old_(uselocale(c_)) {}
  ~CLocale() {
    uselocale(old_);
    freelocale(c_);
  }
  CLocale(const CLocale&) = delete;
  CLocale& operator=(const CLocale&) = delete;

 private:
  locale_t c_;
  locale_t old_;
};

[[gnu::format(printf, 2, 3)]] inline void appendf(std::string& out, const char* format, ...) {
  char buf[512];
  va_list args;
  va_start(args, format);
  const int n = std::vsnprintf(buf, sizeof buf, format, args);
  va_end(args);
  out.append(buf, static_cast<std::size_t>(n));
}

// Player writelog, server/drivers/shell/writelog.cc of Player 3.0.x (the same strings for sonar and
// position2d as in Player 2.1.3): the file header of WriteLog::OpenFile(), the message header of
// WriteLog::Write() "%014.3f %u %u %s %02u %03u %03u ", then the payload.
inline constexpr unsigned kPlayerHost = 16777343;  // 127.0.0.1 as Player's address integer
inline constexpr unsigned kPlayerRobot = 6665;     // the port

inline void playerFileHeader(std::string& out) {
  appendf(out, "## Player version %s \n", "3.0.2");
  appendf(out, "## File version %s \n", "0.3.0");
  appendf(out, "## Format: \n");
  appendf(out, "## - Messages are newline-separated\n");
  appendf(out, "## - Common header to each message is:\n");
  appendf(out, "##   time     host   robot  interface index  type   subtype\n");
  appendf(out, "##   (double) (uint) (uint) (string)  (uint) (uint) (uint)\n");
  appendf(out, "## - Following the common header is the message payload \n");
}

inline void playerHeader(std::string& out, double time, const char* interface, unsigned type,
                         unsigned subtype) {
  appendf(out, "%014.3f %u %u %s %02u %03u %03u ", time, kPlayerHost, kPlayerRobot, interface, 0U,
          type, subtype);
}

// WritePosition(), PLAYER_POSITION2D_DATA_STATE (1:1).
inline void playerPosition(std::string& out, const Scan& s) {
  playerHeader(out, s.time - kPoseLead, "position2d", 1, 1);
  appendf(out, "%+07.3f %+07.3f %+04.3f %+07.3f %+07.3f %+07.3f %d", s.x, s.y, s.theta, s.vx, s.vy,
          s.va, s.stall);
  appendf(out, "\n");
}

// A Player 3 log of a sonar device: its geometry (the PLAYER_SONAR_REQ_GET_GEOM reply, 4:1, that
// WriteGeometries() logs on opening), the position2d geometry reply (4:1, not used by SonarGrid),
// then position2d 1:1 and sonar 1:1 (PLAYER_SONAR_DATA_RANGES) for each scan.
inline std::string playerSonarLog() {
  const CLocale c;
  std::string out;
  playerFileHeader(out);
  const double opened = kScans[0].time - 2 * kPoseLead;
  playerHeader(out, opened, "sonar", 4, 1);
  appendf(out, "%u ", static_cast<unsigned>(kRing.size()));
  for (const Mount& m : kRing) appendf(out, "%+07.3f %+07.3f %+07.4f ", m.x, m.y, m.yaw);
  appendf(out, "\n");
  playerHeader(out, opened, "position2d", 4, 1);
  appendf(out, "%+07.3f %+07.3f %+04.3f %+07.3f %+07.3f", -0.040, 0.000, 0.000, 0.440, 0.380);
  appendf(out, "\n");
  for (const Scan& s : kScans) {
    playerPosition(out, s);
    playerHeader(out, s.time, "sonar", 1, 1);
    appendf(out, "%u ", static_cast<unsigned>(s.ranges.size()));
    for (const double r : s.ranges) appendf(out, "%.3f ", r);
    appendf(out, "\n");
  }
  return out;
}

// WriteRanger()'s geometry, as in the PLAYER_RANGER_REQ_GET_GEOM reply and a stamped scan with
// have_geom: the device pose and size, then each element's pose (in the device frame) and size.
inline void playerRangerGeometry(std::string& out) {
  const auto& d = kRangerDevice;
  const auto& z = kRangerDeviceSize;
  appendf(out, "%+07.3f %+07.3f %+07.3f %+07.3f %+07.3f %+07.3f %+07.3f %+07.3f %+07.3f ", d[0],
          d[1], d[2], d[3], d[4], d[5], z[0], z[1], z[2]);
  appendf(out, "%04d ", static_cast<int>(kRing.size()));
  // z, roll and pitch of the elements: negative, zero and positive, read and not used.
  constexpr std::array<double, 4> tilt{0.000, -0.020, 0.030, 0.000};
  for (std::size_t i = 0; i < kRing.size(); ++i) {
    const Mount& m = kRing[i];
    appendf(out, "%+07.3f %+07.3f %+07.3f %+07.3f %+07.3f %+07.3f ", m.x - d[0], m.y - d[1],
            tilt[i], tilt[(i + 1) % 4], tilt[(i + 2) % 4], m.yaw);
  }
  appendf(out, "%04d ", static_cast<int>(kRing.size()));
  for (std::size_t i = 0; i < kRing.size(); ++i) {
    appendf(out, "%+07.3f %+07.3f %+07.3f ", 0.000, 0.050 + 0.010 * double(i), 0.030);
  }
}

// A Player 3 log of a ranger device (how Stage 4 and Player 3 drivers offer a sonar array): the
// geometry (4:1) and configuration (PLAYER_RANGER_REQ_GET_CONFIG, 4:5) replies, then for each scan
// position2d 1:1 and a ranger scan: plain (PLAYER_RANGER_DATA_RANGE, 1:1) or stamped
// (PLAYER_RANGER_DATA_RANGESTAMPED, 1:2) with the geometry and configuration, with the
// configuration only, and with neither.
inline std::string playerRangerLog() {
  const CLocale c;
  std::string out;
  playerFileHeader(out);
  const double opened = kScans[0].time - 2 * kPoseLead;
  playerHeader(out, opened, "ranger", 4, 1);
  playerRangerGeometry(out);
  appendf(out, "\n");
  // min_angle max_angle angular_res min_range max_range range_res frequency
  const std::array<double, 7> config{-0.218, 0.218, 0.000, 0.000, 5.000, 0.001, 10.000};
  playerHeader(out, opened, "ranger", 4, 5);
  appendf(out, "%lf %lf %lf %lf %lf %lf %lf ", config[0], config[1], config[2], config[3],
          config[4], config[5], config[6]);
  appendf(out, "\n");
  for (std::size_t k = 0; k < kScans.size(); ++k) {
    const Scan& s = kScans[k];
    playerPosition(out, s);
    playerHeader(out, s.time, "ranger", 1, k == 0 ? 1 : 2);
    appendf(out, "%04d ", static_cast<int>(s.ranges.size()));
    for (const double r : s.ranges) appendf(out, "%.3f ", r);
    if (k != 0) {
      const bool haveGeometry = k == 1;
      const bool haveConfig = k != 3;
      appendf(out, "%d ", haveGeometry ? 1 : 0);
      if (haveGeometry) playerRangerGeometry(out);
      if (haveConfig) {
        appendf(out, "%.4f %.4f %.4f %.4f %.4f %.4f %.4f ", config[0], config[1], config[2],
                config[3], config[4], config[5], config[6]);
      }
    }
    appendf(out, "\n");
  }
  return out;
}

// CARMEN's logger, src/logger/writelog.c of CARMEN 0.7.x: the start of the header of
// carmen_logwrite_write_header(), a PARAM line, then per scan ODOM
// (carmen_logwrite_write_odometry), TRUEPOS (carmen_logwrite_write_truepos) and SONAR
// (carmen_logwrite_write_base_sonar), and a SYNC line; every message ends with
// "ipc_timestamp host logger_timestamp".
inline constexpr const char* kCarmenHost = "pioneer-1";

inline std::string carmenLog() {
  const CLocale c;
  std::string out;
  appendf(out, "%s\n", "# CARMEN Logfile");
  appendf(out, "# file format is one message per line\n");
  appendf(out, "# message_name [message contents] ipc_timestamp ipc_hostname logger_timestamp\n");
  appendf(out, "# ODOM x y theta tv rv accel\n");
  appendf(out, "# TRUEPOS true_x true_y true_theta odom_x odom_y odom_theta\n");
  appendf(out, "# SONAR cone_angle num_sonars [sonar_reading] [sonar_offsets x y theta]\n");
  const double opened = kScans[0].time - 2 * kPoseLead;
  appendf(out, "PARAM %s_%s %s %f %s %f\n", "robot", "sonar_cone_angle", "0.4363", opened,
          kCarmenHost, opened + kLoggerLag);
  for (const Scan& s : kScans) {
    const double t = s.time - kPoseLead;
    appendf(out, "ODOM %f %f %f %f %f %f %f %s %f\n", s.x, s.y, s.theta, s.vx, s.va, s.accel, t,
            kCarmenHost, t + kLoggerLag);
    appendf(out, "TRUEPOS %f %f %f %f %f %f %f %s %f\n", s.tx, s.ty, s.ttheta, s.x, s.y, s.theta, t,
            kCarmenHost, t + kLoggerLag);
    appendf(out, "SONAR %f %d ", kConeAngle, static_cast<int>(s.ranges.size()));
    for (const double r : s.ranges) appendf(out, "%.2lf ", r);
    for (const Mount& m : kRing) appendf(out, "%.3f %.3f %f ", m.x, m.y, m.yaw);
    appendf(out, "%lf %s %lf\n", s.time, kCarmenHost, s.time + kLoggerLag);
  }
  const double closed = kScans.back().time + kPoseLead;
  appendf(out, "SYNC %s %f %s %f\n", "end", closed, kCarmenHost, closed + kLoggerLag);
  return out;
}

// Any log in CARMEN's and Player's own format strings (those of carmenLog and playerSonarLog
// above), one message per scan: the same readings in every format, for the readers to be checked
// against each other on a log of any length. Velocities, accelerations and stalls are 0; a
// reading without echo is written at the ring's max_range; each pose message precedes its scan by
// kPoseLead. Every value must already have no more decimals than the formats print (2 for CARMEN's
// ranges, 3 for Player's poses and ranges, 4 for its sonar yaws) for the files to hold the same
// numbers.
inline std::string carmenLogOf(const sg::Dataset& d) {
  const CLocale c;
  std::string out;
  appendf(out, "# CARMEN Logfile\n");
  for (const sg::Scan& s : d.scans) {
    const double t = s.time - kPoseLead;
    const sg::Pose2D& o = s.odometry;
    appendf(out, "ODOM %f %f %f %f %f %f %f %s %f\n", o.x(), o.y(), o.heading, 0.0, 0.0, 0.0, t,
            kCarmenHost, t + kLoggerLag);
    if (s.truth)
      appendf(out, "TRUEPOS %f %f %f %f %f %f %f %s %f\n", s.truth->x(), s.truth->y(),
              s.truth->heading, o.x(), o.y(), o.heading, t, kCarmenHost, t + kLoggerLag);
    std::vector<double> ranges(d.ring.size(), d.ring.maxRange);
    for (const sg::Reading& r : s.readings) ranges[r.sonar] = r.echo() ? r.range : d.ring.maxRange;
    appendf(out, "SONAR %f %d ", d.ring.apertureRad, static_cast<int>(ranges.size()));
    for (const double r : ranges) appendf(out, "%.2lf ", r);
    for (const sg::SonarMount& m : d.ring.sonars)
      appendf(out, "%.3f %.3f %f ", m.pose.x(), m.pose.y(), m.pose.heading);
    appendf(out, "%lf %s %lf\n", s.time, kCarmenHost, s.time + kLoggerLag);
  }
  return out;
}

inline std::string playerSonarLogOf(const sg::Dataset& d) {
  const CLocale c;
  std::string out;
  playerFileHeader(out);
  const double opened = d.scans.empty() ? 0.0 : d.scans.front().time - 2 * kPoseLead;
  playerHeader(out, opened, "sonar", 4, 1);
  appendf(out, "%u ", static_cast<unsigned>(d.ring.size()));
  for (const sg::SonarMount& m : d.ring.sonars)
    appendf(out, "%+07.3f %+07.3f %+07.4f ", m.pose.x(), m.pose.y(), m.pose.heading);
  appendf(out, "\n");
  for (const sg::Scan& s : d.scans) {
    playerHeader(out, s.time - kPoseLead, "position2d", 1, 1);
    appendf(out, "%+07.3f %+07.3f %+04.3f %+07.3f %+07.3f %+07.3f %d", s.odometry.x(),
            s.odometry.y(), s.odometry.heading, 0.0, 0.0, 0.0, 0);
    appendf(out, "\n");
    std::vector<double> ranges(d.ring.size(), d.ring.maxRange);
    for (const sg::Reading& r : s.readings) ranges[r.sonar] = r.echo() ? r.range : d.ring.maxRange;
    playerHeader(out, s.time, "sonar", 1, 1);
    appendf(out, "%u ", static_cast<unsigned>(ranges.size()));
    for (const double r : ranges) appendf(out, "%.3f ", r);
    appendf(out, "\n");
  }
  return out;
}

// The dataset every fixture holds: what the CARMEN fixture loads as, readings at or beyond the
// default maximum range as no echo.
inline sg::Dataset dataset() {
  sg::Dataset d;
  d.name = "CARMEN log";
  d.ring.robot = "custom";
  d.ring.apertureRad = kConeAngle;
  for (const Mount& m : kRing) d.ring.sonars.push_back(sg::SonarMount{sg::Pose2D(m.x, m.y, m.yaw)});
  for (const Scan& s : kScans) {
    sg::Scan& scan = d.scans.emplace_back();
    scan.time = s.time;
    scan.odometry = sg::Pose2D(s.x, s.y, s.theta);
    scan.truth = sg::Pose2D(s.tx, s.ty, s.ttheta);
    for (std::size_t i = 0; i < s.ranges.size(); ++i) {
      const double r = s.ranges[i] >= d.ring.maxRange ? sg::Reading::kNoEcho : s.ranges[i];
      scan.readings.push_back(sg::Reading{static_cast<std::uint16_t>(i), r, s.time});
    }
  }
  return d;
}

// The project's own writer (writeSglog) on the same dataset.
inline std::string sglogLog() {
  sg::Dataset d = dataset();
  d.name = "writer fixture";
  std::ostringstream out;
  sg::writeSglog(d, out);
  return out.str();
}

struct File {
  std::string name;                  // under tests/data/logs/
  std::vector<std::string> corpora;  // fuzz targets whose seeds it joins (tests/fuzz/corpus/<t>/)
  std::string (*make)();
};
inline const std::vector<File>& files() {
  static const std::vector<File> all{
      {"writelog_p3_sonar.playerlog", {"player", "log_auto"}, playerSonarLog},
      {"writelog_p3_ranger.playerlog", {"player", "log_auto"}, playerRangerLog},
      {"logger_07.clf", {"carmen", "log_auto"}, carmenLog},
      {"writer.sglog", {"sglog", "log_auto"}, sglogLog},
  };
  return all;
}

}  // namespace writer_fixtures
