// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A sonar log read from a ROS bag (docs/formats.md, "ROS bags"): any container of bag.h, its
// topics chosen (by LogOptions or by inspectBag's picks), their messages decoded (ros_messages.h)
// and turned into a Dataset:
// - Sonar: sensor_msgs/Range (one topic, or one frame_id, per transducer; each transducer's pose is
//   the chain from the robot's frame to its frame in /tf_static, else /tf, else the ring of
//   LogOptions::ring in the frames' natural order), or a point cloud of echoes in the robot frame
//   (RosAria's sensor_msgs/PointCloud, or PointCloud2), which needs LogOptions::ring.
// - Odometry: nav_msgs/Odometry, else /tf's odom -> robot frame transforms; optionally a true
//   pose (geometry_msgs/PoseStamped or Odometry).
// - Readings that share a stamp form one scan, placed by the odometry (and truth) interpolated at
//   that stamp; readings outside the odometry's time span are left out and reported.
// - Times are seconds since the first sonar or odometry stamp.

#include <string>
#include <string_view>
#include <vector>

#include "sonargrid/data/dataset.h"
#include "sonargrid/io/bag/bag.h"
#include "sonargrid/io/log_options.h"

namespace sg::bag {

// A bag's topics and the ones a load would read when LogOptions names none, with why.
struct Overview {
  Container container = Container::Unknown;
  std::vector<std::string> files;  // the storage files read, in order (a rosbag2 folder may split)
  std::vector<Topic> topics;       // every topic of every file (merged by name)
  BagTopics picks;                 // what auto-detection chose
  std::vector<std::string> notes;  // one line per role: what was picked and why, or why none
};

// Whether `path` is a bag: a rosbag2 folder (holding metadata.yaml, .db3 or .mcap files), its
// metadata.yaml, or a file that starts like a ROS 1 bag, MCAP or SQLite.
bool isBag(const std::string& path);

// Lists the topics without decoding messages (ROS 1 and MCAP: their index or summary, or one
// pass over a bag that lacks them). Throws LogError naming the file.
Overview inspectBag(const std::string& path);

// Reads a bag as a Dataset. Throws LogError (file, "offset N (topic T)", what is wrong) for a
// malformed bag or message, LoadCancelled when options.cancel turns true. With options.lenient a
// bad record or message is skipped and counted in `report`.
Dataset readBag(const std::string& path, const LogOptions& options, LoadReport& report);
// The same for the messages of the first `seconds` of log time (from the first message of a chosen
// topic): a quick look at what a choice of topics gives, read from the first chunks only.
Dataset previewBag(const std::string& path, const LogOptions& options, double seconds,
                   LoadReport& report);
// The same for a ROS 1 bag, an MCAP file or a .db3 in memory.
Dataset readBagBytes(std::string_view bytes, const std::string& name, const LogOptions& options,
                     LoadReport& report);

// A float32 field widened to the double its shortest decimal denotes (what `rostopic echo`
// prints): 2.873f reads as 2.873, not 2.8729999065399170. Sonar ranges are decimal millimetres
// or centimetres; this gives them back as the .sglog, CARMEN and Player readers do.
double widen(float f);
// A float32 angle that is a whole number of degrees in float32 reads as exactly that many degrees
// (degToRad(25) for a 25-degree field of view); any other angle as widen() gives it.
double widenAngle(float radians);
// The heading of a quaternion: atan2(2 (w z + x y), w^2 + x^2 - y^2 - z^2). For a unit quaternion
// this equals the form with 1 - 2 (y^2 + z^2) below, but it stays exact near a quarter turn, where
// that one moves by more than an ulp of the angle per ulp of z; it also needs no normalisation.
double yawOf(double x, double y, double z, double w);

}  // namespace sg::bag
