// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The MCAP records SonarGrid reads (https://mcap.dev/spec), parsed from their content: the opcodes,
// the CRC-32 the spec uses, a little-endian cursor that checks every length, and one parse per
// record kind. Only mcap.cpp includes it; split from there to keep the reader's file readable.
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "sonargrid/io/bag/bag.h"

namespace sg::bag::mcap_records {

constexpr std::string_view kMagic("\x89MCAP0\r\n", 8);
constexpr std::uint64_t kPrefix = 9;          // opcode uint8 + length uint64
constexpr std::uint64_t kFooterContent = 20;  // summary_start, summary_offset_start, summary_crc
constexpr std::uint64_t kFooterRecord = kPrefix + kFooterContent;
constexpr std::size_t kBlock = std::size_t{1} << 20;  // bytes read at once when walking
constexpr std::uint64_t kProgressEvery = std::uint64_t{1} << 20;

enum Op : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kStatistics = 0x0B,
  kDataEnd = 0x0F,
};

inline std::string hex(std::uint64_t v, int digits);

// "a Chunk record (opcode 0x06)", for messages.
inline std::string recordName(std::uint8_t op) {
  static const char* const names[] = {nullptr,      "Header",           "Footer",
                                      "Schema",     "Channel",          "Message",
                                      "Chunk",      "Message Index",    "Chunk Index",
                                      "Attachment", "Attachment Index", "Statistics",
                                      "Metadata",   "Metadata Index",   "Summary Offset",
                                      "Data End"};
  const std::string code = "(opcode " + hex(op, 2) + ")";
  if (op > 0 && op < std::size(names)) return std::string("a ") + names[op] + " record " + code;
  return "a record " + code;
}

inline std::string hex(std::uint64_t v, int digits) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "0x%0*llx", digits, static_cast<unsigned long long>(v));
  return buf;
}

// CRC-32 as the spec uses it: zlib's (reflected polynomial 0xEDB88320, initial and final
// complement).
constexpr std::array<std::uint32_t, 256> makeCrcTable() {
  std::array<std::uint32_t, 256> t{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    t[i] = c;
  }
  return t;
}
constexpr std::array<std::uint32_t, 256> kCrcTable = makeCrcTable();

inline std::uint32_t crc32(std::string_view bytes, std::uint32_t crc = 0) {
  crc = ~crc;
  for (const char ch : bytes) {
    crc = kCrcTable[(crc ^ static_cast<std::uint8_t>(ch)) & 0xFFu] ^ (crc >> 8);
  }
  return ~crc;
}

// A record's content that does not parse; the caller adds the file, offset and record kind.
class Malformed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Little-endian fields of one record's content, every length checked against what is left.
class Cursor {
 public:
  explicit Cursor(std::string_view d) : d_(d) {}
  std::size_t left() const { return d_.size() - p_; }
  bool done() const { return p_ == d_.size(); }

  std::uint8_t u8(const char* field) { return static_cast<std::uint8_t>(take(1, field)[0]); }
  std::uint16_t u16(const char* field) { return static_cast<std::uint16_t>(le(2, field)); }
  std::uint32_t u32(const char* field) { return static_cast<std::uint32_t>(le(4, field)); }
  std::uint64_t u64(const char* field) { return le(8, field); }
  // A uint32 byte length and that many bytes (strings, byte arrays, maps, arrays).
  std::string_view prefixed(const char* field) {
    const std::uint32_t n = u32(field);
    if (n > left()) {
      throw Malformed(std::string(field) + ": a length of " + std::to_string(n) +
                      " bytes, but only " + std::to_string(left()) + " are left in the record");
    }
    return take(n, field);
  }
  std::string_view rest() { return take(left(), ""); }

 private:
  std::string_view take(std::size_t n, const char* field) {
    if (n > left()) {
      throw Malformed(std::string("record cut short in ") + field + " (" + std::to_string(n) +
                      " bytes needed, " + std::to_string(left()) + " left)");
    }
    const std::string_view v = d_.substr(p_, n);
    p_ += n;
    return v;
  }
  std::uint64_t le(std::size_t n, const char* field) {
    const std::string_view b = take(n, field);
    std::uint64_t v = 0;
    for (std::size_t i = n; i-- > 0;) v = (v << 8) | static_cast<std::uint8_t>(b[i]);
    return v;
  }

  std::string_view d_;
  std::size_t p_ = 0;
};

inline std::uint64_t readLe64(std::string_view b) {
  std::uint64_t v = 0;
  for (std::size_t i = 8; i-- > 0;) v = (v << 8) | static_cast<std::uint8_t>(b[i]);
  return v;
}

struct SchemaRec {
  std::uint16_t id = 0;
  std::string_view name, encoding, data;
};
inline SchemaRec parseSchema(std::string_view content) {
  Cursor c(content);
  SchemaRec s;
  s.id = c.u16("Schema.id");
  s.name = c.prefixed("Schema.name");
  s.encoding = c.prefixed("Schema.encoding");
  s.data = c.prefixed("Schema.data");
  return s;
}

struct ChannelRec {
  std::uint16_t id = 0, schemaId = 0;
  std::string_view topic, messageEncoding;
};
inline ChannelRec parseChannel(std::string_view content) {
  Cursor c(content);
  ChannelRec ch;
  ch.id = c.u16("Channel.id");
  ch.schemaId = c.u16("Channel.schema_id");
  ch.topic = c.prefixed("Channel.topic");
  ch.messageEncoding = c.prefixed("Channel.message_encoding");
  c.prefixed("Channel.metadata");
  return ch;
}

struct MessageRec {
  std::uint16_t channelId = 0;
  std::uint64_t logTime = 0;
  std::string_view data;
};
inline MessageRec parseMessage(std::string_view content) {
  Cursor c(content);
  MessageRec m;
  m.channelId = c.u16("Message.channel_id");
  c.u32("Message.sequence");
  m.logTime = c.u64("Message.log_time");
  c.u64("Message.publish_time");
  m.data = c.rest();
  return m;
}

struct ChunkRec {
  std::uint64_t uncompressedSize = 0;
  std::uint32_t crc = 0;
  std::string_view compression, records;
};
inline ChunkRec parseChunk(std::string_view content) {
  Cursor c(content);
  ChunkRec k;
  c.u64("Chunk.message_start_time");
  c.u64("Chunk.message_end_time");
  k.uncompressedSize = c.u64("Chunk.uncompressed_size");
  k.crc = c.u32("Chunk.uncompressed_crc");
  k.compression = c.prefixed("Chunk.compression");
  const std::uint64_t n = c.u64("Chunk.records length");
  if (n != c.left()) {
    throw Malformed("Chunk.records: a length of " + std::to_string(n) + " bytes, but " +
                    std::to_string(c.left()) + " are left in the record");
  }
  k.records = c.rest();
  return k;
}

struct ChunkIndexRec {
  std::uint64_t startTime = 0, endTime = 0, chunkOffset = 0, chunkLength = 0;
  std::vector<std::uint16_t> channels;  // keys of message_index_offsets
  std::uint64_t messageIndexLength = 0;
};
inline ChunkIndexRec parseChunkIndex(std::string_view content) {
  Cursor c(content);
  ChunkIndexRec k;
  k.startTime = c.u64("Chunk Index.message_start_time");
  k.endTime = c.u64("Chunk Index.message_end_time");
  k.chunkOffset = c.u64("Chunk Index.chunk_start_offset");
  k.chunkLength = c.u64("Chunk Index.chunk_length");
  Cursor offsets(c.prefixed("Chunk Index.message_index_offsets"));
  while (!offsets.done()) {
    k.channels.push_back(offsets.u16("Chunk Index.message_index_offsets key"));
    offsets.u64("Chunk Index.message_index_offsets value");
  }
  k.messageIndexLength = c.u64("Chunk Index.message_index_length");
  c.prefixed("Chunk Index.compression");
  c.u64("Chunk Index.compressed_size");
  c.u64("Chunk Index.uncompressed_size");
  return k;
}

struct StatisticsRec {
  std::uint64_t startTime = 0, endTime = 0;
  std::map<std::uint16_t, std::uint64_t> counts;
};
inline StatisticsRec parseStatistics(std::string_view content) {
  Cursor c(content);
  StatisticsRec s;
  c.u64("Statistics.message_count");
  c.u16("Statistics.schema_count");
  c.u32("Statistics.channel_count");
  c.u32("Statistics.attachment_count");
  c.u32("Statistics.metadata_count");
  c.u32("Statistics.chunk_count");
  s.startTime = c.u64("Statistics.message_start_time");
  s.endTime = c.u64("Statistics.message_end_time");
  Cursor counts(c.prefixed("Statistics.channel_message_counts"));
  while (!counts.done()) {
    const std::uint16_t id = counts.u16("Statistics.channel_message_counts key");
    s.counts[id] = counts.u64("Statistics.channel_message_counts value");
  }
  return s;
}

// Per-channel message count and log-time bounds.
struct Tally {
  std::uint64_t count = 0;
  std::uint64_t first = std::numeric_limits<std::uint64_t>::max(), last = 0;
  void add(std::uint64_t t, std::uint64_t n = 1) {
    count += n;
    first = std::min(first, t);
    last = std::max(last, t);
  }
  void bound(std::uint64_t a, std::uint64_t b) {
    first = std::min(first, a);
    last = std::max(last, b);
  }
};

// Pieces of the file, the last one read kept. Walking the records reads ahead a block at a time
// (records are often a few bytes); jumping to an indexed chunk or message index reads just what
// is asked. A view stays valid until the next fetch.
class Window {
 public:
  explicit Window(const ByteSource& src) : src_(src) {}
  std::string_view fetch(std::uint64_t offset, std::size_t n) { return get(offset, n, n); }
  std::string_view ahead(std::uint64_t offset, std::size_t n) {
    const std::uint64_t left = src_.size() > offset ? src_.size() - offset : 0;
    return get(offset, n, static_cast<std::size_t>(std::min<std::uint64_t>(kBlock, left)));
  }

 private:
  std::string_view get(std::uint64_t offset, std::size_t n, std::size_t want) {
    if (offset < start_ || offset - start_ > block_.size() ||
        n > block_.size() - (offset - start_)) {
      src_.read(offset, std::max(want, n), block_);
      start_ = offset;
    }
    return std::string_view(block_).substr(static_cast<std::size_t>(offset - start_), n);
  }

  const ByteSource& src_;
  std::uint64_t start_ = 0;
  std::string block_;
};

struct Schema {
  std::string name, encoding, data;
};
struct Channel {
  std::uint16_t schemaId = 0;
  std::string topic, messageEncoding;
  std::uint64_t offset = 0;  // of the record (or of its chunk) that defined it
};

}  // namespace sg::bag::mcap_records
