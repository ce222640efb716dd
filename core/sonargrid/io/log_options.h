// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// How a log is read (docs/formats.md, "Choosing a reader"): which format, how strictly, the
// sonar geometry and column layout a format may lack, and the progress and cancel hooks of a
// long load. LoadReport says what a load skipped and why.

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "sonargrid/base/log_error.h"
#include "sonargrid/data/pose.h"
#include "sonargrid/data/sonar_ring.h"
#include "sonargrid/io/csv_layout.h"

namespace sg {

enum class LogFormat { Auto, Sglog, Carmen, Player, Csv, Bag };

std::string_view logFormatName(LogFormat f);
// "auto", "sglog", "carmen", "player", "csv" or "bag" (ROS 1 bag, MCAP or rosbag2 SQLite); false
// for anything else.
bool parseLogFormat(std::string_view name, LogFormat& out);

// Thrown when LogOptions::cancel became true during a load; nothing of the load is returned.
class LoadCancelled : public std::runtime_error {
 public:
  explicit LoadCancelled(const std::string& file)
      : std::runtime_error(file + ": loading cancelled") {}
};

// Which topics of a ROS bag make the log (docs/formats.md, "ROS bags"); an empty field is chosen
// from the bag's topics (bag_log.h, inspectBag).
struct BagTopics {
  std::vector<std::string> sonar;  // sensor_msgs/Range topics, or one point cloud topic
  std::string odometry;            // nav_msgs/Odometry; "/tf" for tf's odom -> robot transforms
  std::string truth;               // geometry_msgs/PoseStamped or nav_msgs/Odometry; "-" for none
  bool empty() const { return sonar.empty() && odometry.empty() && truth.empty(); }
  bool operator==(const BagTopics&) const = default;
};

struct LogOptions {
  LogFormat format = LogFormat::Auto;
  // Skip malformed lines (and count them in the LoadReport) instead of stopping at the first.
  // Errors about the file as a whole (cannot open, no geometry, truncated header) still stop it.
  bool lenient = false;
  // The ring for logs that carry no sonar geometry (Player without geometry messages, CSV).
  std::optional<SonarRing> ring;
  // Required for CSV: which column holds what (csv_layout.h).
  std::optional<CsvLayout> csv;
  // CSV only: a second file with the poses, joined to the readings on time.
  std::string posesPath;
  // ROS bags: the topics to read (empty: the bag's obvious ones, reported in LoadReport::notes).
  BagTopics topics;
  // The robot's pose at the log's first scan in the map's frame (start_pose.h): the odometry is
  // moved there. Overrides a .sglog's own start_pose; nullopt keeps the log's (a .sglog's, else
  // the odometry as logged).
  std::optional<Pose2D> startPose;

  // Called after each block read (bytes read so far, file size or 0 when unknown), from the
  // loading thread.
  std::function<void(std::uint64_t done, std::uint64_t total)> progress;
  // Checked after each block read; when true the load throws LoadCancelled.
  const std::atomic<bool>* cancel = nullptr;
};

// What a load left out. Lines are skipped only with LogOptions::lenient; messages of types a
// reader does not use (CARMEN PARAM, Player laser...) are always skipped and counted.
struct LoadReport {
  struct SkipReason {
    std::string field;       // the LogError field, e.g. "SONAR r[2]"
    std::string firstError;  // the full message of the first such line
    std::size_t count = 0;
  };
  LogFormat format = LogFormat::Auto;  // the reader that ran
  std::size_t lines = 0;               // lines read
  std::size_t skippedLines = 0;
  std::vector<SkipReason> skipped;                                   // in order of first sight
  std::vector<std::pair<std::string, std::size_t>> ignoredMessages;  // type, count
  std::vector<std::string> notes;  // what a reader chose or left out (a bag's topics, ...)

  void skip(const LogError& e);
  void ignore(std::string_view messageType);
  // One line per reason, e.g. "2 lines: t.clf:3: SONAR r[2]: expected ... (first of them)".
  std::string summary() const;
};

}  // namespace sg
