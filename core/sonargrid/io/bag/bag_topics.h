// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The first half of reading a bag as a log (bag_log.cpp): its storage files opened as their
// containers, and the topics it offers picked for each role with the reasons said. Only
// bag_log.cpp includes it; split from there to keep the loader's file readable.

#include <algorithm>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "sonargrid/base/log_error.h"
#include "sonargrid/io/bag/bag.h"
#include "sonargrid/io/bag/mcap.h"
#include "sonargrid/io/bag/ros_messages.h"
#include "sonargrid/io/bag/rosbag1.h"
#include "sonargrid/io/bag/rosbag2_sqlite.h"
#include "sonargrid/io/log_options.h"

namespace sg::bag::bag_topics {

namespace fs = std::filesystem;

inline std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

inline bool contains(std::string_view s, std::string_view part) {
  return s.find(part) != std::string_view::npos;
}

// "sonar_2" before "sonar_10": runs of digits compare as numbers.
inline bool naturalLess(std::string_view a, std::string_view b) {
  std::size_t i = 0, j = 0;
  auto digit = [](char c) { return c >= '0' && c <= '9'; };
  while (i < a.size() && j < b.size()) {
    if (digit(a[i]) && digit(b[j])) {
      std::size_t i2 = i, j2 = j;
      while (i2 < a.size() && digit(a[i2])) ++i2;
      while (j2 < b.size() && digit(b[j2])) ++j2;
      std::string_view na = a.substr(i, i2 - i), nb = b.substr(j, j2 - j);
      while (na.size() > 1 && na.front() == '0') na.remove_prefix(1);
      while (nb.size() > 1 && nb.front() == '0') nb.remove_prefix(1);
      if (na.size() != nb.size()) return na.size() < nb.size();
      if (na != nb) return na < nb;
      i = i2;
      j = j2;
    } else {
      if (a[i] != b[j]) return a[i] < b[j];
      ++i;
      ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

inline std::string shortType(std::string_view type) {
  std::string t(type);
  const std::size_t msg = t.find("/msg/");
  if (msg != std::string::npos) t.erase(msg, 4);
  return t;
}

inline bool truthLike(const std::string& name) {
  const std::string n = lower(name);
  return contains(n, "truth") || contains(n, "ground") || contains(n, "mocap") ||
         contains(n, "vicon") || contains(n, "_gt") || n.ends_with("/gt");
}

// --- The bag's files -------------------------------------------------------------------------

inline std::vector<std::string> storageFiles(const std::string& path) {
  fs::path p(path);
  std::error_code ec;
  if (p.filename() == "metadata.yaml") p = p.parent_path();
  if (p.empty()) p = ".";
  if (!fs::is_directory(p, ec)) return {path};
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(p, ec)) {
    const std::string ext = entry.path().extension().string();
    if (entry.is_regular_file(ec) && (ext == ".db3" || ext == ".mcap")) {
      files.push_back(entry.path().string());
    }
  }
  if (ec) throw LogError(path, 0, "", "cannot list the folder: " + ec.message());
  if (files.empty()) {
    throw LogError(path, 0, "",
                   "a folder without rosbag2 storage files (.db3 or .mcap); give a bag file or a "
                   "rosbag2 folder");
  }
  std::sort(files.begin(), files.end(),
            [](const std::string& a, const std::string& b) { return naturalLess(a, b); });
  return files;
}

inline LogError fromBagError(const BagError& e) {
  std::string where;
  // The SQLite storage names a message by its id in the message itself, not by an offset.
  const bool byId = e.message().rfind("message id ", 0) == 0;
  if (!byId && (e.offset() != 0 || !e.topic().empty()))
    where = "offset " + std::to_string(e.offset());
  if (!e.topic().empty())
    where += (where.empty() ? "topic " : " (topic ") + e.topic() + (where.empty() ? "" : ")");
  return LogError(e.file(), 0, where, e.message());
}

struct OpenFile {
  std::string name;  // the storage file, for messages
  Container container = Container::Unknown;
  std::uint64_t size = 0;
  std::unique_ptr<Reader> reader;
};

inline constexpr const char* kNotABag =
    "not a ROS bag: expected '#ROSBAG V2.0' (ROS 1), the MCAP magic or an SQLite database "
    "(rosbag2)";

inline OpenFile openFile(const std::string& file) {
  OpenFile out;
  out.name = file;
  try {
    auto source = fileSource(file);
    out.size = source->size();
    std::string head;
    source->read(0, static_cast<std::size_t>(std::min<std::uint64_t>(out.size, 16)), head);
    out.container = detectContainer(head);
    switch (out.container) {
      case Container::Ros1:
        out.reader = openRos1(std::move(source));
        break;
      case Container::Mcap:
        out.reader = openMcap(std::move(source));
        break;
      case Container::Sqlite:
        out.reader = openSqlite(file);
        break;
      case Container::Unknown:
        throw LogError(file, 0, "format", kNotABag);
    }
  } catch (const BagError& e) {
    throw fromBagError(e);
  }
  return out;
}

inline OpenFile openBytes(std::string_view bytes, const std::string& name) {
  OpenFile out;
  out.name = name;
  out.size = bytes.size();
  out.container = detectContainer(bytes.substr(0, 16));
  try {
    switch (out.container) {
      case Container::Ros1:
        out.reader = openRos1(memorySource(bytes, name));
        break;
      case Container::Mcap:
        out.reader = openMcap(memorySource(bytes, name));
        break;
      case Container::Sqlite:
        out.reader = openSqliteBytes(bytes, name);
        break;
      case Container::Unknown:
        throw LogError(name, 0, "format", kNotABag);
    }
  } catch (const BagError& e) {
    throw fromBagError(e);
  }
  return out;
}

// --- Choosing topics -------------------------------------------------------------------------

inline std::string describe(const Topic& t) {
  return t.name + " (" + shortType(t.type) + ", " + std::to_string(t.count) + " messages)";
}

inline void mergeTopics(std::vector<Topic>& into, const std::vector<Topic>& more) {
  for (const Topic& t : more) {
    auto it =
        std::find_if(into.begin(), into.end(), [&t](const Topic& o) { return o.name == t.name; });
    if (it == into.end()) {
      into.push_back(t);
    } else {
      it->count += t.count;
      if (t.count != 0) {
        it->firstNs = it->count == t.count ? t.firstNs : std::min(it->firstNs, t.firstNs);
        it->lastNs = std::max(it->lastNs, t.lastNs);
      }
    }
  }
}

inline BagTopics pickTopics(const std::vector<Topic>& topics, std::vector<std::string>& notes) {
  BagTopics picks;
  std::vector<const Topic*> ranges, clouds, odoms, truths;
  bool tf = false;
  for (const Topic& t : topics) {
    const MessageType m = messageType(t.type);
    if (m == MessageType::Range) ranges.push_back(&t);
    if ((m == MessageType::PointCloud || m == MessageType::PointCloud2) &&
        contains(lower(t.name), "sonar")) {
      clouds.push_back(&t);
    }
    if ((m == MessageType::Odometry || m == MessageType::PoseStamped) && truthLike(t.name)) {
      truths.push_back(&t);
    } else if (m == MessageType::Odometry) {
      odoms.push_back(&t);
    }
    if (m == MessageType::Tf && t.name == "/tf") tf = true;
  }
  if (!ranges.empty()) {
    std::string list;
    for (const Topic* t : ranges) {
      picks.sonar.push_back(t->name);
      list += (list.empty() ? "" : ", ") + describe(*t);
    }
    notes.push_back("sonar: " + list +
                    (ranges.size() > 1 ? ": every Range topic" : ": the Range topic"));
  } else if (!clouds.empty()) {
    picks.sonar.push_back(clouds.front()->name);
    notes.push_back("sonar: " + describe(*clouds.front()) +
                    ": no Range topic, the point cloud named like a sonar");
  } else {
    notes.push_back(
        "sonar: none (no sensor_msgs/Range topic, and no point cloud named like a sonar)");
  }
  auto rank = [](const Topic* t) {
    const std::string n = lower(t->name);
    return contains(n, "odom") ? 0 : contains(n, "pose") ? 1 : 2;
  };
  std::stable_sort(odoms.begin(), odoms.end(),
                   [&rank](const Topic* a, const Topic* b) { return rank(a) < rank(b); });
  if (!odoms.empty()) {
    picks.odometry = odoms.front()->name;
    notes.push_back("odometry: " + describe(*odoms.front()) +
                    (odoms.size() > 1 ? ", of " + std::to_string(odoms.size()) +
                                            " Odometry topics the one named most like odometry"
                                      : ""));
  } else if (tf) {
    picks.odometry = "/tf";
    notes.push_back("odometry: /tf (no nav_msgs/Odometry topic: the odom -> robot transforms)");
  } else {
    notes.push_back("odometry: none (no nav_msgs/Odometry topic and no /tf)");
  }
  if (!truths.empty()) {
    picks.truth = truths.front()->name;
    notes.push_back("true pose: " + describe(*truths.front()) + ", named like ground truth");
  }
  return picks;
}

}  // namespace sg::bag::bag_topics
