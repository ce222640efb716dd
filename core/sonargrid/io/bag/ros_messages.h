// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The ROS messages a sonar log is made of, decoded from either serialisation (bag.h's Encoding):
// ROS 1 (little-endian, packed) and ROS 2 CDR (XCDR1: a 4-byte encapsulation header whose second
// byte says the endianness, 0x00/0x01 big/little; each primitive aligned to its size, counted from
// the byte after that header). Only the fields SonarGrid uses are kept; the others are read past.
// The layouts are the published message definitions (docs/formats.md, "ROS bags"); ROS 1 and
// ROS 2 differ in std_msgs/Header (ROS 1 has a uint32 `seq` first; ROS 2 has none) and in the
// time type (ROS 1: uint32 secs, uint32 nsecs; ROS 2: int32 sec, uint32 nanosec).

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "sonargrid/io/bag/bag.h"

namespace sg::bag {

// Thrown when a message is shorter than its type, or a length or enum field is impossible. Its
// message names the field ("Range.range: ...") and the byte offset inside the message; the caller
// adds the file, the record offset and the topic (BagError).
class MessageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Stamp {
  std::int64_t sec = 0;    // ROS 1's uint32 secs or ROS 2's int32 sec
  std::uint32_t nsec = 0;  // < 1e9
  std::int64_t ns() const { return sec * 1'000'000'000 + nsec; }
};

struct Header {
  Stamp stamp;
  std::string frameId;
};

struct Vector3 {
  double x = 0, y = 0, z = 0;
};
struct Quaternion {
  double x = 0, y = 0, z = 0, w = 1;
};
struct PoseMsg {
  Vector3 position;
  Quaternion orientation;
};

// sensor_msgs/Range: Header, uint8 radiation_type, float32 field_of_view, min_range, max_range,
// range (the same fields in ROS 1 and ROS 2; only the header differs).
struct RangeMsg {
  Header header;
  std::uint8_t radiationType = 0;  // 0 ultrasound, 1 infrared
  float fieldOfView = 0, minRange = 0, maxRange = 0, range = 0;
};

// sensor_msgs/PointCloud: Header, geometry_msgs/Point32[] points, ChannelFloat32[] channels
// (each: string name, float32[] values). Points are float32 x, y, z.
struct PointCloudMsg {
  Header header;
  std::vector<Vector3> points;  // the float32 coordinates, widened to double as they are
};

// sensor_msgs/PointCloud2: Header, uint32 height, width, PointField[] fields (string name,
// uint32 offset, uint8 datatype, uint32 count), bool is_bigendian, uint32 point_step, row_step,
// uint8[] data, bool is_dense. Decoded to the x, y, z of each point (any of the eight datatypes,
// either byte order, as the fields say); points whose x, y or z is not finite are kept as NaN.
struct PointCloud2Msg {
  Header header;
  std::vector<Vector3> points;
};

// nav_msgs/Odometry: Header, string child_frame_id, geometry_msgs/PoseWithCovariance pose
// (Pose, float64[36]), TwistWithCovariance twist (Twist, float64[36]).
struct OdometryMsg {
  Header header;
  std::string childFrameId;
  PoseMsg pose;
};

// geometry_msgs/PoseStamped: Header, Pose.
struct PoseStampedMsg {
  Header header;
  PoseMsg pose;
};

// geometry_msgs/TransformStamped: Header, string child_frame_id, Transform (Vector3 translation,
// Quaternion rotation). tf2_msgs/TFMessage is TransformStamped[] transforms.
struct TransformMsg {
  Header header;
  std::string childFrameId;
  Vector3 translation;
  Quaternion rotation;
};
struct TfMsg {
  std::vector<TransformMsg> transforms;
};

// The types this file decodes, by their name in either ROS ("sensor_msgs/Range" or
// "sensor_msgs/msg/Range"), or Unknown.
enum class MessageType { Unknown, Range, PointCloud, PointCloud2, Odometry, PoseStamped, Tf };
MessageType messageType(std::string_view typeName);

// Each throws MessageError when `data` is shorter than the type or a field is impossible (a
// string or array length past the end; a CDR encapsulation other than CDR_BE/CDR_LE, 0x0000 or
// 0x0001). Bytes after the message's end are allowed (CDR pads to 4).
RangeMsg decodeRange(std::string_view data, Encoding e);
PointCloudMsg decodePointCloud(std::string_view data, Encoding e);
PointCloud2Msg decodePointCloud2(std::string_view data, Encoding e);
OdometryMsg decodeOdometry(std::string_view data, Encoding e);
PoseStampedMsg decodePoseStamped(std::string_view data, Encoding e);
TfMsg decodeTf(std::string_view data, Encoding e);

}  // namespace sg::bag
