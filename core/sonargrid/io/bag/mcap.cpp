// SPDX-License-Identifier: BSD-3-Clause
// MCAP, read from the public specification (https://mcap.dev/spec). Two roads:
//  - indexed: the footer points at a summary section with Chunk Index records. Schemas, channels,
//    statistics and chunk indexes come from it; the per-channel first/last log times (and counts
//    when there are no Statistics) from the Message Index records after each chunk, or the chunk
//    bounds when a chunk has none. read() visits only the chunks that hold a wanted channel
//    (messages outside chunks, which such a file should not have, are not read).
//  - walked: no summary, a summary without chunk indexes, a summary that is malformed, or a file
//    cut short. Opening walks every record from the start once (decompressing the chunks) to find
//    the schemas and channels and count the messages; read() walks the records again.
// Opening only throws for a file that is not MCAP (magic, Header record). Any other damage found
// while opening is kept and raised by read(): strict reads throw it, lenient reads count it in
// skipped() and go on (the walk skips what it cannot read).

#include "sonargrid/io/bag/mcap.h"

#include <zstd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <iterator>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <utility>

#include "sonargrid/io/bag/codecs.h"
#include "sonargrid/io/bag/mcap_records.h"
#include "sonargrid/io/log_options.h"

namespace sg::bag {
namespace {

using namespace mcap_records;  // NOLINT: the records of this file, split into mcap_records.h

class McapReader final : public Reader {
 public:
  explicit McapReader(std::unique_ptr<ByteSource> src)
      : src_(std::move(src)), name_(src_->name()), size_(src_->size()), window_(*src_) {
    open();
  }

  const std::vector<Topic>& topics() const override { return topics_; }
  const Skipped& skipped() const override { return skipped_; }

  void read(const std::vector<bool>& wanted, const ReadOptions& options,
            const std::function<void(const Message&)>& visit) override {
    skipped_ = {};
    for (const BagError& e : deferred_) problem(e, options);
    Pass pass{wanted, options, visit};
    if (indexed_) {
      readIndexed(pass);
    } else {
      walk(dataStart_, dataEnd_, &pass);
    }
  }

 private:
  struct Pass {
    const std::vector<bool>& wanted;
    const ReadOptions& options;
    const std::function<void(const Message&)>& visit;
    std::uint64_t reported = 0;  // offset of the last progress report
  };

  BagError error(std::uint64_t offset, std::string message, std::string topic = {}) const {
    return BagError(name_, offset, std::move(topic), std::move(message));
  }

  void problem(const BagError& e, const ReadOptions& options) {
    if (!options.lenient) throw e;
    if (skipped_.count++ == 0) skipped_.firstError = e.what();
  }

  void step(Pass& pass, std::uint64_t done) {
    pass.reported = done;
    if (pass.options.progress) pass.options.progress(done, size_);
    if (pass.options.cancel && pass.options.cancel->load()) throw LoadCancelled(name_);
  }

  // ---- opening ----

  void open() {
    if (size_ < kMagic.size() || window_.fetch(0, kMagic.size()) != kMagic) {
      throw error(0, "not an MCAP file: it does not start with the MCAP magic \\x89MCAP0\\r\\n");
    }
    const std::uint64_t at = kMagic.size();
    if (size_ - at < kPrefix) throw error(at, "the file ends before the Header record");
    const std::string_view prefix = window_.fetch(at, kPrefix);
    if (static_cast<std::uint8_t>(prefix[0]) != kHeader) {
      throw error(at, "expected the Header record (opcode 0x01) after the magic, found opcode " +
                          hex(static_cast<std::uint8_t>(prefix[0]), 2));
    }
    const std::uint64_t length = readLe64(prefix.substr(1));
    if (length > size_ - at - kPrefix || length > kMaxChunkBytes) {
      throw error(at, "the Header record's length of " + std::to_string(length) +
                          " bytes runs past the end of the file");
    }
    try {
      Cursor c(window_.fetch(at + kPrefix, static_cast<std::size_t>(length)));
      c.prefixed("Header.profile");
      c.prefixed("Header.library");
    } catch (const Malformed& e) {
      throw error(at, std::string("Header record: ") + e.what());
    }
    dataStart_ = at + kPrefix + length;
    dataEnd_ = size_;

    if (const std::optional<std::uint64_t> summaryStart = footerSummaryStart()) {
      try {
        readSummary(*summaryStart);
      } catch (const BagError& e) {
        // The data section can still be walked: read() reports this, or counts it when lenient.
        deferred_.push_back(e);
        indexed_ = false;
        dataEnd_ = size_;
        schemas_.clear();
      }
    }
    if (!indexed_) firstPass();
  }

  // summary_start of a whole file's footer, or nothing when there is no summary or no footer
  // (a file cut short).
  std::optional<std::uint64_t> footerSummaryStart() {
    if (size_ < dataStart_ + kFooterRecord + kMagic.size()) return std::nullopt;
    footerAt_ = size_ - kMagic.size() - kFooterRecord;
    const std::string_view tail =
        window_.fetch(footerAt_, static_cast<std::size_t>(kFooterRecord + kMagic.size()));
    if (tail.substr(kFooterRecord) != kMagic || static_cast<std::uint8_t>(tail[0]) != kFooter ||
        readLe64(tail.substr(1)) != kFooterContent) {
      return std::nullopt;
    }
    Cursor c(tail.substr(kPrefix));
    const std::uint64_t summaryStart = c.u64("Footer.summary_start");
    summaryOffsetStart_ = c.u64("Footer.summary_offset_start");
    summaryCrc_ = c.u32("Footer.summary_crc");
    if (summaryStart == 0) return std::nullopt;
    return summaryStart;
  }

  void readSummary(std::uint64_t start) {
    if (start < dataStart_ || start > footerAt_) {
      throw error(footerAt_, "the Footer's summary_start " + std::to_string(start) +
                                 " is outside the file's records");
    }
    const std::uint64_t end = summaryOffsetStart_ != 0 ? summaryOffsetStart_ : footerAt_;
    if (end < start || end > footerAt_) {
      throw error(footerAt_, "the Footer's summary_offset_start " +
                                 std::to_string(summaryOffsetStart_) +
                                 " is outside the summary section");
    }
    if (footerAt_ + 25 - start > kMaxChunkBytes) {
      throw error(start, "a summary section of " + std::to_string(footerAt_ - start) +
                             " bytes, over the limit of " + std::to_string(kMaxChunkBytes));
    }
    // The CRC covers the summary (and its offsets) up to the Footer's summary_crc field.
    std::string bytes(window_.fetch(start, static_cast<std::size_t>(footerAt_ + 25 - start)));
    if (summaryCrc_ != 0) {
      const std::uint32_t crc = crc32(bytes);
      if (crc != summaryCrc_) {
        throw error(start, "summary section: CRC " + hex(summaryCrc_, 8) +
                               " but its bytes hash to " + hex(crc, 8));
      }
    }
    const std::string_view summary =
        std::string_view(bytes).substr(0, static_cast<std::size_t>(end - start));
    std::map<std::uint16_t, Channel> channels;
    std::optional<StatisticsRec> stats;
    std::vector<ChunkIndexRec> chunks;
    std::size_t p = 0;
    while (p < summary.size()) {
      const std::uint64_t at = start + p;
      if (summary.size() - p < kPrefix) throw error(at, "summary section: record cut short");
      const auto op = static_cast<std::uint8_t>(summary[p]);
      const std::uint64_t length = readLe64(summary.substr(p + 1, 8));
      if (length > summary.size() - p - kPrefix) {
        throw error(at, "summary section: a record of " + std::to_string(length) +
                            " bytes runs past the end of the section");
      }
      const std::string_view content =
          summary.substr(p + kPrefix, static_cast<std::size_t>(length));
      try {
        if (op == kSchema) {
          addSchema(parseSchema(content));
        } else if (op == kChannel) {
          const ChannelRec ch = parseChannel(content);
          channels.try_emplace(ch.id, Channel{ch.schemaId, std::string(ch.topic),
                                              std::string(ch.messageEncoding), at});
        } else if (op == kChunkIndex) {
          chunks.push_back(parseChunkIndex(content));
          const ChunkIndexRec& k = chunks.back();
          if (k.chunkOffset < dataStart_ || k.chunkOffset > start ||
              k.chunkLength > start - k.chunkOffset || k.chunkLength < kPrefix ||
              k.messageIndexLength > start - k.chunkOffset - k.chunkLength) {
            throw Malformed("the chunk it indexes (offset " + std::to_string(k.chunkOffset) + ", " +
                            std::to_string(k.chunkLength) +
                            " bytes) is not inside the data section");
          }
        } else if (op == kStatistics) {
          stats = parseStatistics(content);
        }
      } catch (const Malformed& e) {
        throw error(at, "summary section: " + std::string(e.what()));
      }
      p += static_cast<std::size_t>(kPrefix + length);
    }
    dataEnd_ = start;
    if (chunks.empty()) return;  // no chunk index: the data section is walked

    std::sort(chunks.begin(), chunks.end(), [](const ChunkIndexRec& a, const ChunkIndexRec& b) {
      return a.chunkOffset < b.chunkOffset;
    });
    std::map<std::uint16_t, Tally> tallies;
    for (const ChunkIndexRec& k : chunks) tallyChunk(k, tallies);
    if (stats) {
      for (auto& [id, t] : tallies) t.count = 0;
      for (const auto& [id, n] : stats->counts) tallies[id].count = n;
    }
    buildTopics(channels, tallies, /*strict=*/true);
    chunks_ = std::move(chunks);
    indexed_ = true;
  }

  // Counts and log-time bounds of the chunk's channels, from its Message Index records (read
  // with the chunk index's lengths), or the chunk's own bounds for the channels it lists.
  void tallyChunk(const ChunkIndexRec& k, std::map<std::uint16_t, Tally>& tallies) {
    std::map<std::uint16_t, Tally> mine;
    try {
      if (k.messageIndexLength == 0 || k.messageIndexLength > kMaxChunkBytes) {
        throw Malformed("no message index");
      }
      const std::string_view all = window_.fetch(k.chunkOffset + k.chunkLength,
                                                 static_cast<std::size_t>(k.messageIndexLength));
      std::size_t p = 0;
      while (p < all.size()) {
        if (all.size() - p < kPrefix) throw Malformed("cut short");
        const auto op = static_cast<std::uint8_t>(all[p]);
        const std::uint64_t length = readLe64(all.substr(p + 1, 8));
        if (length > all.size() - p - kPrefix) throw Malformed("cut short");
        if (op == kMessageIndex) {
          Cursor m(all.substr(p + kPrefix, static_cast<std::size_t>(length)));
          Tally& t = mine[m.u16("Message Index.channel_id")];
          Cursor entries(m.prefixed("Message Index.records"));
          while (!entries.done()) {
            t.add(entries.u64("Message Index.log_time"));
            entries.u64("Message Index.offset");
          }
        }
        p += static_cast<std::size_t>(kPrefix + length);
      }
    } catch (const std::runtime_error&) {  // Malformed, or BagError from the source
      mine.clear();
      for (const std::uint16_t id : k.channels) mine[id].bound(k.startTime, k.endTime);
    }
    for (const auto& [id, t] : mine) {
      Tally& all = tallies[id];
      all.count += t.count;
      if (t.first <= t.last) all.bound(t.first, t.last);
    }
  }

  void addSchema(const SchemaRec& s) {
    schemas_.try_emplace(s.id,
                         Schema{std::string(s.name), std::string(s.encoding), std::string(s.data)});
  }

  // topics_ from the channels in id order. A channel whose schema the file lacks is an error
  // (strict: thrown; else left out, and read() meets its record again). Channels whose messages
  // are neither CDR nor ROS 1 are left out and their messages passed over.
  void buildTopics(const std::map<std::uint16_t, Channel>& channels,
                   const std::map<std::uint16_t, Tally>& tallies, bool strict) {
    std::vector<Topic> topics;
    std::map<std::uint16_t, std::size_t> index;
    std::set<std::uint16_t> other;
    for (const auto& [id, ch] : channels) {
      const Schema* schema = nullptr;
      if (ch.schemaId != 0) {
        const auto s = schemas_.find(ch.schemaId);
        if (s == schemas_.end()) {
          if (strict) throw unknownSchema(ch.offset, id, ch);
          continue;
        }
        schema = &s->second;
      }
      Topic t;
      if (ch.messageEncoding == "cdr") {
        t.encoding = Encoding::Cdr;
      } else if (ch.messageEncoding == "ros1") {
        t.encoding = Encoding::Ros1;
      } else {
        other.insert(id);
        continue;
      }
      t.name = ch.topic;
      if (schema) {
        t.type = schema->name;
        t.definition = schema->data;
      }
      if (const auto tally = tallies.find(id); tally != tallies.end()) {
        t.count = tally->second.count;
        if (tally->second.first <= tally->second.last) {
          t.firstNs = static_cast<std::int64_t>(tally->second.first);
          t.lastNs = static_cast<std::int64_t>(tally->second.last);
        }
      }
      index[id] = topics.size();
      topics.push_back(std::move(t));
    }
    topics_ = std::move(topics);
    channelTopic_ = std::move(index);
    otherChannels_ = std::move(other);
  }

  BagError unknownSchema(std::uint64_t offset, std::uint16_t id, const Channel& ch) const {
    return error(offset,
                 "channel " + std::to_string(id) + " names schema " + std::to_string(ch.schemaId) +
                     ", which no Schema record defines",
                 ch.topic);
  }

  // Walks the whole file once, tolerating damage (read() reports it): schemas, channels and each
  // channel's messages, inside chunks too.
  void firstPass() {
    std::map<std::uint16_t, Channel> channels;
    std::map<std::uint16_t, Tally> tallies;
    std::string scratch;
    const auto record = [&](std::uint8_t op, std::string_view content, std::uint64_t at) {
      if (op == kSchema) {
        addSchema(parseSchema(content));
      } else if (op == kChannel) {
        const ChannelRec ch = parseChannel(content);
        channels.try_emplace(ch.id, Channel{ch.schemaId, std::string(ch.topic),
                                            std::string(ch.messageEncoding), at});
      } else if (op == kMessage) {
        const MessageRec m = parseMessage(content);
        tallies[m.channelId].add(m.logTime);
      }
    };
    std::uint64_t at = dataStart_;
    while (dataEnd_ - at >= kPrefix) {
      const std::string_view prefix = window_.ahead(at, kPrefix);
      const auto op = static_cast<std::uint8_t>(prefix[0]);
      const std::uint64_t length = readLe64(prefix.substr(1));
      if (length > dataEnd_ - at - kPrefix) break;  // cut short
      if (op == kDataEnd || op == kFooter) break;
      if ((op == kSchema || op == kChannel || op == kMessage || op == kChunk) &&
          length <= kMaxChunkBytes) {
        try {
          const std::string_view content =
              window_.ahead(at + kPrefix, static_cast<std::size_t>(length));
          if (op == kChunk) {
            const std::string_view records = chunkRecords(at, content, scratch);
            forEachRecord(records, [&](std::uint8_t inner, std::string_view c, std::size_t) {
              record(inner, c, at);
            });
          } else {
            record(op, content, at);
          }
        } catch (const Malformed&) {
        } catch (const BagError&) {
        }
      }
      at += kPrefix + length;
    }
    buildTopics(channels, tallies, /*strict=*/false);
  }

  // ---- chunks and records ----

  // The chunk's records, decompressed into `out` when compressed, its CRC checked.
  std::string_view chunkRecords(std::uint64_t at, std::string_view content, std::string& out) {
    ChunkRec k;
    try {
      k = parseChunk(content);
    } catch (const Malformed& e) {
      throw error(at, std::string("Chunk record: ") + e.what());
    }
    std::string_view records;
    try {
      if (k.compression.empty()) {
        if (k.uncompressedSize != k.records.size()) {
          throw CodecError("an uncompressed chunk of " + std::to_string(k.records.size()) +
                           " bytes that declares " + std::to_string(k.uncompressedSize));
        }
        records = k.records;
      } else {
        if (k.uncompressedSize > kMaxChunkBytes) {
          throw CodecError("an uncompressed size of " + std::to_string(k.uncompressedSize) +
                           " bytes, over the limit of " + std::to_string(kMaxChunkBytes));
        }
        checkPlausible(k);
        const auto size = static_cast<std::size_t>(k.uncompressedSize);
        if (k.compression == "zstd") {
          decompressZstd(k.records, size, out);
        } else if (k.compression == "lz4") {
          decompressLz4Frame(k.records, size, out);
        } else {
          throw error(at, "unknown chunk compression '" + printable(k.compression) +
                              "'; SonarGrid reads zstd, lz4 and none");
        }
        records = out;
      }
    } catch (const CodecError& e) {
      throw error(at, std::string("chunk: ") + e.what());
    }
    if (k.crc != 0) {
      const std::uint32_t crc = crc32(records);
      if (crc != k.crc) {
        throw error(at, "chunk at offset " + std::to_string(at) + ": CRC " + hex(k.crc, 8) +
                            " but its records hash to " + hex(crc, 8));
      }
    }
    return records;
  }

  // The codecs make room for the declared size before decompressing; a few corrupt bytes must
  // not make them allocate up to kMaxChunkBytes. A zstd frame header usually carries its content
  // size; when it is not the declared one (or absent, or there are several frames, or the ratio
  // is over 1024, which only crafted data or long runs of one byte reach) the data are
  // decompressed once into a small buffer, only counting. No LZ4 byte expands to more than 255
  // (a sequence's length byte).
  static void checkPlausible(const ChunkRec& k) {
    if (k.compression == "zstd") {
      const unsigned long long frame = ZSTD_getFrameContentSize(k.records.data(), k.records.size());
      if (frame == ZSTD_CONTENTSIZE_ERROR) {
        throw CodecError("corrupt zstd data (no zstd frame header)");
      }
      if (frame == k.uncompressedSize && k.uncompressedSize / 1024 <= k.records.size()) return;
      // No content size, a wrong one, or several frames: count what they decompress to.
      const std::uint64_t n = frame != ZSTD_CONTENTSIZE_UNKNOWN && frame > k.uncompressedSize
                                  ? frame
                                  : zstdOutputSize(k.records, k.uncompressedSize);
      if (n != k.uncompressedSize) {
        throw CodecError("zstd data decompress to " +
                         std::string(n > k.uncompressedSize ? "more than " : "") +
                         std::to_string(n) + " bytes, not the " +
                         std::to_string(k.uncompressedSize) + " the chunk declares");
      }
    } else if (k.compression == "lz4") {
      if (k.uncompressedSize / 255 > k.records.size() + 64) {
        throw CodecError(std::to_string(k.records.size()) + " bytes of LZ4 data cannot hold the " +
                         std::to_string(k.uncompressedSize) + " bytes the chunk declares");
      }
    }
  }

  // Bytes the zstd frames of `in` decompress to, counted in a 64 KiB buffer; stops once over
  // `limit`.
  static std::uint64_t zstdOutputSize(std::string_view in, std::uint64_t limit) {
    std::unique_ptr<ZSTD_DCtx, decltype(&ZSTD_freeDCtx)> ctx(ZSTD_createDCtx(), &ZSTD_freeDCtx);
    if (!ctx) throw CodecError("cannot create a zstd decompression context");
    std::string buffer(std::size_t{1} << 16, '\0');
    ZSTD_inBuffer input{in.data(), in.size(), 0};
    std::uint64_t total = 0;
    while (true) {
      ZSTD_outBuffer output{buffer.data(), buffer.size(), 0};
      const std::size_t hint = ZSTD_decompressStream(ctx.get(), &output, &input);
      if (ZSTD_isError(hint)) {
        throw CodecError(std::string("corrupt zstd data (") + ZSTD_getErrorName(hint) + ")");
      }
      total += output.pos;
      if (total > limit) return total;
      if (hint == 0 && input.pos == input.size) return total;  // the last frame ended
      if (output.pos == 0 && input.pos == input.size) {
        throw CodecError("zstd data cut short after " + std::to_string(in.size()) + " bytes");
      }
    }
  }

  static std::string printable(std::string_view s) {
    std::string out;
    for (const char ch : s.substr(0, 64)) {
      const auto u = static_cast<unsigned char>(ch);
      out += (u >= 0x20 && u < 0x7F) ? std::string(1, ch) : hex(u, 2);
    }
    return s.size() > 64 ? out + "..." : out;
  }

  // f(opcode, content, position in `records`) for each record; Malformed when one runs past the
  // end.
  template <class F>
  static void forEachRecord(std::string_view records, F&& f) {
    std::size_t p = 0;
    while (p < records.size()) {
      if (records.size() - p < kPrefix) {
        throw Malformed("a record at byte " + std::to_string(p) +
                        " of the chunk's records is cut short");
      }
      const auto op = static_cast<std::uint8_t>(records[p]);
      const std::uint64_t length = readLe64(records.substr(p + 1, 8));
      if (length > records.size() - p - kPrefix) {
        throw Malformed("a record at byte " + std::to_string(p) + " of the chunk's records (" +
                        std::to_string(records.size()) + " bytes) declares " +
                        std::to_string(length) + " bytes, past their end");
      }
      f(op, records.substr(p + kPrefix, static_cast<std::size_t>(length)), p);
      p += static_cast<std::size_t>(kPrefix + length);
    }
  }

  // One record met by read(): a message is visited when its channel is wanted; a channel's schema
  // is checked. `at` is the record's offset, or its chunk's.
  void visitRecord(Pass& pass, std::uint8_t op, std::string_view content, std::uint64_t at,
                   const char* where) {
    try {
      if (op == kMessage) {
        const MessageRec m = parseMessage(content);
        const auto it = channelTopic_.find(m.channelId);
        if (it == channelTopic_.end()) {
          if (otherChannels_.count(m.channelId) != 0) return;
          problem(error(at, std::string(where) + "a message on channel " +
                                std::to_string(m.channelId) + ", which no Channel record defines"),
                  pass.options);
          return;
        }
        if (it->second >= pass.wanted.size() || !pass.wanted[it->second]) return;
        Message msg;
        msg.topic = it->second;
        msg.logTimeNs = static_cast<std::int64_t>(m.logTime);
        msg.data = m.data;
        msg.offset = at;
        pass.visit(msg);
      } else if (op == kChannel) {
        const ChannelRec ch = parseChannel(content);
        if (ch.schemaId != 0 && schemas_.count(ch.schemaId) == 0) {
          problem(unknownSchema(at, ch.id, Channel{ch.schemaId, std::string(ch.topic), {}, at}),
                  pass.options);
        }
      } else if (op == kSchema) {
        parseSchema(content);
      }
    } catch (const Malformed& e) {
      problem(error(at, std::string(where) + e.what()), pass.options);
    }
  }

  void visitChunk(Pass& pass, std::uint64_t at, std::string_view content) {
    std::string_view records;
    try {
      records = chunkRecords(at, content, chunk_);
    } catch (const BagError& e) {
      problem(e, pass.options);
      return;
    }
    try {
      forEachRecord(records, [&](std::uint8_t op, std::string_view c, std::size_t p) {
        const std::string where = "in the chunk, the record at byte " + std::to_string(p) + ": ";
        visitRecord(pass, op, c, at, where.c_str());
      });
    } catch (const Malformed& e) {
      problem(error(at, std::string("chunk: ") + e.what()), pass.options);
    }
  }

  void readIndexed(Pass& pass) {
    for (const ChunkIndexRec& k : chunks_) {
      const bool needed =
          k.channels.empty() || std::any_of(k.channels.begin(), k.channels.end(), [&](auto id) {
            const auto it = channelTopic_.find(id);
            if (it == channelTopic_.end()) {
              return otherChannels_.count(id) == 0;  // unknown: read to report it
            }
            return it->second < pass.wanted.size() && pass.wanted[it->second];
          });
      if (!needed) continue;
      if (k.chunkLength - kPrefix > kMaxChunkBytes) {
        problem(
            error(k.chunkOffset, "a Chunk record of " + std::to_string(k.chunkLength) +
                                     " bytes, over the limit of " + std::to_string(kMaxChunkBytes)),
            pass.options);
      } else {
        // The whole record in one read; the index gave its length.
        const std::string_view record =
            window_.fetch(k.chunkOffset, static_cast<std::size_t>(k.chunkLength));
        if (static_cast<std::uint8_t>(record[0]) != kChunk ||
            readLe64(record.substr(1, 8)) != k.chunkLength - kPrefix) {
          problem(
              error(k.chunkOffset, "the chunk index points at a record that is not a Chunk of " +
                                       std::to_string(k.chunkLength) + " bytes"),
              pass.options);
        } else {
          visitChunk(pass, k.chunkOffset, record.substr(kPrefix));
        }
      }
      step(pass, k.chunkOffset + k.chunkLength);
    }
  }

  // read() without chunk indexes: every record of [begin, end) in order.
  void walk(std::uint64_t begin, std::uint64_t end, Pass* pass) {
    std::uint64_t at = begin;
    while (at < end) {
      if (end - at < kPrefix) {
        problem(error(at, "the file ends " + std::to_string(end - at) +
                              " bytes into a record's opcode and length (cut short?)"),
                pass->options);
        return;
      }
      const std::string_view prefix = window_.ahead(at, kPrefix);
      const auto op = static_cast<std::uint8_t>(prefix[0]);
      const std::uint64_t length = readLe64(prefix.substr(1));
      if (length > end - at - kPrefix) {
        problem(error(at, recordName(op) + " of " + std::to_string(length) +
                              " bytes runs past the end of the file, which has " +
                              std::to_string(end - at - kPrefix) +
                              " bytes left after its opcode and length (cut short?)"),
                pass->options);
        return;
      }
      if (op == kDataEnd || op == kFooter) return;
      if (op == kSchema || op == kChannel || op == kMessage || op == kChunk) {
        if (length > kMaxChunkBytes) {
          problem(error(at, recordName(op) + " of " + std::to_string(length) +
                                " bytes, over the limit of " + std::to_string(kMaxChunkBytes)),
                  pass->options);
        } else {
          const std::string_view content =
              window_.ahead(at + kPrefix, static_cast<std::size_t>(length));
          if (op == kChunk) {
            visitChunk(*pass, at, content);
          } else {
            visitRecord(*pass, op, content, at, "");
          }
        }
      }
      at += kPrefix + length;
      if (op == kChunk || at - pass->reported >= kProgressEvery) step(*pass, at);
    }
  }

  std::unique_ptr<ByteSource> src_;
  std::string name_;
  std::uint64_t size_ = 0;
  Window window_;
  std::uint64_t dataStart_ = 0, dataEnd_ = 0;
  std::uint64_t footerAt_ = 0, summaryOffsetStart_ = 0;
  std::uint32_t summaryCrc_ = 0;
  bool indexed_ = false;
  std::vector<ChunkIndexRec> chunks_;
  std::map<std::uint16_t, Schema> schemas_;
  std::map<std::uint16_t, std::size_t> channelTopic_;
  std::set<std::uint16_t> otherChannels_;
  std::vector<Topic> topics_;
  std::vector<BagError> deferred_;
  Skipped skipped_;
  std::string chunk_;  // the decompressed chunk being visited
};

}  // namespace

std::unique_ptr<Reader> openMcap(std::unique_ptr<ByteSource> source) {
  return std::make_unique<McapReader>(std::move(source));
}

}  // namespace sg::bag
