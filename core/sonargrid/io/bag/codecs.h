// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The chunk compressions bags use, through Debian's libraries: bz2 and LZ4 (ROS 1 bags; roslz4
// writes the LZ4 frame format), zstd and LZ4 frames (MCAP).

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

namespace sg::bag {

// Thrown for corrupt compressed data or a result whose size is not `expectedSize`; the container
// readers add the file, offset and topic (BagError).
class CodecError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Each decompresses `in`, which must give exactly `expectedSize` bytes, into `out` (resized).
void decompressBz2(std::string_view in, std::size_t expectedSize, std::string& out);
void decompressLz4Frame(std::string_view in, std::size_t expectedSize, std::string& out);
void decompressZstd(std::string_view in, std::size_t expectedSize, std::string& out);

// The largest uncompressed chunk a reader accepts (bags' chunks are a few MB; a bigger size field
// is a corrupt file, not a reason to allocate it).
inline constexpr std::size_t kMaxChunkBytes = std::size_t{1} << 30;

}  // namespace sg::bag
