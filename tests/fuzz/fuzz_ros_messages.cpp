// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the ROS message decoders of sonargrid/io/bag/ros_messages.h
// (tests/fuzz/README.md). The first byte chooses the type (byte % 6: Range, PointCloud,
// PointCloud2, Odometry, PoseStamped, TFMessage) and the encoding ((byte / 6) % 2: ROS 1, CDR);
// the rest is the message. A result or a MessageError are the only acceptable outcomes.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "sonargrid/io/bag/ros_messages.h"

namespace {

void checkStamp(const sg::bag::Stamp& s) {
  if (s.nsec >= 1'000'000'000u) std::abort();  // the decoders carry whole seconds
}

void decode(unsigned type, std::string_view data, sg::bag::Encoding e) {
  using namespace sg::bag;
  switch (type) {
    case 0:
      checkStamp(decodeRange(data, e).header.stamp);
      break;
    case 1: {
      const PointCloudMsg p = decodePointCloud(data, e);
      if (p.points.size() > data.size() / 12) std::abort();  // 12 bytes a point at least
      break;
    }
    case 2: {
      const PointCloud2Msg p = decodePointCloud2(data, e);
      // Every point takes at least one byte of data (each of x, y, z one byte or more).
      if (p.points.size() > data.size()) std::abort();
      break;
    }
    case 3:
      checkStamp(decodeOdometry(data, e).header.stamp);
      break;
    case 4:
      checkStamp(decodePoseStamped(data, e).header.stamp);
      break;
    default: {
      const TfMsg tf = decodeTf(data, e);
      for (const TransformMsg& t : tf.transforms) checkStamp(t.header.stamp);
      break;
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string_view rest(reinterpret_cast<const char*>(data + 1), size - 1);
  const unsigned type = data[0] % 6u;
  const auto encoding = (data[0] / 6u) % 2u == 0 ? sg::bag::Encoding::Ros1 : sg::bag::Encoding::Cdr;
  try {
    decode(type, rest, encoding);
  } catch (const sg::bag::MessageError&) {
  }
  sg::bag::messageType(rest);
  return 0;
}
