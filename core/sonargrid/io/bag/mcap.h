// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// MCAP (docs/formats.md, "ROS bags"), the storage of rosbag2 since ROS 2 Iron: the magic
// "\x89MCAP0\r\n", records of an opcode byte and a uint64 length, and the magic again at the end.
// Schemas, channels and messages, bare or inside chunks (compression "", "zstd" or "lz4"); the
// summary section (channel and chunk indexes, statistics) is used when the footer points at one,
// and a file without a summary, or cut short, is read by walking its records from the start.

#include <memory>

#include "sonargrid/io/bag/bag.h"

namespace sg::bag {

// Reads the header, and the summary when there is one, now; messages on read(). Throws BagError
// for a file that is not MCAP or whose records are malformed.
std::unique_ptr<Reader> openMcap(std::unique_ptr<ByteSource> source);

}  // namespace sg::bag
