// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// ROS 1 bag format 2.0 (docs/formats.md, "ROS bags"): the "#ROSBAG V2.0\n" line, then records of
// a length-prefixed header (name=value fields) and a length-prefixed data part. Op codes: 0x03
// bag header (index_pos, conn_count, chunk_count), 0x05 chunk (compression none/bz2/lz4, size),
// 0x07 connection, 0x02 message data, 0x04 index data, 0x06 chunk info. Read from the index at
// index_pos when the bag has one (a bag closed cleanly); a bag without one (a recording cut short)
// is read by walking its chunks from the start.

#include <memory>

#include "sonargrid/io/bag/bag.h"

namespace sg::bag {

// Reads the file's header and index (or, without an index, its connections) now; messages on
// read(). Throws BagError for a file that is not a ROS 1 bag 2.0 or whose header is malformed.
std::unique_ptr<Reader> openRos1(std::unique_ptr<ByteSource> source);

}  // namespace sg::bag
