// SPDX-License-Identifier: BSD-3-Clause
// The ROS messages of ros_messages.h, decoded field by field from the published .msg layouts.
//
// One Cursor walks a message. ROS 1 is little-endian and packed. ROS 2 CDR starts with the 4-byte
// encapsulation header (0x00, then 0x00 CDR_BE or 0x01 CDR_LE, then 2 option bytes); after it each
// primitive is aligned to its own size (1, 2, 4 or 8), counted from the byte after the header.
// Byte offsets in error messages count from the start of `data`, the CDR header included.
//
// Every read is checked against the end; an array's count is checked against the bytes left
// (count times the smallest size of an element) before anything is reserved, so a corrupt count
// cannot ask for gigabytes. Fields are named by their path from the message ("Odometry.pose.pose.
// orientation.w", "TFMessage.transforms[1].header.frame_id"), built only when an error is thrown.
#include "sonargrid/io/bag/ros_messages.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>

namespace sg::bag {
namespace {

constexpr std::size_t kNoIndex = std::numeric_limits<std::size_t>::max();

// A field's place in the message: its name, the array index when it is an element, and the
// field it belongs to. Lives on the stack of the decoding functions; rendered only for errors.
struct Field {
  const Field* parent = nullptr;
  std::string_view name;
  std::size_t index = kNoIndex;
};

std::string path(const Field& f) {
  std::string head = f.parent ? path(*f.parent) + "." : std::string();
  head += f.name;
  if (f.index != kNoIndex) head += "[" + std::to_string(f.index) + "]";
  return head;
}

[[noreturn]] void fail(const Field& f, const std::string& what) {
  throw MessageError(path(f) + ": " + what);
}

class Cursor {
 public:
  Cursor(std::string_view data, Encoding e, const Field& message) : data_(data) {
    if (e == Encoding::Ros1) return;
    cdr_ = true;
    if (data_.size() < 4) {
      fail(message, "the message ends at byte " + std::to_string(data_.size()) +
                        ", 4 bytes are needed at byte 0 for the CDR encapsulation header");
    }
    const auto b0 = static_cast<unsigned char>(data_[0]);
    const auto b1 = static_cast<unsigned char>(data_[1]);
    const std::string kind = "CDR encapsulation 0x" + hex(b0) + " 0x" + hex(b1);
    if (b0 == 0 && (b1 == 0 || b1 == 1)) {
      little_ = b1 == 1;
    } else if (b0 == 0 && (b1 == 2 || b1 == 3)) {
      fail(message, kind +
                        " is parameter-list CDR (PL_CDR), which is not read (only plain "
                        "CDR_BE 0x00 0x00 and CDR_LE 0x00 0x01)");
    } else if (b0 == 0 && b1 >= 6 && b1 <= 0x0b) {
      fail(message, kind +
                        " is XCDR2, which is not read (only XCDR1's CDR_BE 0x00 0x00 and "
                        "CDR_LE 0x00 0x01)");
    } else {
      fail(message, kind +
                        " is not a CDR encapsulation this reader knows (CDR_BE 0x00 0x00, "
                        "CDR_LE 0x00 0x01)");
    }
    pos_ = origin_ = 4;
  }

  bool cdr() const { return cdr_; }
  std::size_t pos() const { return pos_; }

  // One primitive, aligned (CDR) and byte-swapped as the data's byte order says.
  template <class T>
  T read(const Field& f) {
    static_assert(std::is_arithmetic_v<T>);
    const std::size_t at = aligned(sizeof(T));
    need(at, sizeof(T), f);
    T value = load<T>(data_.data() + at, little_);
    pos_ = at + sizeof(T);
    return value;
  }

  // ROS 1: uint32 length and the bytes. CDR: uint32 length including the terminating NUL, the
  // bytes and the NUL (dropped); a length of 0 is read as the empty string.
  std::string readString(const Field& f) {
    const std::uint32_t n = read<std::uint32_t>(f);
    need(pos_, n, f);
    std::string_view s = data_.substr(pos_, n);
    pos_ += n;
    if (cdr_ && !s.empty() && s.back() == '\0') s.remove_suffix(1);
    return std::string(s);
  }

  // An array's uint32 count, checked against the bytes left: each element takes at least
  // `minBytes` (> 0), not counting alignment.
  std::size_t readCount(const Field& f, std::size_t minBytes) {
    const std::uint32_t n = read<std::uint32_t>(f);
    const std::uint64_t needed = std::uint64_t{n} * minBytes;
    if (needed > data_.size() - pos_) {
      fail(f, std::to_string(n) + " elements need at least " + std::to_string(needed) +
                  " bytes at byte " + std::to_string(pos_) + ", the message ends at byte " +
                  std::to_string(data_.size()));
    }
    return n;
  }

  // `count` primitives of `size` bytes each, read past (the first aligned to `size` in CDR).
  void skip(std::size_t count, std::size_t size, const Field& f) {
    const std::size_t at = count ? aligned(size) : pos_;
    need(at, count * size, f);
    pos_ = at + count * size;
  }

  // `n` raw bytes (a uint8[] array's contents).
  std::string_view bytes(std::size_t n, const Field& f) {
    need(pos_, n, f);
    std::string_view s = data_.substr(pos_, n);
    pos_ += n;
    return s;
  }

  // The `n` bytes at the cursor (after aligning to `align`), without moving past them.
  const char* peek(std::size_t n, std::size_t align, const Field& f) {
    pos_ = aligned(align);
    need(pos_, n, f);
    return data_.data() + pos_;
  }
  void advance(std::size_t n) { pos_ += n; }

  template <class T>
  static T load(const char* p, bool little) {
    T value;
    if (little == (std::endian::native == std::endian::little)) {
      std::memcpy(&value, p, sizeof(T));
    } else {
      char b[sizeof(T)];
      for (std::size_t i = 0; i < sizeof(T); ++i) b[i] = p[sizeof(T) - 1 - i];
      std::memcpy(&value, b, sizeof(T));
    }
    return value;
  }
  bool little() const { return little_; }

 private:
  static std::string hex(unsigned v) {
    static const char digits[] = "0123456789abcdef";
    return {digits[(v >> 4) & 0xf], digits[v & 0xf]};
  }

  std::size_t aligned(std::size_t size) const {
    if (!cdr_ || size == 1) return pos_;
    const std::size_t rel = pos_ - origin_;
    return pos_ + (size - rel % size) % size;
  }

  void need(std::size_t at, std::size_t n, const Field& f) const {
    if (at > data_.size() || n > data_.size() - at) {
      fail(f, "the message ends at byte " + std::to_string(data_.size()) + ", " +
                  std::to_string(n) + (n == 1 ? " byte is" : " bytes are") + " needed at byte " +
                  std::to_string(at));
    }
  }

  std::string_view data_;
  std::size_t pos_ = 0;
  std::size_t origin_ = 0;
  bool cdr_ = false;
  bool little_ = true;
};

// ROS 1: uint32 secs, uint32 nsecs. ROS 2: int32 sec, uint32 nanosec. A nanosecond count of a
// second or more is carried into the seconds.
Stamp readStamp(Cursor& c, const Field& f) {
  Stamp s;
  if (c.cdr()) {
    s.sec = c.read<std::int32_t>({&f, "sec"});
    s.nsec = c.read<std::uint32_t>({&f, "nanosec"});
  } else {
    s.sec = c.read<std::uint32_t>({&f, "secs"});
    s.nsec = c.read<std::uint32_t>({&f, "nsecs"});
  }
  s.sec += s.nsec / 1'000'000'000u;
  s.nsec %= 1'000'000'000u;
  return s;
}

// std_msgs/Header: ROS 1 uint32 seq, time stamp, string frame_id; ROS 2 has no seq.
Header readHeader(Cursor& c, const Field& f) {
  Header h;
  if (!c.cdr()) c.read<std::uint32_t>({&f, "seq"});
  h.stamp = readStamp(c, {&f, "stamp"});
  h.frameId = c.readString({&f, "frame_id"});
  return h;
}

// geometry_msgs/Point, Vector3: float64 x, y, z.
Vector3 readVector3(Cursor& c, const Field& f) {
  Vector3 v;
  v.x = c.read<double>({&f, "x"});
  v.y = c.read<double>({&f, "y"});
  v.z = c.read<double>({&f, "z"});
  return v;
}

// geometry_msgs/Quaternion: float64 x, y, z, w.
Quaternion readQuaternion(Cursor& c, const Field& f) {
  Quaternion q;
  q.x = c.read<double>({&f, "x"});
  q.y = c.read<double>({&f, "y"});
  q.z = c.read<double>({&f, "z"});
  q.w = c.read<double>({&f, "w"});
  return q;
}

// geometry_msgs/Pose: Point position, Quaternion orientation.
PoseMsg readPose(Cursor& c, const Field& f) {
  PoseMsg p;
  p.position = readVector3(c, {&f, "position"});
  p.orientation = readQuaternion(c, {&f, "orientation"});
  return p;
}

// The smallest serialised sizes of array elements, for the count checks (no alignment, empty
// strings, empty arrays): every real element takes at least this many bytes.
constexpr std::size_t kPoint32Bytes = 12;                   // float32 x, y, z
constexpr std::size_t kChannelMinBytes = 4 + 4;             // string name, float32[] values
constexpr std::size_t kPointFieldMinBytes = 4 + 4 + 1 + 4;  // name, offset, datatype, count
// TransformStamped: header (ROS 1's seq, the stamp, frame_id's length), child_frame_id's length,
// translation and rotation (7 float64).
std::size_t transformMinBytes(bool cdr) {
  return (cdr ? 0 : 4) + 8 + 4 + 4 + 7 * 8;
}

// sensor_msgs/PointField datatypes.
std::size_t datatypeSize(std::uint8_t t) {
  switch (t) {
    case 1:  // INT8
    case 2:  // UINT8
      return 1;
    case 3:  // INT16
    case 4:  // UINT16
      return 2;
    case 5:  // INT32
    case 6:  // UINT32
    case 7:  // FLOAT32
      return 4;
    case 8:  // FLOAT64
      return 8;
    default:
      return 0;
  }
}

double loadScalar(const char* p, std::uint8_t datatype, bool little) {
  switch (datatype) {
    case 1:
      return static_cast<std::int8_t>(*p);
    case 2:
      return static_cast<std::uint8_t>(*p);
    case 3:
      return Cursor::load<std::int16_t>(p, little);
    case 4:
      return Cursor::load<std::uint16_t>(p, little);
    case 5:
      return Cursor::load<std::int32_t>(p, little);
    case 6:
      return Cursor::load<std::uint32_t>(p, little);
    case 7:
      return Cursor::load<float>(p, little);
    default:
      return Cursor::load<double>(p, little);
  }
}

struct CoordinateField {
  bool found = false;
  std::uint32_t offset = 0;
  std::uint8_t datatype = 0;
  std::size_t index = 0;  // in `fields`, for messages
};

}  // namespace

MessageType messageType(std::string_view typeName) {
  // "pkg/msg/Type" (ROS 2) is read as "pkg/Type".
  std::string name(typeName);
  if (const auto slash = name.find('/');
      slash != std::string::npos && name.compare(slash, 5, "/msg/") == 0) {
    name.erase(slash, 4);
  }
  if (name == "sensor_msgs/Range") return MessageType::Range;
  if (name == "sensor_msgs/PointCloud") return MessageType::PointCloud;
  if (name == "sensor_msgs/PointCloud2") return MessageType::PointCloud2;
  if (name == "nav_msgs/Odometry") return MessageType::Odometry;
  if (name == "geometry_msgs/PoseStamped") return MessageType::PoseStamped;
  // ROS 1's tf/tfMessage (before tf2) has the same layout as tf2_msgs/TFMessage.
  if (name == "tf2_msgs/TFMessage" || name == "tf/tfMessage") return MessageType::Tf;
  return MessageType::Unknown;
}

// sensor_msgs/Range: Header, uint8 radiation_type, float32 field_of_view, min_range, max_range,
// range. Newer ROS 2 releases add float32 variance at the end: it is past the fields read, so a
// message with or without it reads the same.
RangeMsg decodeRange(std::string_view data, Encoding e) {
  const Field m{nullptr, "Range"};
  Cursor c(data, e, m);
  RangeMsg r;
  r.header = readHeader(c, {&m, "header"});
  r.radiationType = c.read<std::uint8_t>({&m, "radiation_type"});
  r.fieldOfView = c.read<float>({&m, "field_of_view"});
  r.minRange = c.read<float>({&m, "min_range"});
  r.maxRange = c.read<float>({&m, "max_range"});
  r.range = c.read<float>({&m, "range"});
  return r;
}

// sensor_msgs/PointCloud: Header, geometry_msgs/Point32[] points, ChannelFloat32[] channels
// (string name, float32[] values; read past).
PointCloudMsg decodePointCloud(std::string_view data, Encoding e) {
  const Field m{nullptr, "PointCloud"};
  Cursor c(data, e, m);
  PointCloudMsg p;
  p.header = readHeader(c, {&m, "header"});
  const Field pointsField{&m, "points"};
  const std::size_t n = c.readCount(pointsField, kPoint32Bytes);
  const char* raw = c.peek(n * kPoint32Bytes, 4, pointsField);
  p.points.resize(n);
  const bool little = c.little();
  for (std::size_t i = 0; i < n; ++i) {
    const char* q = raw + i * kPoint32Bytes;
    p.points[i] = {Cursor::load<float>(q, little), Cursor::load<float>(q + 4, little),
                   Cursor::load<float>(q + 8, little)};
  }
  c.advance(n * kPoint32Bytes);
  const Field channelsField{&m, "channels"};
  const std::size_t channels = c.readCount(channelsField, kChannelMinBytes);
  for (std::size_t i = 0; i < channels; ++i) {
    const Field ch{&m, "channels", i};
    c.readString({&ch, "name"});
    const Field values{&ch, "values"};
    c.skip(c.readCount(values, 4), 4, values);
  }
  return p;
}

// sensor_msgs/PointCloud2: Header, uint32 height, width, PointField[] fields, bool is_bigendian,
// uint32 point_step, row_step, uint8[] data, bool is_dense. Point (row r, column k) starts at
// r * row_step + k * point_step in data (row_step is not used when there is one row).
PointCloud2Msg decodePointCloud2(std::string_view data, Encoding e) {
  const Field m{nullptr, "PointCloud2"};
  Cursor c(data, e, m);
  PointCloud2Msg p;
  p.header = readHeader(c, {&m, "header"});
  const std::uint32_t height = c.read<std::uint32_t>({&m, "height"});
  const std::uint32_t width = c.read<std::uint32_t>({&m, "width"});

  CoordinateField xyz[3];
  static constexpr std::string_view kNames[3] = {"x", "y", "z"};
  const Field fieldsField{&m, "fields"};
  const std::size_t nFields = c.readCount(fieldsField, kPointFieldMinBytes);
  for (std::size_t i = 0; i < nFields; ++i) {
    const Field pf{&m, "fields", i};
    const std::string name = c.readString({&pf, "name"});
    const std::uint32_t offset = c.read<std::uint32_t>({&pf, "offset"});
    const std::uint8_t datatype = c.read<std::uint8_t>({&pf, "datatype"});
    c.read<std::uint32_t>({&pf, "count"});
    for (int k = 0; k < 3; ++k) {
      if (name != kNames[k] || xyz[k].found) continue;  // the first field of the name counts
      if (datatypeSize(datatype) == 0) {
        fail({&pf, "datatype"},
             std::to_string(datatype) + " is not a PointField datatype (1 INT8 to 8 FLOAT64)");
      }
      xyz[k] = {true, offset, datatype, i};
    }
  }
  const bool bigEndian = c.read<std::uint8_t>({&m, "is_bigendian"}) != 0;
  const std::uint32_t pointStep = c.read<std::uint32_t>({&m, "point_step"});
  const std::uint32_t rowStep = c.read<std::uint32_t>({&m, "row_step"});
  const Field dataField{&m, "data"};
  const std::string_view bytes = c.bytes(c.readCount(dataField, 1), dataField);
  c.read<std::uint8_t>({&m, "is_dense"});

  for (int k = 0; k < 3; ++k) {
    if (!xyz[k].found) {
      fail(fieldsField, "no field is named \"" + std::string(kNames[k]) + "\" (" +
                            std::to_string(nFields) + " fields)");
    }
    const std::uint64_t end = std::uint64_t{xyz[k].offset} + datatypeSize(xyz[k].datatype);
    if (end > pointStep) {
      const Field pf{&m, "fields", xyz[k].index};
      fail({&pf, "offset"}, "field \"" + std::string(kNames[k]) + "\" at offset " +
                                std::to_string(xyz[k].offset) + " (" +
                                std::to_string(datatypeSize(xyz[k].datatype)) +
                                " bytes) does not fit in point_step " + std::to_string(pointStep));
    }
  }
  if (width == 0 || height == 0) return p;
  // Both fit in 64 bits: each factor is below 2^32 and the first is checked against the data.
  const std::uint64_t rowBytes = std::uint64_t{width} * pointStep;
  if (height > 1 && rowStep < rowBytes) {
    fail({&m, "row_step"}, "row_step " + std::to_string(rowStep) + " is less than width " +
                               std::to_string(width) + " times point_step " +
                               std::to_string(pointStep));
  }
  const std::uint64_t stride = height > 1 ? rowStep : rowBytes;
  if (rowBytes > bytes.size() || stride * (height - 1) > bytes.size() - rowBytes) {
    fail(dataField, std::to_string(height) + " rows of " + std::to_string(width) +
                        " points (point_step " + std::to_string(pointStep) + ", row_step " +
                        std::to_string(rowStep) + ") do not fit in its " +
                        std::to_string(bytes.size()) + " bytes");
  }

  const bool little = !bigEndian;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  p.points.reserve(std::size_t{width} * height);
  for (std::uint64_t r = 0; r < height; ++r) {
    const char* row = bytes.data() + r * stride;
    for (std::uint64_t k = 0; k < width; ++k) {
      const char* point = row + k * pointStep;
      Vector3 v{loadScalar(point + xyz[0].offset, xyz[0].datatype, little),
                loadScalar(point + xyz[1].offset, xyz[1].datatype, little),
                loadScalar(point + xyz[2].offset, xyz[2].datatype, little)};
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) v = {nan, nan, nan};
      p.points.push_back(v);
    }
  }
  return p;
}

// nav_msgs/Odometry: Header, string child_frame_id, PoseWithCovariance pose (Pose, float64[36]),
// TwistWithCovariance twist (Twist: Vector3 linear, angular; float64[36]); the twist is read past.
OdometryMsg decodeOdometry(std::string_view data, Encoding e) {
  const Field m{nullptr, "Odometry"};
  Cursor c(data, e, m);
  OdometryMsg o;
  o.header = readHeader(c, {&m, "header"});
  o.childFrameId = c.readString({&m, "child_frame_id"});
  const Field pose{&m, "pose"};
  o.pose = readPose(c, {&pose, "pose"});
  c.skip(36, 8, {&pose, "covariance"});
  const Field twist{&m, "twist"};
  const Field twistTwist{&twist, "twist"};
  c.skip(3, 8, {&twistTwist, "linear"});
  c.skip(3, 8, {&twistTwist, "angular"});
  c.skip(36, 8, {&twist, "covariance"});
  return o;
}

// geometry_msgs/PoseStamped: Header, Pose.
PoseStampedMsg decodePoseStamped(std::string_view data, Encoding e) {
  const Field m{nullptr, "PoseStamped"};
  Cursor c(data, e, m);
  PoseStampedMsg p;
  p.header = readHeader(c, {&m, "header"});
  p.pose = readPose(c, {&m, "pose"});
  return p;
}

// tf2_msgs/TFMessage: geometry_msgs/TransformStamped[] transforms (Header, string
// child_frame_id, Transform: Vector3 translation, Quaternion rotation).
TfMsg decodeTf(std::string_view data, Encoding e) {
  const Field m{nullptr, "TFMessage"};
  Cursor c(data, e, m);
  TfMsg tf;
  const std::size_t n = c.readCount({&m, "transforms"}, transformMinBytes(c.cdr()));
  tf.transforms.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Field t{&m, "transforms", i};
    TransformMsg x;
    x.header = readHeader(c, {&t, "header"});
    x.childFrameId = c.readString({&t, "child_frame_id"});
    const Field transform{&t, "transform"};
    x.translation = readVector3(c, {&transform, "translation"});
    x.rotation = readQuaternion(c, {&transform, "rotation"});
    tf.transforms.push_back(std::move(x));
  }
  return tf;
}

}  // namespace sg::bag
