// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/io/bag/bag_log.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <utility>

#include "sonargrid/io/bag/bag_topics.h"
#include "sonargrid/io/bag/mcap.h"
#include "sonargrid/io/bag/ros_messages.h"
#include "sonargrid/io/bag/rosbag1.h"
#include "sonargrid/io/bag/rosbag2_sqlite.h"

namespace sg::bag {
namespace {

namespace fs = std::filesystem;

using namespace bag_topics;  // NOLINT: the files and topics of this file, split into bag_topics.h

// --- Reading ---------------------------------------------------------------------------------

enum class Role {
  None,
  Range,
  Cloud,
  Cloud2,
  Odometry,
  OdometryTf,
  Truth,
  TruthOdometry,
  TfStatic,
  Tf
};

// When a message happened: its header's stamp, the container's log time, and its topic. A topic
// whose every header stamp is zero (a driver that leaves them unset) is placed by its log times;
// any other by its stamps, a stamp of 0 included (simulated time starts there).
struct When {
  std::int64_t stamp = 0, log = 0;
  std::size_t topic = 0;  // into Collected::stamped
};

struct Sample {
  When when;
  Pose2D pose;
  std::int64_t ns = 0;  // resolved in build()
};

struct Edge {
  std::string parent;
  Pose2D pose;  // the child frame in the parent's
};

struct RangeObs {
  When when;
  std::int64_t ns = 0;
  std::size_t sensor = 0;  // into Collected::sensors
  double range = 0.0;
};

struct CloudObs {
  When when;
  std::int64_t ns = 0;
  std::vector<Vector3> points;
};

struct Sensor {
  std::string topic, frame;
  float fieldOfView = 0, minRange = 0, maxRange = 0;
};

struct Collected {
  std::vector<Sensor> sensors;
  std::map<std::pair<std::string, std::string>, std::size_t> sensorIndex;
  std::vector<RangeObs> ranges;
  std::vector<CloudObs> clouds;
  std::vector<Sample> odometry, truth;
  std::vector<Sample> tfOdometry;  // /tf's odom -> robot frame transforms
  std::vector<std::string> tfOdometryChild;
  std::map<std::string, std::size_t> topicIds;
  std::vector<bool> stamped;  // per topic: a header stamp other than 0 was seen
  std::map<std::string, Edge> staticEdges, dynamicEdges;
  std::string baseFrame;
  std::size_t messages = 0;
  std::size_t invalidRanges = 0;
};

Pose2D poseOf(const PoseMsg& p) {
  const Quaternion& q = p.orientation;
  return Pose2D(p.position.x, p.position.y, yawOf(q.x, q.y, q.z, q.w));
}

Pose2D poseOf(const TransformMsg& t) {
  const Quaternion& q = t.rotation;
  return Pose2D(t.translation.x, t.translation.y, yawOf(q.x, q.y, q.z, q.w));
}

std::string stripSlash(std::string frame) {
  if (!frame.empty() && frame.front() == '/') frame.erase(0, 1);
  return frame;
}

// Stamps and log times this far from the epoch (146 years) are corrupt; bounding them keeps every
// difference of two within int64.
constexpr std::int64_t kMaxNs = std::int64_t{1} << 62;

class Loader {
 public:
  Loader(std::string name, const LogOptions& options, LoadReport& report)
      : name_(std::move(name)), options_(options), report_(report) {}

  // Reads only the messages within `seconds` of log time from the first one read (a preview).
  void stopAfter(double seconds) { spanNs_ = static_cast<std::int64_t>(seconds * 1e9); }

  Dataset run(std::vector<OpenFile>& files) {
    std::vector<Topic> topics;
    for (const OpenFile& f : files) mergeTopics(topics, f.reader->topics());
    chooseTopics(topics);
    std::uint64_t total = 0, before = 0;
    for (const OpenFile& f : files) total += f.size;
    for (OpenFile& f : files) {
      if (enough_) break;
      readFile(f, before, total);
      before += f.size;
    }
    return build();
  }

 private:
  void chooseTopics(const std::vector<Topic>& topics) {
    std::vector<std::string> notes;
    const BagTopics auto_ = pickTopics(topics, notes);
    picks_ = options_.topics;
    if (picks_.sonar.empty()) picks_.sonar = auto_.sonar;
    if (picks_.odometry.empty()) picks_.odometry = auto_.odometry;
    if (picks_.truth.empty()) picks_.truth = auto_.truth;
    if (picks_.truth == "-") picks_.truth.clear();
    std::string names;
    for (const Topic& t : topics)
      names += (names.empty() ? "" : ", ") + t.name + " (" + shortType(t.type) + ")";
    if (names.empty()) names = "none";
    auto find = [&](const std::string& topic, const char* role) -> const Topic& {
      auto it = std::find_if(topics.begin(), topics.end(),
                             [&](const Topic& t) { return t.name == topic; });
      if (it == topics.end()) {
        throw LogError(name_, 0, "topics",
                       std::string("the ") + role + " topic " + topic +
                           " is not in the bag; its topics: " + names);
      }
      return *it;
    };
    if (picks_.sonar.empty()) {
      throw LogError(name_, 0, "topics",
                     "no sonar topic: the bag has no sensor_msgs/Range topic and no point cloud "
                     "named like a sonar (choose one with --sonar-topic); its topics: " +
                         names);
    }
    if (picks_.odometry.empty()) {
      throw LogError(name_, 0, "topics",
                     "no odometry: the bag has no nav_msgs/Odometry topic and no /tf (choose one "
                     "with --odom-topic); its topics: " +
                         names);
    }
    for (const std::string& s : picks_.sonar) {
      const Topic& t = find(s, "sonar");
      const MessageType m = messageType(t.type);
      if (m == MessageType::Range) {
        roles_[s] = Role::Range;
      } else if (m == MessageType::PointCloud || m == MessageType::PointCloud2) {
        if (picks_.sonar.size() > 1) {
          throw LogError(name_, 0, "topics",
                         "a point cloud sonar topic (" + s + ") goes alone, not with other topics");
        }
        roles_[s] = m == MessageType::PointCloud ? Role::Cloud : Role::Cloud2;
      } else {
        throw LogError(name_, 0, "topics",
                       "the sonar topic " + s + " holds " + t.type +
                           "; a sonar topic holds sensor_msgs/Range, PointCloud or PointCloud2");
      }
    }
    if (picks_.odometry == "/tf") {
      roles_["/tf"] = Role::OdometryTf;
    } else {
      const Topic& t = find(picks_.odometry, "odometry");
      if (messageType(t.type) != MessageType::Odometry) {
        throw LogError(name_, 0, "topics",
                       "the odometry topic " + t.name + " holds " + t.type +
                           "; odometry comes from nav_msgs/Odometry or /tf");
      }
      roles_[t.name] = Role::Odometry;
    }
    if (!picks_.truth.empty()) {
      const Topic& t = find(picks_.truth, "true pose");
      const MessageType m = messageType(t.type);
      if (m != MessageType::PoseStamped && m != MessageType::Odometry) {
        throw LogError(
            name_, 0, "topics",
            "the true pose topic " + t.name + " holds " + t.type +
                "; a true pose comes from geometry_msgs/PoseStamped or nav_msgs/Odometry");
      }
      roles_[t.name] = m == MessageType::PoseStamped ? Role::Truth : Role::TruthOdometry;
    }
    for (const Topic& t : topics) {
      if (messageType(t.type) != MessageType::Tf) continue;
      if (t.name == "/tf_static") roles_.emplace(t.name, Role::TfStatic);
      if (t.name == "/tf") roles_.emplace(t.name, Role::Tf);
    }
    // What was chosen, as the user will see it.
    auto line = [&](const char* role, const std::string& topic, bool chosen) {
      if (topic.empty()) return;
      if (topic == "/tf") {
        report_.notes.push_back(std::string(role) + ": /tf (odom -> robot transforms)" +
                                (chosen ? ", as asked" : ""));
        return;
      }
      report_.notes.push_back(std::string(role) + ": " + describe(find(topic, role)) +
                              (chosen ? ", as asked" : ", picked"));
    };
    for (const std::string& s : picks_.sonar) line("sonar", s, !options_.topics.sonar.empty());
    line("odometry", picks_.odometry, !options_.topics.odometry.empty());
    line("true pose", picks_.truth, !options_.topics.truth.empty());
    for (const Topic& t : topics) {
      if (!roles_.contains(t.name)) report_.ignore(t.name + " (" + shortType(t.type) + ")");
    }
  }

  void readFile(OpenFile& f, std::uint64_t before, std::uint64_t total) {
    const std::vector<Topic>& topics = f.reader->topics();
    std::vector<bool> wanted(topics.size(), false);
    std::vector<Role> roles(topics.size(), Role::None);
    for (std::size_t i = 0; i < topics.size(); ++i) {
      auto it = roles_.find(topics[i].name);
      if (it == roles_.end()) continue;
      wanted[i] = true;
      roles[i] = it->second;
      if (roles[i] == Role::Tf && picks_.odometry == "/tf") roles[i] = Role::OdometryTf;
    }
    ReadOptions ro;
    ro.lenient = options_.lenient;
    ro.cancel = options_.cancel;
    if (options_.progress) {
      ro.progress = [&](std::uint64_t done, std::uint64_t) {
        options_.progress(before + done, total);
      };
    }
    struct Enough {};
    try {
      f.reader->read(wanted, ro, [&](const Message& m) {
        const Topic& t = topics[m.topic];
        if (spanNs_ >= 0) {
          if (!firstNs_) firstNs_ = m.logTimeNs;
          // Compared as a difference of bounded times (kMaxNs): no overflow.
          if (m.logTimeNs >= -kMaxNs && m.logTimeNs <= kMaxNs && m.logTimeNs - *firstNs_ > spanNs_)
            throw Enough{};
        }
        try {
          decode(roles[m.topic], t, m);
        } catch (const MessageError& e) {
          // SQLite's messages are rows: named by id, not by offset.
          const std::string at = (f.container == Container::Sqlite ? "message id " : "offset ") +
                                 std::to_string(m.offset);
          if (!options_.lenient)
            throw LogError(f.name, 0, at + " (topic " + t.name + ")", e.what());
          // Skips are counted by topic, with the first one's place in the message.
          report_.skip(LogError(f.name, 0, "topic " + t.name, at + ": " + e.what()));
        }
      });
    } catch (const BagError& e) {
      throw fromBagError(e);
    } catch (const Enough&) {
      enough_ = true;
    }
    const Skipped& skipped = f.reader->skipped();
    if (skipped.count != 0) {
      report_.skippedLines += skipped.count;
      report_.skipped.push_back(
          LoadReport::SkipReason{"record", skipped.firstError, skipped.count});
    }
  }

  std::size_t sensorOf(const std::string& topic, const RangeMsg& r) {
    const std::string frame = stripSlash(r.header.frameId);
    auto key = std::make_pair(topic, frame);
    auto it = collected_.sensorIndex.find(key);
    if (it != collected_.sensorIndex.end()) return it->second;
    collected_.sensors.push_back(Sensor{topic, frame, r.fieldOfView, r.minRange, r.maxRange});
    collected_.sensorIndex.emplace(key, collected_.sensors.size() - 1);
    return collected_.sensors.size() - 1;
  }

  When when(const Topic& t, const Message& m, const Header& h) {
    const std::int64_t stamp = h.stamp.ns();
    if (m.logTimeNs > kMaxNs || m.logTimeNs < -kMaxNs) {
      throw MessageError("log time " + std::to_string(m.logTimeNs) +
                         " ns: more than 146 years from the epoch");
    }
    auto [it, added] = collected_.topicIds.emplace(t.name, collected_.stamped.size());
    if (added) collected_.stamped.push_back(false);
    if (stamp != 0) collected_.stamped[it->second] = true;
    return When{stamp, m.logTimeNs, it->second};
  }

  std::int64_t resolve(const When& w) const {
    return collected_.stamped[w.topic] ? w.stamp : w.log;
  }

  void decode(Role role, const Topic& t, const Message& m) {
    ++collected_.messages;
    ++report_.lines;
    switch (role) {
      case Role::Range: {
        const RangeMsg r = decodeRange(m.data, t.encoding);
        double range = 0.0;
        if (std::isinf(r.range) && r.range > 0) {
          range = Reading::kNoEcho;  // REP 117: nothing within range
        } else if (!std::isfinite(r.range) || r.range < 0) {
          const std::string what = std::isnan(r.range) ? "NaN (REP 117: an invalid measurement)"
                                   : std::isinf(r.range)
                                       ? "-inf (REP 117: too close to measure)"
                                       : "negative (" + std::to_string(r.range) + ")";
          throw MessageError("Range.range: the range is " + what +
                             "; --lenient leaves such readings out");
        } else if (r.maxRange > 0 && r.range >= r.maxRange) {
          range = Reading::kNoEcho;
        } else {
          range = widen(r.range);
        }
        // After the range's checks, so that a reading --lenient leaves out adds no transducer.
        const When w = when(t, m, r.header);
        collected_.ranges.push_back(RangeObs{w, 0, sensorOf(t.name, r), range});
        break;
      }
      case Role::Cloud:
      case Role::Cloud2: {
        CloudObs c;
        if (role == Role::Cloud) {
          PointCloudMsg p = decodePointCloud(m.data, t.encoding);
          c.when = when(t, m, p.header);
          c.points = std::move(p.points);
        } else {
          PointCloud2Msg p = decodePointCloud2(m.data, t.encoding);
          c.when = when(t, m, p.header);
          c.points = std::move(p.points);
        }
        collected_.clouds.push_back(std::move(c));
        break;
      }
      case Role::Odometry: {
        const OdometryMsg o = decodeOdometry(m.data, t.encoding);
        if (collected_.baseFrame.empty()) collected_.baseFrame = stripSlash(o.childFrameId);
        collected_.odometry.push_back(Sample{when(t, m, o.header), poseOf(o.pose)});
        break;
      }
      case Role::Truth: {
        const PoseStampedMsg p = decodePoseStamped(m.data, t.encoding);
        collected_.truth.push_back(Sample{when(t, m, p.header), poseOf(p.pose)});
        break;
      }
      case Role::TruthOdometry: {
        const OdometryMsg o = decodeOdometry(m.data, t.encoding);
        collected_.truth.push_back(Sample{when(t, m, o.header), poseOf(o.pose)});
        break;
      }
      case Role::TfStatic:
      case Role::Tf:
      case Role::OdometryTf: {
        const TfMsg tf = decodeTf(m.data, t.encoding);
        for (const TransformMsg& x : tf.transforms) {
          const std::string child = stripSlash(x.childFrameId);
          const std::string parent = stripSlash(x.header.frameId);
          auto& edges = role == Role::TfStatic ? collected_.staticEdges : collected_.dynamicEdges;
          // Odometry: the transforms from odom to a frame (the robot's, chosen in build()).
          if (role == Role::OdometryTf && parent == "odom") {
            collected_.tfOdometry.push_back(Sample{when(t, m, x.header), poseOf(x)});
            collected_.tfOdometryChild.push_back(child);
            continue;
          }
          // The first transform seen for a frame places it (a sensor on /tf).
          if (edges.find(child) == edges.end()) edges.emplace(child, Edge{parent, poseOf(x)});
        }
        break;
      }
      case Role::None:
        break;
    }
  }

  // The pose of `frame` in `base`, following parents through /tf_static, then /tf.
  std::optional<Pose2D> chain(const std::string& base, std::string frame) const {
    Pose2D pose;
    for (int depth = 0; depth < 64; ++depth) {
      if (frame == base) return pose;
      auto it = collected_.staticEdges.find(frame);
      if (it == collected_.staticEdges.end()) {
        it = collected_.dynamicEdges.find(frame);
        if (it == collected_.dynamicEdges.end()) return std::nullopt;
      }
      // pose (frame in base) = parent-in-base composed with frame-in-parent; built from the
      // sensor up: frame-in-parent first.
      pose = depth == 0 ? it->second.pose : it->second.pose.compose(pose);
      frame = it->second.parent;
    }
    return std::nullopt;
  }

  SonarRing ringFromSensors() {
    std::vector<std::size_t> order(collected_.sensors.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      const Sensor& x = collected_.sensors[a];
      const Sensor& y = collected_.sensors[b];
      if (x.frame != y.frame) return naturalLess(x.frame, y.frame);
      return naturalLess(x.topic, y.topic);
    });
    sensorSlot_.assign(order.size(), 0);
    for (std::size_t i = 0; i < order.size(); ++i) sensorSlot_[order[i]] = i;
    SonarRing ring;
    const Sensor& first = collected_.sensors[order.front()];
    ring.apertureRad = widenAngle(first.fieldOfView);
    ring.minRange = widen(first.minRange);
    ring.maxRange = widen(first.maxRange);
    std::string missing;
    for (std::size_t i : order) {
      const Sensor& s = collected_.sensors[i];
      // A Range in the robot's own frame (or in none) says nothing of where its transducer is.
      const auto pose =
          s.frame.empty() || s.frame == base() ? std::nullopt : chain(base(), s.frame);
      if (!pose) {
        if (missing.empty()) missing = s.frame.empty() ? "(an empty frame_id)" : s.frame;
        continue;
      }
      ring.sonars.push_back(SonarMount{*pose});
    }
    if (!missing.empty()) {
      if (options_.ring && options_.ring->size() == order.size()) {
        report_.notes.push_back("sonar poses: the robot's (" + options_.ring->robot +
                                "), in the frames' natural order: no transform from " + base() +
                                " to " + missing);
        return *options_.ring;
      }
      throw LogError(name_, 0, "sonar geometry",
                     "no transform from " + base() + " to the sonar frame " + missing +
                         " in /tf_static or /tf; give the robot (--robot p3dx, amigobot, k2a or a "
                         "geometry file) whose sonars are the bag's " +
                         std::to_string(order.size()) + " frames in natural order");
    }
    nameAfterPreset(ring);
    report_.notes.push_back("sonar poses: " + std::to_string(ring.size()) + " from " + base() +
                            " to each Range frame_id in /tf_static or /tf" +
                            (ring.robot != "custom" ? " (the " + ring.robot + "'s)" : ""));
    return ring;
  }

  static void nameAfterPreset(SonarRing& ring) {
    for (const std::string& n : SonarRing::presetNames()) {
      SonarRing preset;
      if (!SonarRing::preset(n, preset)) continue;
      preset.robot = ring.robot;
      if (preset == ring) {
        SonarRing::preset(n, ring);
        return;
      }
    }
  }

  const std::string& base() const {
    static const std::string kBaseLink = "base_link";
    return collected_.baseFrame.empty() ? kBaseLink : collected_.baseFrame;
  }

  // Odometry from /tf: the transforms whose child is the robot's frame.
  void odometryFromTf() {
    const std::string robot = base();
    for (std::size_t i = 0; i < collected_.tfOdometry.size(); ++i) {
      if (collected_.tfOdometryChild[i] == robot)
        collected_.odometry.push_back(collected_.tfOdometry[i]);
    }
    if (collected_.odometry.empty()) {
      throw LogError(name_, 0, "/tf",
                     "no transform from odom to the robot's frame " + robot +
                         " in /tf, so no odometry; choose an Odometry topic with --odom-topic");
    }
  }

  static std::optional<Pose2D> interpolate(const std::vector<Sample>& s, std::int64_t ns) {
    if (s.empty() || ns < s.front().ns || ns > s.back().ns) return std::nullopt;
    auto it = std::lower_bound(s.begin(), s.end(), ns,
                               [](const Sample& a, std::int64_t t) { return a.ns < t; });
    if (it->ns == ns) return it->pose;  // exactly a sample: its pose, untouched
    const Sample& b = *it;
    const Sample& a = *(it - 1);
    const double f = static_cast<double>(ns - a.ns) / static_cast<double>(b.ns - a.ns);
    Pose2D p;
    p.position = a.pose.position + f * (b.pose.position - a.pose.position);
    p.heading = wrapAngle(a.pose.heading + f * wrapAngle(b.pose.heading - a.pose.heading));
    return p;
  }

  Dataset build() {
    Dataset d;
    if (picks_.odometry == "/tf") odometryFromTf();
    for (Sample& x : collected_.odometry) x.ns = resolve(x.when);
    for (Sample& x : collected_.truth) x.ns = resolve(x.when);
    for (RangeObs& x : collected_.ranges) x.ns = resolve(x.when);
    for (CloudObs& x : collected_.clouds) x.ns = resolve(x.when);
    auto byTime = [](const Sample& a, const Sample& b) { return a.ns < b.ns; };
    std::stable_sort(collected_.odometry.begin(), collected_.odometry.end(), byTime);
    std::stable_sort(collected_.truth.begin(), collected_.truth.end(), byTime);
    if (collected_.odometry.empty()) {
      throw LogError(name_, 0, "topics",
                     "the odometry topic " + picks_.odometry + " has no messages");
    }
    // Readings, each with its stamp, in the ring's numbering.
    struct Obs {
      std::int64_t ns;
      std::uint16_t sonar;
      double range;
    };
    std::vector<Obs> obs;
    if (!collected_.ranges.empty()) {
      d.ring = ringFromSensors();
      obs.reserve(collected_.ranges.size());
      for (const RangeObs& r : collected_.ranges) {
        obs.push_back(Obs{r.ns, static_cast<std::uint16_t>(sensorSlot_[r.sensor]), r.range});
      }
    } else if (!collected_.clouds.empty()) {
      if (!options_.ring) {
        throw LogError(name_, 0, "sonar geometry",
                       "the sonar topic " + picks_.sonar.front() +
                           " holds echoes as points, not transducers: give the robot (--robot "
                           "p3dx for RosAria) so that each point is given its sonar");
      }
      d.ring = *options_.ring;
      report_.notes.push_back("sonar poses: the robot's (" + d.ring.robot +
                              "); point i of a cloud " + "of " + std::to_string(d.ring.size()) +
                              " is sonar i, other clouds' points go to the sonar they face");
      for (const CloudObs& c : collected_.clouds) cloudReadings(d.ring, c, obs);
    } else {
      throw LogError(name_, 0, "topics", "the sonar topics have no messages");
    }
    if (d.ring.size() > 65535) throw LogError(name_, 0, "sonar geometry", "more than 65535 sonars");
    std::stable_sort(obs.begin(), obs.end(),
                     [](const Obs& a, const Obs& b) { return a.ns < b.ns; });
    const std::int64_t t0 = std::min(obs.empty() ? collected_.odometry.front().ns : obs.front().ns,
                                     collected_.odometry.front().ns);
    auto seconds = [t0](std::int64_t ns) { return static_cast<double>(ns - t0) / 1e9; };
    std::size_t outside = 0;
    std::size_t i = 0;
    while (i < obs.size()) {
      std::size_t j = i;
      while (j < obs.size() && obs[j].ns == obs[i].ns) ++j;
      const auto odom = interpolate(collected_.odometry, obs[i].ns);
      if (!odom) {
        outside += j - i;
        i = j;
        continue;
      }
      Scan s;
      s.time = seconds(obs[i].ns);
      s.odometry = *odom;
      s.truth = interpolate(collected_.truth, obs[i].ns);
      s.readings.reserve(j - i);
      for (std::size_t k = i; k < j; ++k)
        s.readings.push_back(Reading{obs[k].sonar, obs[k].range, s.time});
      d.scans.push_back(std::move(s));
      i = j;
    }
    if (outside != 0) {
      report_.notes.push_back(std::to_string(outside) + " reading" + (outside == 1 ? "" : "s") +
                              " outside the odometry's time span (" +
                              std::to_string(seconds(collected_.odometry.front().ns)) + " s to " +
                              std::to_string(seconds(collected_.odometry.back().ns)) +
                              " s) left out: a pose there would be invented");
    }
    if (d.scans.empty()) {
      const auto span = [&](std::int64_t a, std::int64_t b) {
        return std::to_string(seconds(a)) + " s to " + std::to_string(seconds(b)) + " s";
      };
      throw LogError(
          name_, 0, "topics",
          "no reading falls within the odometry's time span (" +
              span(collected_.odometry.front().ns, collected_.odometry.back().ns) +
              (obs.empty() ? std::string("; the sonar topics gave no reading")
                           : "; the readings' span: " + span(obs.front().ns, obs.back().ns)) +
              ")");
    }
    if (!collected_.truth.empty()) {
      std::size_t without = 0;
      for (const Scan& s : d.scans) without += s.truth ? 0 : 1;
      if (without != 0) {
        report_.notes.push_back(std::to_string(without) +
                                " scans outside the true pose's time span " + "have no true pose");
      }
    }
    std::string sonar;
    for (const std::string& s : picks_.sonar) sonar += (sonar.empty() ? "" : ", ") + s;
    fs::path shown = fs::path(name_).lexically_normal();
    if (!shown.has_filename()) shown = shown.parent_path();
    if (shown.filename() == "metadata.yaml") shown = shown.parent_path();
    d.name = "ROS bag " + shown.filename().string() + ": sonar " + sonar + ", odometry " +
             picks_.odometry + (picks_.truth.empty() ? "" : ", true pose " + picks_.truth);
    report_.format = LogFormat::Bag;
    return d;
  }

  void cloudReadings(const SonarRing& ring, const CloudObs& c, auto& obs) {
    const bool byIndex = c.points.size() == ring.size();
    for (std::size_t i = 0; i < c.points.size(); ++i) {
      const Vector3& p = c.points[i];
      // float32 points widen through their decimal; a float64 one (PointCloud2) beyond float's
      // range is no sonar echo.
      constexpr double kFloatMax = std::numeric_limits<float>::max();
      if (!(std::abs(p.x) <= kFloatMax) || !(std::abs(p.y) <= kFloatMax)) continue;
      const Position point(widen(static_cast<float>(p.x)), widen(static_cast<float>(p.y)));
      std::size_t k = i;
      if (!byIndex) {
        double best = 10.0;
        for (std::size_t s = 0; s < ring.size(); ++s) {
          const Pose2D& m = ring.sonars[s].pose;
          const Position v = point - m.position;
          const double off = std::abs(wrapAngle(std::atan2(v.y(), v.x()) - m.heading));
          if (off < best) {
            best = off;
            k = s;
          }
        }
      }
      const double range = (point - ring.sonars[k].pose.position).norm();
      // RosAria puts a reading without an echo at the maximum range; float32 points land on
      // either side of it by a few micrometres.
      const bool echo = range < ring.maxRange - 1e-4;
      obs.push_back({c.ns, static_cast<std::uint16_t>(k), echo ? range : Reading::kNoEcho});
    }
  }

  std::string name_;
  const LogOptions& options_;
  LoadReport& report_;
  BagTopics picks_;
  std::map<std::string, Role> roles_;
  Collected collected_;
  std::vector<std::size_t> sensorSlot_;
  std::int64_t spanNs_ = -1;  // a preview's span of log time, or -1: the whole bag
  std::optional<std::int64_t> firstNs_;
  bool enough_ = false;
};

}  // namespace

double widen(float f) {
  if (!std::isfinite(f)) return static_cast<double>(f);
  char buf[32];
  const auto end = std::to_chars(buf, buf + sizeof buf, f).ptr;
  double d = 0.0;
  std::from_chars(buf, end, d);
  return d;
}

double widenAngle(float radians) {
  if (!std::isfinite(radians)) return static_cast<double>(radians);
  const double degrees = std::round(radToDeg(static_cast<double>(radians)));
  if (std::abs(degrees) <= 360.0 && static_cast<float>(degToRad(degrees)) == radians) {
    return degToRad(degrees);
  }
  return widen(radians);
}

double yawOf(double x, double y, double z, double w) {
  return std::atan2(2.0 * (w * z + x * y), w * w + x * x - y * y - z * z);
}

bool isBag(const std::string& path) {
  std::error_code ec;
  fs::path p(path);
  if (p.filename() == "metadata.yaml") return true;
  if (fs::is_directory(p, ec)) {
    for (const auto& entry : fs::directory_iterator(p, ec)) {
      const std::string ext = entry.path().extension().string();
      if (entry.path().filename() == "metadata.yaml" || ext == ".db3" || ext == ".mcap")
        return true;
    }
    return false;
  }
  try {
    auto source = fileSource(path);
    std::string head;
    source->read(0, static_cast<std::size_t>(std::min<std::uint64_t>(source->size(), 16)), head);
    return detectContainer(head) != Container::Unknown;
  } catch (const BagError&) {
    return false;
  }
}

Overview inspectBag(const std::string& path) {
  Overview o;
  o.files = storageFiles(path);
  for (const std::string& f : o.files) {
    OpenFile file = openFile(f);
    if (o.container == Container::Unknown) o.container = file.container;
    mergeTopics(o.topics, file.reader->topics());
  }
  o.picks = pickTopics(o.topics, o.notes);
  return o;
}

Dataset readBag(const std::string& path, const LogOptions& options, LoadReport& report) {
  std::vector<OpenFile> files;
  for (const std::string& f : storageFiles(path)) files.push_back(openFile(f));
  return Loader(path, options, report).run(files);
}

Dataset previewBag(const std::string& path, const LogOptions& options, double seconds,
                   LoadReport& report) {
  std::vector<OpenFile> files;
  for (const std::string& f : storageFiles(path)) files.push_back(openFile(f));
  Loader loader(path, options, report);
  loader.stopAfter(seconds);
  return loader.run(files);
}

Dataset readBagBytes(std::string_view bytes, const std::string& name, const LogOptions& options,
                     LoadReport& report) {
  std::vector<OpenFile> files;
  files.push_back(openBytes(bytes, name));
  return Loader(name, options, report).run(files);
}

}  // namespace sg::bag
