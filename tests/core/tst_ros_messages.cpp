// SPDX-License-Identifier: BSD-3-Clause
// The ROS messages of sonargrid/io/bag/ros_messages.h, read from bytes written by real writers
// (tests/data/bags/messages/): ROS 1 by genpy's message classes (make_ros1_messages.py), ROS 2
// CDR little-endian by @foxglove/rosmsg2-serialization's MessageWriter and big-endian by
// @foxglove/cdr's CdrWriter (make_cdr_messages.mjs). Every expected value is the one those
// scripts write. Then cut, patched and hand-made messages: each gives a MessageError that names
// the field and the byte, never a crash or a huge allocation.

#include <QtTest>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "sonargrid/io/bag/ros_messages.h"

using sg::bag::Encoding;
using sg::bag::MessageError;

namespace {

std::string fixture(const QString& name) {
  const std::string path =
      std::string(SONARGRID_TEST_DATA) + "/bags/messages/" + name.toStdString();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

Encoding encodingOf(const QString& name) {
  return name.contains(".ros1.") ? Encoding::Ros1 : Encoding::Cdr;
}

// The same double or float to the last bit (QCOMPARE's are fuzzy), or both NaN.
bool same(double a, double b) {
  return a == b || (std::isnan(a) && std::isnan(b));
}
#define SAME(actual, expected)                                                        \
  QVERIFY2(same(actual, expected), qPrintable(QStringLiteral("%1 is %2, expected %3") \
                                                  .arg(#actual)                       \
                                                  .arg(double(actual), 0, 'g', 17)    \
                                                  .arg(double(expected), 0, 'g', 17)))

// `data` with the uint32 at `at` replaced by `value`, in the byte order given.
std::string patched(std::string data, std::size_t at, std::uint32_t value, bool bigEndian = false) {
  for (int i = 0; i < 4; ++i) {
    const int shift = bigEndian ? 8 * (3 - i) : 8 * i;
    data[at + i] = static_cast<char>((value >> shift) & 0xff);
  }
  return data;
}

// The text of the MessageError that decoding `data` as `type` throws, or what happened instead.
template <class Decode>
std::string errorOf(Decode decode, const std::string& data, Encoding e) {
  try {
    decode(data, e);
  } catch (const MessageError& error) {
    return error.what();
  } catch (const std::exception& error) {
    return std::string("unexpected exception: ") + error.what();
  }
  return "no error";
}

// Decodes `data` as the type a fixture's name starts with.
void decodeAs(const QString& name, std::string_view data, Encoding e) {
  if (name.startsWith("range"))
    sg::bag::decodeRange(data, e);
  else if (name.startsWith("pointcloud2"))
    sg::bag::decodePointCloud2(data, e);
  else if (name.startsWith("pointcloud"))
    sg::bag::decodePointCloud(data, e);
  else if (name.startsWith("odometry"))
    sg::bag::decodeOdometry(data, e);
  else if (name.startsWith("posestamped"))
    sg::bag::decodePoseStamped(data, e);
  else if (name.startsWith("tf"))
    sg::bag::decodeTf(data, e);
  else
    throw std::logic_error("no type for " + name.toStdString());
}

// Hand-made messages: ROS 1 packed, or CDR little-endian with its header and alignment.
class Bytes {
 public:
  explicit Bytes(bool cdr) : cdr_(cdr) {
    if (cdr) s_ = std::string("\x00\x01\x00\x00", 4);
  }
  template <class T>
  Bytes& put(T v) {
    if (cdr_) {
      while ((s_.size() - 4) % sizeof(T) != 0) s_.push_back('\0');
    }
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));  // the test machines are little-endian, like the data
    s_.append(b, sizeof(T));
    return *this;
  }
  Bytes& str(const std::string& v, bool nul = true) {
    put<std::uint32_t>(static_cast<std::uint32_t>(v.size() + (cdr_ && nul ? 1 : 0)));
    s_ += v;
    if (cdr_ && nul) s_.push_back('\0');
    return *this;
  }
  Bytes& raw(const std::string& v) {
    s_ += v;
    return *this;
  }
  const std::string& bytes() const { return s_; }

 private:
  bool cdr_;
  std::string s_;
};

}  // namespace

class TstRosMessages : public QObject {
  Q_OBJECT
 private slots:
  void typeNamesOfBothRosVersionsAreKnown();
  void rangeReadsTheSameInEveryEncoding_data();
  void rangeReadsTheSameInEveryEncoding();
  void odometryReadsTheSameInEveryEncoding_data();
  void odometryReadsTheSameInEveryEncoding();
  void poseStampedReadsTheSameInEveryEncoding_data();
  void poseStampedReadsTheSameInEveryEncoding();
  void tfReadsEveryTransform_data();
  void tfReadsEveryTransform();
  void pointCloudReadsItsPointsAndSkipsTheChannels_data();
  void pointCloudReadsItsPointsAndSkipsTheChannels();
  void pointCloud2OfFloat32KeepsAnInvalidPointAsNan_data();
  void pointCloud2OfFloat32KeepsAnInvalidPointAsNan();
  void pointCloud2OfFloat64FollowsRowStepPadding();
  void pointCloud2ReadsBigEndianIntegers();
  void pointCloud2ReadsTheOtherDatatypes();
  void errorsNameTheFieldAndTheByte_data();
  void errorsNameTheFieldAndTheByte();
  void everyCutMessageIsAMessageError_data();
  void everyCutMessageIsAMessageError();
  void aByteTakenOutAnywhereNeverCrashes_data();
  void aByteTakenOutAnywhereNeverCrashes();
  void hugeCountsAreRejectedBeforeAllocating_data();
  void hugeCountsAreRejectedBeforeAllocating();
  void pointCloud2FieldsThatCannotBeReadAreErrors_data();
  void pointCloud2FieldsThatCannotBeReadAreErrors();
  void onlyPlainXcdr1EncapsulationsAreRead_data();
  void onlyPlainXcdr1EncapsulationsAreRead();
  void cdrStringsWithoutTheirNulAreRead();
  void nanosecondsOfASecondOrMoreCarryIntoTheSeconds();
};

void TstRosMessages::typeNamesOfBothRosVersionsAreKnown() {
  using sg::bag::MessageType;
  using sg::bag::messageType;
  QCOMPARE(messageType("sensor_msgs/Range"), MessageType::Range);
  QCOMPARE(messageType("sensor_msgs/msg/Range"), MessageType::Range);
  QCOMPARE(messageType("sensor_msgs/PointCloud"), MessageType::PointCloud);
  QCOMPARE(messageType("sensor_msgs/msg/PointCloud2"), MessageType::PointCloud2);
  QCOMPARE(messageType("nav_msgs/Odometry"), MessageType::Odometry);
  QCOMPARE(messageType("nav_msgs/msg/Odometry"), MessageType::Odometry);
  QCOMPARE(messageType("geometry_msgs/PoseStamped"), MessageType::PoseStamped);
  QCOMPARE(messageType("geometry_msgs/msg/PoseStamped"), MessageType::PoseStamped);
  QCOMPARE(messageType("tf2_msgs/TFMessage"), MessageType::Tf);
  QCOMPARE(messageType("tf2_msgs/msg/TFMessage"), MessageType::Tf);
  QCOMPARE(messageType("tf/tfMessage"), MessageType::Tf);  // ROS 1's tf, the same layout
  QCOMPARE(messageType("sensor_msgs/LaserScan"), MessageType::Unknown);
  QCOMPARE(messageType("sensor_msgs/srv/Range"), MessageType::Unknown);
  QCOMPARE(messageType("Range"), MessageType::Unknown);
  QCOMPARE(messageType(""), MessageType::Unknown);
}

void TstRosMessages::rangeReadsTheSameInEveryEncoding_data() {
  QTest::addColumn<QString>("file");
  QTest::newRow("ROS 1, genpy") << "range.ros1.bin";
  QTest::newRow("CDR LE, MessageWriter") << "range.cdr-le.bin";
  QTest::newRow("CDR BE, CdrWriter") << "range.cdr-be.bin";
  // The newer ROS 2 definition with float32 variance (0.0009) at the end: read past.
  QTest::newRow("CDR LE with variance") << "range-variance.cdr-le.bin";
}

void TstRosMessages::rangeReadsTheSameInEveryEncoding() {
  QFETCH(QString, file);
  const sg::bag::RangeMsg r = sg::bag::decodeRange(fixture(file), encodingOf(file));
  // Both scripts: stamp 12 s 500000000 ns, frame "sonar_3", INFRARED (1), field_of_view 0.4363,
  // min_range 0.1, max_range 5.0, range 2.873 (float32).
  QCOMPARE(r.header.stamp.sec, std::int64_t{12});
  QCOMPARE(r.header.stamp.nsec, std::uint32_t{500000000});
  QCOMPARE(r.header.stamp.ns(), std::int64_t{12'500'000'000});
  QCOMPARE(r.header.frameId, std::string("sonar_3"));
  QCOMPARE(r.radiationType, std::uint8_t{1});
  SAME(r.fieldOfView, 0.4363f);
  SAME(r.minRange, 0.1f);
  SAME(r.maxRange, 5.0f);
  SAME(r.range, 2.873f);
}

void TstRosMessages::odometryReadsTheSameInEveryEncoding_data() {
  QTest::addColumn<QString>("file");
  QTest::newRow("ROS 1, genpy") << "odometry.ros1.bin";
  QTest::newRow("CDR LE, MessageWriter") << "odometry.cdr-le.bin";
  QTest::newRow("CDR BE, CdrWriter") << "odometry.cdr-be.bin";
}

void TstRosMessages::odometryReadsTheSameInEveryEncoding() {
  QFETCH(QString, file);
  const std::string data = fixture(file);
  const sg::bag::OdometryMsg o = sg::bag::decodeOdometry(data, encodingOf(file));
  // Both scripts: stamp 1700000000 s 123456789 ns, "odom" -> "base_link", position
  // (1.25, -3.5, 0.0625), orientation yaw 0.3 (z = sin 0.15, w = cos 0.15, Python's repr).
  QCOMPARE(o.header.stamp.sec, std::int64_t{1700000000});
  QCOMPARE(o.header.stamp.nsec, std::uint32_t{123456789});
  QCOMPARE(o.header.frameId, std::string("odom"));
  QCOMPARE(o.childFrameId, std::string("base_link"));
  SAME(o.pose.position.x, 1.25);
  SAME(o.pose.position.y, -3.5);
  SAME(o.pose.position.z, 0.0625);
  SAME(o.pose.orientation.x, 0.0);
  SAME(o.pose.orientation.y, 0.0);
  SAME(o.pose.orientation.z, 0.14943813247359922);
  SAME(o.pose.orientation.w, 0.9887710779360422);
  // The covariances and the twist are read past: all 713 (ROS 1) or 724 (CDR) bytes are needed.
  QCOMPARE(data.size(), std::size_t{encodingOf(file) == Encoding::Ros1 ? 713u : 724u});
}

void TstRosMessages::poseStampedReadsTheSameInEveryEncoding_data() {
  QTest::addColumn<QString>("file");
  QTest::newRow("ROS 1, genpy") << "posestamped.ros1.bin";
  QTest::newRow("CDR LE, MessageWriter") << "posestamped.cdr-le.bin";
}

void TstRosMessages::poseStampedReadsTheSameInEveryEncoding() {
  QFETCH(QString, file);
  const sg::bag::PoseStampedMsg p = sg::bag::decodePoseStamped(fixture(file), encodingOf(file));
  // Both scripts: stamp 42 s 1 ns, frame "map", position (10.5, 20.25, -0.75), yaw -1.2
  // (z = sin -0.6, w = cos -0.6).
  QCOMPARE(p.header.stamp.ns(), std::int64_t{42'000'000'001});
  QCOMPARE(p.header.frameId, std::string("map"));
  SAME(p.pose.position.x, 10.5);
  SAME(p.pose.position.y, 20.25);
  SAME(p.pose.position.z, -0.75);
  SAME(p.pose.orientation.z, -0.5646424733950354);
  SAME(p.pose.orientation.w, 0.8253356149096783);
}

void TstRosMessages::tfReadsEveryTransform_data() {
  QTest::addColumn<QString>("file");
  QTest::newRow("ROS 1, genpy") << "tf.ros1.bin";
  QTest::newRow("CDR LE, MessageWriter") << "tf.cdr-le.bin";
}

void TstRosMessages::tfReadsEveryTransform() {
  QFETCH(QString, file);
  const sg::bag::TfMsg tf = sg::bag::decodeTf(fixture(file), encodingOf(file));
  QCOMPARE(tf.transforms.size(), std::size_t{2});
  // Both scripts: odom -> base_link at 100.25 s, (0.1, 0.2, 0.3), yaw 0.3.
  const sg::bag::TransformMsg& a = tf.transforms[0];
  QCOMPARE(a.header.stamp.sec, std::int64_t{100});
  QCOMPARE(a.header.stamp.nsec, std::uint32_t{250000000});
  QCOMPARE(a.header.frameId, std::string("odom"));
  QCOMPARE(a.childFrameId, std::string("base_link"));
  SAME(a.translation.x, 0.1);
  SAME(a.translation.y, 0.2);
  SAME(a.translation.z, 0.3);
  SAME(a.rotation.z, 0.14943813247359922);
  SAME(a.rotation.w, 0.9887710779360422);
  // base_link -> sonar_3 one nanosecond later, (0.115, -0.05, 0.2), yaw pi/2 (sqrt 0.5).
  const sg::bag::TransformMsg& b = tf.transforms[1];
  QCOMPARE(b.header.stamp.nsec, std::uint32_t{250000001});
  QCOMPARE(b.header.frameId, std::string("base_link"));
  QCOMPARE(b.childFrameId, std::string("sonar_3"));
  SAME(b.translation.x, 0.115);
  SAME(b.translation.y, -0.05);
  SAME(b.translation.z, 0.2);
  SAME(b.rotation.x, 0.0);
  SAME(b.rotation.y, 0.0);
  SAME(b.rotation.z, 0.7071067811865476);
  SAME(b.rotation.w, 0.7071067811865476);
}

void TstRosMessages::pointCloudReadsItsPointsAndSkipsTheChannels_data() {
  QTest::addColumn<QString>("file");
  QTest::newRow("ROS 1, genpy") << "pointcloud.ros1.bin";
  QTest::newRow("CDR LE, MessageWriter") << "pointcloud.cdr-le.bin";
}

void TstRosMessages::pointCloudReadsItsPointsAndSkipsTheChannels() {
  QFETCH(QString, file);
  const sg::bag::PointCloudMsg p = sg::bag::decodePointCloud(fixture(file), encodingOf(file));
  // Both scripts: frame "sonar_ring" at 12.5 s; points (1.5, -0.25, 0.125), (2.75, 0.5, 0),
  // (-1, 3.25, 0.5); channels "intensity" and "sonar" (three values each) after them.
  QCOMPARE(p.header.frameId, std::string("sonar_ring"));
  QCOMPARE(p.header.stamp.ns(), std::int64_t{12'500'000'000});
  QCOMPARE(p.points.size(), std::size_t{3});
  const double expected[3][3] = {{1.5, -0.25, 0.125}, {2.75, 0.5, 0}, {-1, 3.25, 0.5}};
  for (std::size_t i = 0; i < 3; ++i) {
    SAME(p.points[i].x, expected[i][0]);
    SAME(p.points[i].y, expected[i][1]);
    SAME(p.points[i].z, expected[i][2]);
  }
}

void TstRosMessages::pointCloud2OfFloat32KeepsAnInvalidPointAsNan_data() {
  QTest::addColumn<QString>("file");
  QTest::newRow("ROS 1, genpy") << "pointcloud2.ros1.bin";
  QTest::newRow("CDR LE, MessageWriter") << "pointcloud2.cdr-le.bin";
}

void TstRosMessages::pointCloud2OfFloat32KeepsAnInvalidPointAsNan() {
  QFETCH(QString, file);
  const sg::bag::PointCloud2Msg p = sg::bag::decodePointCloud2(fixture(file), encodingOf(file));
  // Both scripts: FLOAT32 x, y, z, intensity at 0, 4, 8, 12; point_step 16; one row of four.
  QCOMPARE(p.header.frameId, std::string("sonar_ring"));
  QCOMPARE(p.points.size(), std::size_t{4});
  const double expected[3][3] = {{1.5, -2.25, 0.125}, {3.0, 0.5, -0.75}, {0.0625, 100.5, 7.0}};
  for (std::size_t i = 0; i < 3; ++i) {
    SAME(p.points[i].x, expected[i][0]);
    SAME(p.points[i].y, expected[i][1]);
    SAME(p.points[i].z, expected[i][2]);
  }
  // The fourth point's x is NaN (y 1, z 2): the point is kept, all NaN.
  QVERIFY(std::isnan(p.points[3].x));
  QVERIFY(std::isnan(p.points[3].y));
  QVERIFY(std::isnan(p.points[3].z));
}

void TstRosMessages::pointCloud2OfFloat64FollowsRowStepPadding() {
  const sg::bag::PointCloud2Msg p =
      sg::bag::decodePointCloud2(fixture("pointcloud2-f64.cdr-le.bin"), Encoding::Cdr);
  // make_cdr_messages.mjs: a FLOAT32 intensity, then FLOAT64 x, y, z at 8, 16, 24; point_step 32,
  // two rows of two with row_step 72 (8 bytes of padding after each row).
  QCOMPARE(p.points.size(), std::size_t{4});
  const double expected[4][3] = {
      {1.1, 2.2, 3.3}, {-4.4, 5.5, -6.6}, {7.7, -8.8, 9.9}, {0.001, 0.002, 0.003}};
  for (std::size_t i = 0; i < 4; ++i) {
    SAME(p.points[i].x, expected[i][0]);
    SAME(p.points[i].y, expected[i][1]);
    SAME(p.points[i].z, expected[i][2]);
  }
}

void TstRosMessages::pointCloud2ReadsBigEndianIntegers() {
  const sg::bag::PointCloud2Msg p =
      sg::bag::decodePointCloud2(fixture("pointcloud2-int-be.cdr-le.bin"), Encoding::Cdr);
  // make_cdr_messages.mjs: is_bigendian true (in a little-endian CDR message); INT16 x at 0,
  // UINT32 y at 2, INT8 z at 6; points (-1234, 3000000000, -7) and (32767, 1, 127).
  QCOMPARE(p.points.size(), std::size_t{2});
  SAME(p.points[0].x, -1234.0);
  SAME(p.points[0].y, 3000000000.0);
  SAME(p.points[0].z, -7.0);
  SAME(p.points[1].x, 32767.0);
  SAME(p.points[1].y, 1.0);
  SAME(p.points[1].z, 127.0);
}

void TstRosMessages::pointCloud2ReadsTheOtherDatatypes() {
  // Hand-made (ROS 1): UINT8 x at 0, UINT16 y at 1, INT32 z at 3; point_step 7; one point
  // (200, 65000, -2000000000), little-endian.
  Bytes b(false);
  b.put<std::uint32_t>(0).put<std::uint32_t>(5).put<std::uint32_t>(0).str("cloud");
  b.put<std::uint32_t>(1).put<std::uint32_t>(1);  // height, width
  b.put<std::uint32_t>(3);
  b.str("x").put<std::uint32_t>(0).put<std::uint8_t>(2).put<std::uint32_t>(1);
  b.str("y").put<std::uint32_t>(1).put<std::uint8_t>(4).put<std::uint32_t>(1);
  b.str("z").put<std::uint32_t>(3).put<std::uint8_t>(5).put<std::uint32_t>(1);
  b.put<std::uint8_t>(0).put<std::uint32_t>(7).put<std::uint32_t>(7);
  b.put<std::uint32_t>(7).put<std::uint8_t>(200).put<std::uint16_t>(65000);
  b.put<std::int32_t>(-2000000000).put<std::uint8_t>(1);
  const sg::bag::PointCloud2Msg p = sg::bag::decodePointCloud2(b.bytes(), Encoding::Ros1);
  QCOMPARE(p.header.stamp.sec, std::int64_t{5});
  QCOMPARE(p.points.size(), std::size_t{1});
  SAME(p.points[0].x, 200.0);
  SAME(p.points[0].y, 65000.0);
  SAME(p.points[0].z, -2000000000.0);
}

void TstRosMessages::errorsNameTheFieldAndTheByte_data() {
  QTest::addColumn<QString>("file");
  QTest::addColumn<int>("cut");
  QTest::addColumn<QString>("message");
  // range.ros1.bin: seq 0, stamp 4, frame_id 12 (length) and 16 ("sonar_3"), radiation_type 23,
  // field_of_view 24, min_range 28, max_range 32, range 36 to 40.
  QTest::newRow("ROS 1 Range, range") << "range.ros1.bin" << 37
                                      << "Range.range: the message ends at byte 37, 4 bytes are "
                                         "needed at byte 36";
  QTest::newRow("ROS 1 Range, frame_id")
      << "range.ros1.bin" << 20
      << "Range.header.frame_id: the message ends at byte 20, 7 bytes are needed at byte 16";
  // range.cdr-le.bin: the header 0, sec 4, nanosec 8, frame_id 12 and 16 (8 bytes with the NUL),
  // radiation_type 24, 3 bytes of padding, field_of_view 28.
  QTest::newRow("CDR Range, field_of_view after padding")
      << "range.cdr-le.bin" << 26
      << "Range.field_of_view: the message ends at byte 26, 4 bytes are needed at byte 28";
  QTest::newRow("CDR Range, the encapsulation header")
      << "range.cdr-le.bin" << 3
      << "Range: the message ends at byte 3, 4 bytes are needed at byte 0 for the CDR "
         "encapsulation header";
  QTest::newRow("CDR Range, radiation_type")
      << "range.cdr-le.bin" << 24
      << "Range.radiation_type: the message ends at byte 24, 1 byte is needed at byte 24";
  // odometry.ros1.bin: frame_id "odom" 12..19, child_frame_id "base_link" 20..32, position 33,
  // orientation 57 (x), 65, 73, 81 (w) to 89.
  QTest::newRow("ROS 1 Odometry, orientation.w")
      << "odometry.ros1.bin" << 85
      << "Odometry.pose.pose.orientation.w: the message ends at byte 85, 8 bytes are needed at "
         "byte 81";
  // odometry.cdr-le.bin: child_frame_id 24..37, position aligned to 44 (8 after the header's 4),
  // orientation w at 92, the pose covariance 100..387, the twist 388..435, its covariance
  // 436..723.
  QTest::newRow("CDR Odometry, orientation.w")
      << "odometry.cdr-le.bin" << 99
      << "Odometry.pose.pose.orientation.w: the message ends at byte 99, 8 bytes are needed at "
         "byte 92";
  QTest::newRow("CDR Odometry, twist covariance")
      << "odometry.cdr-le.bin" << 723
      << "Odometry.twist.covariance: the message ends at byte 723, 288 bytes are needed at byte "
         "436";
  QTest::newRow("CDR Odometry, twist linear")
      << "odometry.cdr-le.bin" << 400
      << "Odometry.twist.twist.linear: the message ends at byte 400, 24 bytes are needed at byte "
         "388";
  // tf.ros1.bin: the count 0, transform 0 at 4..92 (89 bytes), transform 1's header 93..117
  // ("base_link"), child_frame_id 118..128 ("sonar_3"), translation 129..152, rotation 153..184.
  // (A cut before byte 156 is caught by the count: two transforms need at least 152 bytes.)
  QTest::newRow("ROS 1 TF, second rotation")
      << "tf.ros1.bin" << 160
      << "TFMessage.transforms[1].transform.rotation.x: the message ends at byte 160, 8 bytes are "
         "needed at byte 153";
  QTest::newRow("ROS 1 TF, the count")
      << "tf.ros1.bin" << 112
      << "TFMessage.transforms: 2 elements need at least 152 bytes at byte 4, the message ends at "
         "byte 112";
}

void TstRosMessages::errorsNameTheFieldAndTheByte() {
  QFETCH(QString, file);
  QFETCH(int, cut);
  QFETCH(QString, message);
  const std::string data = fixture(file).substr(0, static_cast<std::size_t>(cut));
  std::string what = "no error";
  try {
    decodeAs(file, data, encodingOf(file));
  } catch (const MessageError& e) {
    what = e.what();
  }
  QCOMPARE(QString::fromStdString(what), message);
}

void TstRosMessages::everyCutMessageIsAMessageError_data() {
  QTest::addColumn<QString>("file");
  QTest::addColumn<int>("end");  // where the fields read end: every shorter prefix is an error
  for (const char* f :
       {"range.ros1.bin", "range.cdr-le.bin", "range.cdr-be.bin", "odometry.ros1.bin",
        "odometry.cdr-le.bin", "odometry.cdr-be.bin", "posestamped.ros1.bin",
        "posestamped.cdr-le.bin", "tf.ros1.bin", "tf.cdr-le.bin", "pointcloud.ros1.bin",
        "pointcloud.cdr-le.bin", "pointcloud2.ros1.bin", "pointcloud2.cdr-le.bin",
        "pointcloud2-f64.cdr-le.bin", "pointcloud2-int-be.cdr-le.bin"}) {
    QTest::newRow(f) << f << static_cast<int>(fixture(f).size());
  }
  // Range's variance (the last 4 bytes) is not read: cutting into it is no error.
  QTest::newRow("range-variance.cdr-le.bin") << "range-variance.cdr-le.bin" << 44;
}

void TstRosMessages::everyCutMessageIsAMessageError() {
  QFETCH(QString, file);
  QFETCH(int, end);
  const std::string data = fixture(file);
  for (std::size_t n = 0; n < static_cast<std::size_t>(end); ++n) {
    // A copy of exactly n bytes, so that ASan sees any read past it.
    const std::string cut = data.substr(0, n);
    bool threw = false;
    try {
      decodeAs(file, cut, encodingOf(file));
    } catch (const MessageError&) {
      threw = true;
    }
    QVERIFY2(threw, qPrintable(QStringLiteral("no MessageError for the first %1 bytes").arg(n)));
  }
  for (std::size_t n = static_cast<std::size_t>(end); n <= data.size(); ++n) {
    decodeAs(file, data.substr(0, n), encodingOf(file));
  }
}

void TstRosMessages::aByteTakenOutAnywhereNeverCrashes_data() {
  QTest::addColumn<QString>("file");
  for (const char* f :
       {"range.ros1.bin", "range.cdr-be.bin", "odometry.cdr-le.bin", "tf.ros1.bin", "tf.cdr-le.bin",
        "pointcloud.cdr-le.bin", "pointcloud2.ros1.bin", "pointcloud2-f64.cdr-le.bin"}) {
    QTest::newRow(f) << f;
  }
}

void TstRosMessages::aByteTakenOutAnywhereNeverCrashes() {
  // Shifted fields make nonsense lengths and counts: a result or a MessageError, nothing else.
  QFETCH(QString, file);
  const std::string data = fixture(file);
  for (std::size_t i = 0; i < data.size(); ++i) {
    const std::string shifted = data.substr(0, i) + data.substr(i + 1);
    try {
      decodeAs(file, shifted, encodingOf(file));
    } catch (const MessageError&) {
    }
  }
}

void TstRosMessages::hugeCountsAreRejectedBeforeAllocating_data() {
  QTest::addColumn<QString>("file");
  QTest::addColumn<int>("at");
  QTest::addColumn<QString>("message");
  // pointcloud.ros1.bin: header 0..25 (frame_id "sonar_ring"), the points' count at 26. 2^31 - 1
  // Point32 need 12 bytes each.
  QTest::newRow("ROS 1 PointCloud points")
      << "pointcloud.ros1.bin" << 26
      << "PointCloud.points: 2147483647 elements need at least 25769803764 bytes at byte 30, the "
         "message ends at byte 124";
  // pointcloud.cdr-le.bin: frame_id "sonar_ring\0" 16..26, the count aligned to 28.
  QTest::newRow("CDR PointCloud points")
      << "pointcloud.cdr-le.bin" << 28
      << "PointCloud.points: 2147483647 elements need at least 25769803764 bytes at byte 32, the "
         "message ends at byte 132";
  // tf.ros1.bin: the count first; a TransformStamped takes at least 76 bytes in ROS 1 (seq,
  // stamp, two string lengths, seven float64).
  QTest::newRow("ROS 1 TF transforms")
      << "tf.ros1.bin" << 0
      << "TFMessage.transforms: 2147483647 elements need at least 163208757172 bytes at byte 4, "
         "the message ends at byte 185";
  // tf.cdr-le.bin: the count after the encapsulation header; 72 bytes at least (no seq).
  QTest::newRow("CDR TF transforms")
      << "tf.cdr-le.bin" << 4
      << "TFMessage.transforms: 2147483647 elements need at least 154618822584 bytes at byte 8, "
         "the message ends at byte 196";
  // range.ros1.bin: frame_id's length at 12.
  QTest::newRow("ROS 1 Range frame_id")
      << "range.ros1.bin" << 12
      << "Range.header.frame_id: the message ends at byte 40, 2147483647 bytes are needed at "
         "byte 16";
  // pointcloud2.ros1.bin: header 0..25, height 26, width 30, the fields' count 34, field "x"
  // 38..51, "y" 52..65, "z" 66..79, "intensity" 80..101, is_bigendian 102, point_step 103,
  // row_step 107, the data's count 111, the data 115..178, is_dense 179.
  QTest::newRow("ROS 1 PointCloud2 fields")
      << "pointcloud2.ros1.bin" << 34
      << "PointCloud2.fields: 2147483647 elements need at least 27917287411 bytes at byte 38, the "
         "message ends at byte 180";
  QTest::newRow("ROS 1 PointCloud2 data")
      << "pointcloud2.ros1.bin" << 111
      << "PointCloud2.data: 2147483647 elements need at least 2147483647 bytes at byte 115, the "
         "message ends at byte 180";
  QTest::newRow("ROS 1 PointCloud2 width")
      << "pointcloud2.ros1.bin" << 30
      << "PointCloud2.data: 1 rows of 2147483647 points (point_step 16, row_step 64) do not fit "
         "in its 64 bytes";
  QTest::newRow("ROS 1 PointCloud2 height")
      << "pointcloud2.ros1.bin" << 26
      << "PointCloud2.data: 2147483647 rows of 4 points (point_step 16, row_step 64) do not fit "
         "in its 64 bytes";
  // odometry.cdr-be.bin: child_frame_id's length at 24, big-endian.
  QTest::newRow("CDR BE Odometry child_frame_id")
      << "odometry.cdr-be.bin" << 24
      << "Odometry.child_frame_id: the message ends at byte 724, 2147483647 bytes are needed at "
         "byte 28";
}

void TstRosMessages::hugeCountsAreRejectedBeforeAllocating() {
  QFETCH(QString, file);
  QFETCH(int, at);
  QFETCH(QString, message);
  const bool bigEndian = file.contains("cdr-be");
  const std::string data =
      patched(fixture(file), static_cast<std::size_t>(at), 0x7fffffff, bigEndian);
  std::string what = "no error";
  try {
    decodeAs(file, data, encodingOf(file));
  } catch (const MessageError& e) {
    what = e.what();
  }
  QCOMPARE(QString::fromStdString(what), message);
  // 0xffffffff too: no overflow of count times size.
  try {
    decodeAs(file, patched(fixture(file), static_cast<std::size_t>(at), 0xffffffff, bigEndian),
             encodingOf(file));
    QFAIL("no error");
  } catch (const MessageError&) {
  }
}

void TstRosMessages::pointCloud2FieldsThatCannotBeReadAreErrors_data() {
  QTest::addColumn<int>("at");
  QTest::addColumn<int>("byte");  // a single byte patched at `at`, or -1 for the uint32 below
  QTest::addColumn<uint>("value");
  QTest::addColumn<QString>("message");
  // Offsets in pointcloud2.ros1.bin (see hugeCountsAreRejectedBeforeAllocating): "z"'s name at 70,
  // "x"'s datatype at 47, "z"'s offset at 71, height 26, row_step 107, point_step 103.
  QTest::newRow("no z") << 70 << int('w') << 0u
                        << "PointCloud2.fields: no field is named \"z\" (4 fields)";
  QTest::newRow("datatype 9") << 47 << 9 << 0u
                              << "PointCloud2.fields[0].datatype: 9 is not a PointField "
                                 "datatype (1 INT8 to 8 FLOAT64)";
  QTest::newRow("datatype 0") << 47 << 0 << 0u
                              << "PointCloud2.fields[0].datatype: 0 is not a PointField "
                                 "datatype (1 INT8 to 8 FLOAT64)";
  QTest::newRow("z past point_step")
      << 71 << -1 << 13u
      << "PointCloud2.fields[2].offset: field \"z\" at offset 13 (4 bytes) does not fit in "
         "point_step 16";
  QTest::newRow("z offset near 2^32")
      << 71 << -1 << 0xfffffffeu
      << "PointCloud2.fields[2].offset: field \"z\" at offset 4294967294 (4 bytes) does not fit "
         "in point_step 16";
  QTest::newRow("point_step 0")
      << 103 << -1 << 0u
      << "PointCloud2.fields[0].offset: field \"x\" at offset 0 (4 bytes) does not fit in "
         "point_step 0";
  // Two rows of four need (2 - 1) * 64 + 64 = 128 bytes; there are 64.
  QTest::newRow("two rows") << 26 << -1 << 2u
                            << "PointCloud2.data: 2 rows of 4 points (point_step 16, row_step "
                               "64) do not fit in its 64 bytes";
  QTest::newRow("rows overlap") << 26 << -1 << 2u << "";  // with row_step 32 below
}

void TstRosMessages::pointCloud2FieldsThatCannotBeReadAreErrors() {
  QFETCH(int, at);
  QFETCH(int, byte);
  QFETCH(uint, value);
  QFETCH(QString, message);
  std::string data = fixture("pointcloud2.ros1.bin");
  if (byte >= 0)
    data[static_cast<std::size_t>(at)] = static_cast<char>(byte);
  else
    data = patched(data, static_cast<std::size_t>(at), value);
  if (message.isEmpty()) {
    data = patched(data, 107, 32);  // row_step 32 < width 4 * point_step 16
    message = "PointCloud2.row_step: row_step 32 is less than width 4 times point_step 16";
  }
  QCOMPARE(QString::fromStdString(errorOf(sg::bag::decodePointCloud2, data, Encoding::Ros1)),
           message);
}

void TstRosMessages::onlyPlainXcdr1EncapsulationsAreRead_data() {
  QTest::addColumn<QByteArray>("head");
  QTest::addColumn<QString>("message");
  QTest::newRow("PL_CDR_BE") << QByteArray("\x00\x02", 2)
                             << "Range: CDR encapsulation 0x00 0x02 is parameter-list CDR "
                                "(PL_CDR), which is not read (only plain CDR_BE 0x00 0x00 and "
                                "CDR_LE 0x00 0x01)";
  QTest::newRow("PL_CDR_LE") << QByteArray("\x00\x03", 2)
                             << "Range: CDR encapsulation 0x00 0x03 is parameter-list CDR "
                                "(PL_CDR), which is not read (only plain CDR_BE 0x00 0x00 and "
                                "CDR_LE 0x00 0x01)";
  // XCDR2's RTPS kinds 0x06..0x0b (plain, delimited, parameter-list; BE and LE).
  for (int kind = 6; kind <= 0x0b; ++kind) {
    const QString hex = QStringLiteral("%1").arg(kind, 2, 16, QChar('0'));
    QTest::newRow(qPrintable("XCDR2 0x" + hex))
        << QByteArray(1, '\0') + QByteArray(1, static_cast<char>(kind))
        << "Range: CDR encapsulation 0x00 0x" + hex +
               " is XCDR2, which is not read (only XCDR1's CDR_BE 0x00 0x00 and CDR_LE 0x00 "
               "0x01)";
  }
  QTest::newRow("0x01 0x00") << QByteArray("\x01\x00", 2)
                             << "Range: CDR encapsulation 0x01 0x00 is not a CDR encapsulation "
                                "this reader knows (CDR_BE 0x00 0x00, CDR_LE 0x00 0x01)";
  QTest::newRow("ROS 1 bytes") << QByteArray("\x07\x00", 2)
                               << "Range: CDR encapsulation 0x07 0x00 is not a CDR encapsulation "
                                  "this reader knows (CDR_BE 0x00 0x00, CDR_LE 0x00 0x01)";
}

void TstRosMessages::onlyPlainXcdr1EncapsulationsAreRead() {
  QFETCH(QByteArray, head);
  QFETCH(QString, message);
  std::string data = fixture("range.cdr-le.bin");
  data[0] = head[0];
  data[1] = head[1];
  QCOMPARE(QString::fromStdString(errorOf(sg::bag::decodeRange, data, Encoding::Cdr)), message);
  // The option bytes (2 and 3) are not looked at.
  std::string options = fixture("range.cdr-le.bin");
  options[2] = '\x12';
  options[3] = '\x34';
  SAME(sg::bag::decodeRange(options, Encoding::Cdr).range, 2.873f);
}

void TstRosMessages::cdrStringsWithoutTheirNulAreRead() {
  // A length of 0 (the NUL itself missing) is the empty string; a string whose last byte is not
  // a NUL is kept whole. Hand-made CDR PoseStamped messages.
  Bytes empty(true);
  empty.put<std::int32_t>(-5).put<std::uint32_t>(7).put<std::uint32_t>(0);
  for (double v : {1.0, 2.0, 3.0, 0.0, 0.0, 0.0, 1.0}) empty.put<double>(v);
  const sg::bag::PoseStampedMsg a = sg::bag::decodePoseStamped(empty.bytes(), Encoding::Cdr);
  QCOMPARE(a.header.frameId, std::string());
  QCOMPARE(a.header.stamp.sec, std::int64_t{-5});  // int32 in ROS 2: before 1970
  QCOMPARE(a.header.stamp.ns(), std::int64_t{-4'999'999'993});
  SAME(a.pose.position.x, 1.0);  // aligned to byte 20 (16 after the header)
  SAME(a.pose.orientation.w, 1.0);

  Bytes noNul(true);
  noNul.put<std::int32_t>(1).put<std::uint32_t>(0).str("map", false);
  for (double v : {4.0, 5.0, 6.0, 0.0, 0.0, 0.0, 1.0}) noNul.put<double>(v);
  const sg::bag::PoseStampedMsg b = sg::bag::decodePoseStamped(noNul.bytes(), Encoding::Cdr);
  QCOMPARE(b.header.frameId, std::string("map"));
  SAME(b.pose.position.z, 6.0);
}

void TstRosMessages::nanosecondsOfASecondOrMoreCarryIntoTheSeconds() {
  // ROS 1 secs 4294967295 (uint32) and nsecs 2500000000: 4294967297 s 500000000 ns.
  std::string data = fixture("range.ros1.bin");
  data = patched(patched(data, 4, 0xffffffff), 8, 2500000000u);
  const sg::bag::RangeMsg r = sg::bag::decodeRange(data, Encoding::Ros1);
  QCOMPARE(r.header.stamp.sec, std::int64_t{4294967297});
  QCOMPARE(r.header.stamp.nsec, std::uint32_t{500000000});
}

QTEST_APPLESS_MAIN(TstRosMessages)
#include "tst_ros_messages.moc"
