// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The records of a ROS 1 bag, format 2.0 (http://wiki.ros.org/Bags/Format/2.0), as rosbag1.cpp
// frames them: the op codes, little-endian numbers and times, a record header's fields, and the
// records inside a decompressed chunk. Only rosbag1.cpp includes it; split from there to keep the
// reader's file readable.
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sonargrid/io/bag/codecs.h"

namespace sg::bag::rosbag1_records {

constexpr std::string_view kVersionLine = "#ROSBAG V2.0\n";
constexpr std::uint64_t kBagHeaderPos = kVersionLine.size();
// Record headers are a few fields (connection records carry the long message definition in their
// data part); a bigger header length is a corrupt file, not a reason to allocate it.
constexpr std::uint64_t kMaxHeaderBytes = std::uint64_t{16} << 20;
// The compressed bytes of a chunk of at most kMaxChunkBytes (bz2 and LZ4 add a little to data
// that do not compress).
constexpr std::uint64_t kMaxStoredChunkBytes = kMaxChunkBytes + kMaxChunkBytes / 64 + 4096;
// An LZ4 block sequence turns each extra byte of match length into 255 bytes at most, so a
// frame cannot hold more than about 255 times its size.
constexpr std::uint64_t kMaxLz4Ratio = 256;
// Progress of bags without chunks: at least every MiB.
constexpr std::uint64_t kProgressStep = std::uint64_t{1} << 20;

enum Op : std::uint8_t {
  kMessageData = 0x02,
  kBagHeader = 0x03,
  kIndexData = 0x04,
  kChunk = 0x05,
  kChunkInfo = 0x06,
  kConnection = 0x07,
};

// A malformed record before its file, offset and topic are known; the callers make a BagError.
struct Malformed {
  std::string message;
};

inline std::uint32_t le32(const char* p) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(p[i]);
  return v;
}

inline std::uint64_t le64(const char* p) {
  return (std::uint64_t{le32(p + 4)} << 32) | le32(p);
}

// ROS time: uint32 seconds, uint32 nanoseconds.
inline std::int64_t timeNs(const char* p) {
  return static_cast<std::int64_t>(le32(p)) * 1000000000 + static_cast<std::int64_t>(le32(p + 4));
}

inline std::string hex(unsigned value) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "0x%02x", value & 0xffu);
  return buf;
}

// Bytes of a file quoted in a message: printable ASCII as is, the rest as \xNN, at most 64.
inline std::string printable(std::string_view s) {
  std::string out;
  for (const char c : s.substr(0, 64)) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7f && c != '\\') {
      out += c;
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", u);
      out += buf;
    }
  }
  if (s.size() > 64) out += "...";
  return out;
}

// The fields of a record header, or of a connection record's data: each a uint32 length, then
// "name=value" with a binary value.
class Fields {
 public:
  explicit Fields(std::string_view bytes) {
    std::size_t pos = 0;
    while (pos < bytes.size()) {
      const std::size_t left = bytes.size() - pos;
      if (left < 4) {
        throw Malformed{"a header field's length is cut short (" + std::to_string(left) +
                        " bytes left in the header)"};
      }
      const std::uint32_t len = le32(bytes.data() + pos);
      pos += 4;
      if (len > bytes.size() - pos) {
        throw Malformed{"a header field of " + std::to_string(len) +
                        " bytes runs past the end of the header (" +
                        std::to_string(bytes.size() - pos) + " bytes left)"};
      }
      const std::string_view field = bytes.substr(pos, len);
      pos += len;
      const std::size_t eq = field.find('=');
      if (eq == std::string_view::npos) {
        throw Malformed{"a header field without '=' (\"" + printable(field) + "\")"};
      }
      items_.emplace_back(field.substr(0, eq), field.substr(eq + 1));
    }
  }

  // The value of the last field of that name (a repeated field overrides), if any.
  std::optional<std::string_view> find(std::string_view name) const {
    for (auto it = items_.rbegin(); it != items_.rend(); ++it) {
      if (it->first == name) return it->second;
    }
    return std::nullopt;
  }
  std::string_view bytes(std::string_view name) const {
    const std::optional<std::string_view> v = find(name);
    if (!v) throw Malformed{"missing required field '" + std::string(name) + "'"};
    return *v;
  }
  std::uint8_t u8(std::string_view name) const {
    return static_cast<std::uint8_t>(*sized(name, 1).data());
  }
  std::uint32_t u32(std::string_view name) const { return le32(sized(name, 4).data()); }
  std::uint64_t u64(std::string_view name) const { return le64(sized(name, 8).data()); }
  std::int64_t time(std::string_view name) const { return timeNs(sized(name, 8).data()); }

 private:
  std::string_view sized(std::string_view name, std::size_t n) const {
    const std::string_view v = bytes(name);
    if (v.size() != n) {
      throw Malformed{"field '" + std::string(name) + "' has " + std::to_string(v.size()) +
                      " bytes, not " + std::to_string(n)};
    }
    return v;
  }

  std::vector<std::pair<std::string_view, std::string_view>> items_;
};

// A record inside a decompressed chunk.
struct ChunkRecord {
  std::string_view header, data;
  std::size_t end = 0;  // where the next record starts
};

inline ChunkRecord chunkRecordAt(std::string_view buf, std::size_t pos) {
  std::size_t left = buf.size() - pos;
  if (left < 4) {
    throw Malformed{"the record is cut short: " + std::to_string(left) +
                    " bytes left in the chunk, fewer than its 4-byte header length"};
  }
  const std::uint32_t headerLen = le32(buf.data() + pos);
  left -= 4;
  if (headerLen > left) {
    throw Malformed{"a header of " + std::to_string(headerLen) +
                    " bytes runs past the end of the chunk (" + std::to_string(left) +
                    " bytes left)"};
  }
  const std::size_t lenPos = pos + 4 + headerLen;
  left -= headerLen;
  if (left < 4) throw Malformed{"the record is cut short after its header (no data length)"};
  const std::uint32_t dataLen = le32(buf.data() + lenPos);
  left -= 4;
  if (dataLen > left) {
    throw Malformed{"data of " + std::to_string(dataLen) +
                    " bytes run past the end of the chunk (" + std::to_string(left) +
                    " bytes left)"};
  }
  return {buf.substr(pos + 4, headerLen), buf.substr(lenPos + 4, dataLen), lenPos + 4 + dataLen};
}

// A record of the file: its header read, its data where they lie.
struct FileRecord {
  std::uint64_t offset = 0;
  std::string header;
  std::uint64_t dataPos = 0;
  std::uint32_t dataLen = 0;
  std::uint64_t end = 0;  // where the next record starts
};

// A chunk as the index (or the walk without one) describes it.
struct ChunkRef {
  std::uint64_t pos = 0;
  std::int64_t startNs = 0, endNs = 0;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> counts;  // connection, messages
};

}  // namespace sg::bag::rosbag1_records
