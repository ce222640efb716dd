// SPDX-License-Identifier: BSD-3-Clause
// ROS 1 bag format 2.0, from the format page (http://wiki.ros.org/Bags/Format/2.0).
//
// What this reader does where the format leaves a choice:
// - The index is used when the bag header's index_pos lies between the first record and the end
//   of the file, the bag has chunks (chunk_count > 0), and the records from index_pos on are
//   connection and chunk info records that agree with the bag header (conn_count, chunk_count,
//   chunk positions before index_pos, connections of every chunk info declared). Then only the
//   chunk infos say which chunks hold which connections: read() visits those that hold a wanted
//   one. Message records outside chunks are not indexed by chunk infos and are not read then.
//   An uncompressed chunk that also holds unwanted connections (a camera's images beside the
//   sonar) is not read whole: the index data records after it give each wanted message's offset
//   in it, and only those records are read (in stored order). When they do not read or disagree
//   with the chunk info, the whole chunk is read instead. Compressed chunks are read whole.
// - Otherwise (index_pos 0 as a recording cut short leaves it, an index_pos past the end, an index
//   that does not parse or agree, a bag without chunks) the constructor walks the records from the
//   start once and collects the connections in the order they are declared, with their message
//   counts and first and last log times. A chunk's connections, counts and times come from the
//   index data records the writers put after each chunk they finish; a chunk is decompressed on
//   that walk only when those are missing or name a connection not yet declared (connection
//   records are inside the chunk of a connection's first message). read() then decompresses only
//   the chunks that hold a wanted connection (and those the walk could not account for). The
//   walk passes over bad chunks and stops at the first record whose framing is broken (a file
//   cut short); read() reports them (strict) or counts them (lenient). A chunk header with both
//   sizes 0 (one the writer had not finished) is an empty chunk; the records after it, if
//   stored as is, are read as records outside chunks.
// - Topic counts come from the chunk infos; first and last log times from the chunk infos'
//   start and end times, made exact with the index data records after the chunks that hold a
//   topic's earliest and latest messages (a few small reads; the bounds stay when those records
//   do not read).
// - Connections with the same topic name and type (several publishers on one topic) are one
//   Topic; its count is their sum.
// - Records of unknown op codes are passed over.

#include "sonargrid/io/bag/rosbag1.h"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <type_traits>
#include <utility>

#include "sonargrid/io/bag/codecs.h"
#include "sonargrid/io/bag/rosbag1_records.h"
#include "sonargrid/io/log_options.h"

namespace sg::bag {
namespace {

using namespace rosbag1_records;  // NOLINT: the records of this file, split into rosbag1_records.h

// How a pass over the records treats what it finds.
struct Pass {
  bool scanning = false;  // the constructor's walk of a bag without index: collect, never throw
  bool lenient = false;
  const std::vector<bool>* wanted = nullptr;
  const std::function<void(const Message&)>* visit = nullptr;
};

class Ros1Reader final : public Reader {
 public:
  explicit Ros1Reader(std::unique_ptr<ByteSource> source)
      : src_(std::move(source)), size_(src_->size()) {
    checkVersionLine();
    std::uint32_t connCount = 0, chunkCount = 0;
    readBagHeader(connCount, chunkCount);
    if (indexPos_ >= dataStart_ && indexPos_ < size_ && chunkCount > 0) {
      indexed_ = readIndex(connCount, chunkCount);
    }
    if (!indexed_) {
      Pass scan;
      scan.scanning = true;
      walkFile(scan, nullptr);
    }
  }

  const std::vector<Topic>& topics() const override { return topics_; }
  const Skipped& skipped() const override { return skipped_; }

  void read(const std::vector<bool>& wanted, const ReadOptions& options,
            const std::function<void(const Message&)>& visit) override {
    skipped_ = {};
    Pass pass;
    pass.lenient = options.lenient;
    pass.wanted = &wanted;
    pass.visit = &visit;
    if (!indexed_) {
      walkFile(pass, &options);
      return;
    }
    for (std::size_t i = 0; i < chunks_.size(); ++i) {
      const ChunkRef& c = chunks_[i];
      if (anyWanted(c.counts, wanted)) {
        FileRecord r;
        std::string_view body;
        bool loaded = false;
        try {
          readRecord(c.pos, r);
          const Fields f = fields(r);
          const std::uint8_t op = atRecord(r.offset, [&] { return f.u8("op"); });
          if (op != kChunk) {
            throw BagError(file(), c.pos, "",
                           "the index has a chunk here, but the record is op " + hex(op));
          }
          // An uncompressed chunk that also holds other topics (a camera's): only the wanted
          // messages are read, where the index data records after it put them.
          if (allWanted(c.counts, wanted) || !readWantedOnly(r, f, c, pass)) {
            body = loadChunk(r, f);
            loaded = true;
          }
        } catch (const BagError& e) {
          recordError(pass, e);
        }
        if (loaded) walkChunk(body, c.pos, pass, nullptr);
      }
      step(options, i + 1 < chunks_.size() ? chunks_[i + 1].pos : size_);
    }
  }

 private:
  const std::string& file() const { return src_->name(); }

  // Runs `f`, making a Malformed it throws a BagError at `offset`.
  template <class F>
  std::invoke_result_t<F&> atRecord(std::uint64_t offset, F&& f) const {
    try {
      return f();
    } catch (const Malformed& m) {
      throw BagError(file(), offset, "", m.message);
    }
  }

  BagError cutShort(std::uint64_t offset, std::uint64_t need) const {
    return BagError(file(), offset, "",
                    "the file is cut short: file ends at byte " + std::to_string(size_) + ", " +
                        std::to_string(offset + need - size_) + " bytes short of the record");
  }

  // Frames the record at `offset`: reads its header, checks that its data lie inside the file.
  void readRecord(std::uint64_t offset, FileRecord& r) {
    r.offset = offset;
    if (offset > size_ || size_ - offset < 4) throw cutShort(offset, 4);
    src_->read(offset, 4, scratch_);
    const std::uint32_t headerLen = le32(scratch_.data());
    if (headerLen > kMaxHeaderBytes) {
      throw BagError(file(), offset, "",
                     "a record header of " + std::to_string(headerLen) +
                         " bytes (SonarGrid reads headers of up to " +
                         std::to_string(kMaxHeaderBytes) + " bytes)");
    }
    if (size_ - offset < std::uint64_t{8} + headerLen) throw cutShort(offset, 8 + headerLen);
    src_->read(offset + 4, headerLen, r.header);
    src_->read(offset + 4 + headerLen, 4, scratch_);
    r.dataLen = le32(scratch_.data());
    r.dataPos = offset + 8 + headerLen;
    if (size_ - r.dataPos < r.dataLen) {
      throw cutShort(offset, std::uint64_t{8} + headerLen + r.dataLen);
    }
    r.end = r.dataPos + r.dataLen;
  }

  Fields fields(const FileRecord& r) const {
    return atRecord(r.offset, [&] { return Fields(r.header); });
  }

  void readData(const FileRecord& r, std::uint64_t limit, std::string& out) {
    if (r.dataLen > limit) {
      throw BagError(file(), r.offset, "",
                     "a record with " + std::to_string(r.dataLen) +
                         " bytes of data (SonarGrid reads up to " + std::to_string(limit) +
                         " bytes there)");
    }
    src_->read(r.dataPos, r.dataLen, out);
  }

  void checkVersionLine() {
    std::string head;
    src_->read(0, static_cast<std::size_t>(std::min<std::uint64_t>(size_, kVersionLine.size())),
               head);
    if (head == kVersionLine) return;
    if (head.starts_with("#ROSBAG V")) {
      std::string version = head.substr(9);
      if (const std::size_t nl = version.find('\n'); nl != std::string::npos) version.resize(nl);
      throw BagError(
          file(), 0, "",
          "ROS bag format " + printable(version) + " is not supported; SonarGrid reads format 2.0");
    }
    throw BagError(file(), 0, "", "not a ROS 1 bag: the file does not start with \"#ROSBAG V2.0\"");
  }

  void readBagHeader(std::uint32_t& connCount, std::uint32_t& chunkCount) {
    FileRecord r;
    readRecord(kBagHeaderPos, r);
    const Fields f = fields(r);
    atRecord(r.offset, [&] {
      const std::uint8_t op = f.u8("op");
      if (op != kBagHeader) {
        throw Malformed{"the first record is op " + hex(op) + ", not the bag header (0x03)"};
      }
      if (const auto enc = f.find("encryptor"); enc && !enc->empty()) {
        throw Malformed{"the bag is encrypted (encryptor '" + printable(*enc) +
                        "'); SonarGrid reads bags without encryption"};
      }
      indexPos_ = f.u64("index_pos");
      connCount = f.u32("conn_count");
      chunkCount = f.u32("chunk_count");
      return 0;
    });
    dataStart_ = r.end;
  }

  // A connection record: header fields conn and topic, data a connection header (type,
  // message_definition, md5sum...). Declares the connection when it is new and `declare` is set.
  void connection(const Fields& header, std::string_view data, bool declare) {
    const std::uint32_t conn = header.u32("conn");
    const std::string_view topic = header.bytes("topic");
    const Fields d(data);
    const std::string_view type = d.bytes("type");
    const std::string_view definition = d.find("message_definition").value_or("");
    if (!declare || topicOf_.count(conn) != 0) return;
    for (std::size_t i = 0; i < topics_.size(); ++i) {
      if (topics_[i].name == topic && topics_[i].type == type) {
        topicOf_[conn] = i;
        return;
      }
    }
    Topic t;
    t.name = std::string(topic);
    t.type = std::string(type);
    t.encoding = Encoding::Ros1;
    t.definition = std::string(definition);
    topics_.push_back(std::move(t));
    topicOf_[conn] = topics_.size() - 1;
  }

  // The index from index_pos on: connection and chunk info records. False (and nothing kept)
  // when it is not there or does not agree with the bag header; the file is then walked.
  bool readIndex(std::uint32_t connCount, std::uint32_t chunkCount) {
    try {
      std::size_t connections = 0;
      for (std::uint64_t pos = indexPos_; pos < size_;) {
        FileRecord r;
        readRecord(pos, r);
        const Fields f = fields(r);
        const std::uint8_t op = atRecord(pos, [&] { return f.u8("op"); });
        if (op == kConnection) {
          readData(r, kMaxHeaderBytes, data_);
          atRecord(pos, [&] {
            connection(f, data_, true);
            return 0;
          });
          ++connections;
        } else if (op == kChunkInfo) {
          readData(r, kMaxChunkBytes, data_);
          chunks_.push_back(atRecord(pos, [&] { return chunkInfo(f, data_); }));
        } else {
          return dropIndex();
        }
        pos = r.end;
      }
      if (connections != connCount || chunks_.size() != chunkCount) return dropIndex();
      std::sort(chunks_.begin(), chunks_.end(),
                [](const ChunkRef& a, const ChunkRef& b) { return a.pos < b.pos; });
      for (std::size_t i = 0; i < chunks_.size(); ++i) {
        const ChunkRef& c = chunks_[i];
        if (c.pos < dataStart_ || c.pos >= indexPos_) return dropIndex();
        if (i > 0 && c.pos == chunks_[i - 1].pos) return dropIndex();
        for (const auto& [conn, count] : c.counts) {
          const auto it = topicOf_.find(conn);
          if (it == topicOf_.end()) return dropIndex();
          topics_[it->second].count += count;
        }
      }
    } catch (const BagError&) {
      return dropIndex();
    }
    refineTimes();
    return true;
  }

  bool dropIndex() {
    topics_.clear();
    topicOf_.clear();
    chunks_.clear();
    return false;
  }

  static ChunkRef chunkInfo(const Fields& f, std::string_view data) {
    const std::uint32_t ver = f.u32("ver");
    if (ver != 1) throw Malformed{"chunk info version " + std::to_string(ver) + ", not 1"};
    ChunkRef c;
    c.pos = f.u64("chunk_pos");
    c.startNs = f.time("start_time");
    c.endNs = f.time("end_time");
    const std::uint32_t count = f.u32("count");
    if (data.size() != std::uint64_t{count} * 8) {
      throw Malformed{"chunk info with " + std::to_string(count) + " connections has " +
                      std::to_string(data.size()) + " bytes of data, not " +
                      std::to_string(std::uint64_t{count} * 8)};
    }
    for (std::uint32_t i = 0; i < count; ++i) {
      c.counts.emplace_back(le32(data.data() + 8 * i), le32(data.data() + 8 * i + 4));
    }
    return c;
  }

  // An index data record (version 1: `count` entries of time and offset, 12 bytes each).
  struct IndexData {
    std::uint32_t conn = 0, count = 0;
    std::uint64_t end = 0;  // where the next record starts
  };

  // The index data record at `pos`, its entries read into data_; nothing when the record there is
  // of another op. Throws BagError or Malformed for one that does not read or agree with its count.
  std::optional<IndexData> indexDataAt(std::uint64_t pos) {
    FileRecord r;
    readRecord(pos, r);
    const Fields f = fields(r);
    if (f.u8("op") != kIndexData) return std::nullopt;
    const IndexData d{f.u32("conn"), f.u32("count"), r.end};
    if (f.u32("ver") != 1 || r.dataLen != std::uint64_t{d.count} * 12)
      throw Malformed{"an index data record whose version or size does not fit"};
    readData(r, kMaxChunkBytes, data_);
    return d;
  }

  // Each connection's earliest and latest log time in chunk `c`, from the index data records that
  // follow it; nothing when they do not read.
  std::optional<std::map<std::uint32_t, std::pair<std::int64_t, std::int64_t>>> chunkTimes(
      const ChunkRef& c) {
    std::map<std::uint32_t, std::pair<std::int64_t, std::int64_t>> out;
    try {
      FileRecord r;
      readRecord(c.pos, r);
      if (fields(r).u8("op") != kChunk) return std::nullopt;
      std::uint64_t pos = r.end;
      for (std::size_t k = 0; k < c.counts.size() && pos < indexPos_; ++k) {
        const std::optional<IndexData> d = indexDataAt(pos);
        if (!d) break;
        for (std::uint64_t e = 0; e < d->count; ++e) {
          const std::int64_t t = timeNs(data_.data() + 12 * e);
          const auto [it, fresh] = out.try_emplace(d->conn, t, t);
          if (!fresh) {
            it->second.first = std::min(it->second.first, t);
            it->second.second = std::max(it->second.second, t);
          }
        }
        pos = d->end;
      }
    } catch (const BagError&) {
      return std::nullopt;
    } catch (const Malformed&) {
      return std::nullopt;
    }
    return out;
  }

  // Topic first and last times: the chunk infos bound them; the index data records of the chunks
  // that may hold the earliest (latest) message make them exact.
  void refineTimes() {
    std::map<std::size_t,
             std::optional<std::map<std::uint32_t, std::pair<std::int64_t, std::int64_t>>>>
        cache;
    auto timesOf = [&](std::size_t ci) -> const auto& {
      auto it = cache.find(ci);
      if (it == cache.end()) it = cache.emplace(ci, chunkTimes(chunks_[ci])).first;
      return it->second;
    };
    // The chunks that hold each topic, in file order.
    std::vector<std::vector<std::size_t>> holdingOf(topics_.size());
    for (std::size_t ci = 0; ci < chunks_.size(); ++ci) {
      for (const auto& [conn, count] : chunks_[ci].counts) {
        std::vector<std::size_t>& h = holdingOf[topicOf_.at(conn)];
        if (count > 0 && (h.empty() || h.back() != ci)) h.push_back(ci);
      }
    }
    for (std::size_t ti = 0; ti < topics_.size(); ++ti) {
      std::vector<std::size_t>& holding = holdingOf[ti];
      if (holding.empty()) continue;
      // The exact time of topic `ti` in chunk `ci`, earliest or latest, or the chunk's bound.
      auto exact = [&](std::size_t ci, bool earliest) {
        std::int64_t bound = earliest ? chunks_[ci].startNs : chunks_[ci].endNs;
        const auto& times = timesOf(ci);
        if (!times) return bound;
        std::optional<std::int64_t> best;
        for (const auto& [conn, range] : *times) {
          const auto it = topicOf_.find(conn);
          if (it == topicOf_.end() || it->second != ti) continue;
          const std::int64_t t = earliest ? range.first : range.second;
          if (!best || (earliest ? t < *best : t > *best)) best = t;
        }
        return best.value_or(bound);
      };
      std::stable_sort(holding.begin(), holding.end(), [&](std::size_t a, std::size_t b) {
        return chunks_[a].startNs < chunks_[b].startNs;
      });
      std::int64_t first = std::numeric_limits<std::int64_t>::max();
      for (const std::size_t ci : holding) {
        if (chunks_[ci].startNs >= first) break;  // nothing earlier there
        first = std::min(first, exact(ci, true));
      }
      std::stable_sort(holding.begin(), holding.end(), [&](std::size_t a, std::size_t b) {
        return chunks_[a].endNs > chunks_[b].endNs;
      });
      std::int64_t last = std::numeric_limits<std::int64_t>::min();
      for (const std::size_t ci : holding) {
        if (chunks_[ci].endNs <= last) break;  // nothing later there
        last = std::max(last, exact(ci, false));
      }
      topics_[ti].firstNs = first;
      topics_[ti].lastNs = last;
    }
  }

  // The uncompressed records of the chunk record `r` (in `chunk_`).
  std::string_view loadChunk(const FileRecord& r, const Fields& f) {
    std::string_view compression;
    std::uint32_t size = 0;
    atRecord(r.offset, [&] {
      compression = f.bytes("compression");
      size = f.u32("size");
      return 0;
    });
    auto fail = [&](const std::string& message) { return BagError(file(), r.offset, "", message); };
    const bool none = compression == "none", bz2 = compression == "bz2";
    if (!none && !bz2 && compression != "lz4") {
      throw fail("unknown chunk compression '" + printable(compression) +
                 "'; SonarGrid reads none, bz2 and lz4");
    }
    if (size == 0 && r.dataLen == 0) {
      // The header a writer puts before a chunk it has not finished (its sizes come at the end):
      // the records that follow, if any, are read at the top level.
      chunk_.clear();
      return chunk_;
    }
    if (size > kMaxChunkBytes) {
      throw fail("the chunk declares " + std::to_string(size) +
                 " uncompressed bytes, over the limit of " + std::to_string(kMaxChunkBytes));
    }
    if (none) {
      if (r.dataLen != size) {
        throw fail("an uncompressed chunk of " + std::to_string(r.dataLen) +
                   " bytes declares a size of " + std::to_string(size));
      }
      readData(r, kMaxChunkBytes, chunk_);
      return chunk_;
    }
    if (!bz2 && size > std::uint64_t{r.dataLen} * kMaxLz4Ratio + 1024) {
      throw fail("an lz4 chunk of " + std::to_string(r.dataLen) + " bytes cannot hold the " +
                 std::to_string(size) + " bytes it declares");
    }
    readData(r, kMaxStoredChunkBytes, stored_);
    try {
      if (bz2) {
        decompressBz2(stored_, size, chunk_);
      } else {
        decompressLz4Frame(stored_, size, chunk_);
      }
    } catch (const CodecError& e) {
      throw fail(std::string("the ") + (bz2 ? "bz2" : "lz4") + " chunk does not decompress to " +
                 std::to_string(size) + " bytes: " + e.what());
    }
    return chunk_;
  }

  BagError chunkError(std::uint64_t chunkPos, std::size_t at, const std::string& topic,
                      const std::string& message) const {
    return BagError(file(), chunkPos, topic,
                    "chunk at offset " + std::to_string(chunkPos) + ", record at byte " +
                        std::to_string(at) + " of the chunk: " + message);
  }

  // A bad record or chunk: thrown in a strict read, counted in a lenient one, passed over by the
  // constructor's walk.
  void recordError(const Pass& pass, const BagError& e) {
    if (pass.scanning) return;
    if (!pass.lenient) throw e;
    if (skipped_.count++ == 0) skipped_.firstError = e.what();
  }

  bool allWanted(const std::vector<std::pair<std::uint32_t, std::uint32_t>>& counts,
                 const std::vector<bool>& wanted) const {
    return std::all_of(counts.begin(), counts.end(), [&](const auto& c) {
      const auto it = topicOf_.find(c.first);
      return it != topicOf_.end() && it->second < wanted.size() && wanted[it->second];
    });
  }

  // Reads the wanted messages of the uncompressed chunk record `r` from the file, at the offsets
  // the index data records after it give (in stored order, as a walk of the chunk visits them;
  // each run of them that no other message interrupts in one read). False, having visited nothing,
  // when the chunk is compressed or its index data records do not read or disagree with the chunk
  // info's counts: the caller then reads the whole chunk. A message record that is not where its
  // index puts it is an error of the chunk.
  bool readWantedOnly(const FileRecord& r, const Fields& f, const ChunkRef& c, const Pass& pass) {
    std::uint32_t size = 0;
    try {
      if (f.bytes("compression") != "none") return false;
      size = f.u32("size");
    } catch (const Malformed&) {
      return false;
    }
    if (size != r.dataLen || size > kMaxChunkBytes) return false;
    // (offset in the chunk, topic) of each wanted message, and where every indexed message starts.
    std::vector<std::pair<std::uint32_t, std::size_t>> wanted;
    std::vector<std::uint32_t> starts;
    try {
      std::uint64_t pos = r.end;
      std::size_t records = 0;
      for (; records < c.counts.size() && pos < size_; ++records) {
        const std::optional<IndexData> d = indexDataAt(pos);
        if (!d) break;
        const auto declared = std::find(c.counts.begin(), c.counts.end(),
                                        std::pair<std::uint32_t, std::uint32_t>(d->conn, d->count));
        if (declared == c.counts.end()) return false;  // not what the chunk info says
        const auto it = topicOf_.find(d->conn);
        const bool want = it != topicOf_.end() && isWanted(pass, it->second);
        for (std::uint32_t e = 0; e < d->count; ++e) {
          const std::uint32_t offset = le32(data_.data() + std::size_t{12} * e + 8);
          starts.push_back(offset);
          if (want) wanted.emplace_back(offset, it->second);
        }
        pos = d->end;
      }
      if (records != c.counts.size()) return false;
    } catch (const BagError&) {
      return false;
    } catch (const Malformed&) {
      return false;
    }
    std::sort(wanted.begin(), wanted.end());
    std::sort(starts.begin(), starts.end());
    // Runs of wanted records with no other indexed record between them, each read at once: a
    // record ends at the next indexed record's start (or the chunk's end) at the latest.
    auto boundOf = [&](std::uint32_t offset) -> std::uint32_t {
      const auto next = std::upper_bound(starts.begin(), starts.end(), offset);
      return next == starts.end() ? size : std::min(*next, size);
    };
    for (std::size_t i = 0; i < wanted.size();) {
      const std::uint32_t first = wanted[i].first;
      std::size_t j = i + 1;
      std::uint32_t end = boundOf(first);
      while (j < wanted.size() && wanted[j].first == end && end < size) {
        end = boundOf(wanted[j].first);
        ++j;
      }
      if (first >= size) {
        for (; i < j; ++i)
          recordError(pass, chunkError(c.pos, wanted[i].first, topics_[wanted[i].second].name,
                                       "the index puts a message past the chunk's end"));
        continue;
      }
      src_->read(r.dataPos + first, end - first, chunk_);
      for (; i < j; ++i) {
        const auto [offset, topic] = wanted[i];
        std::optional<Message> message;
        try {
          const ChunkRecord rec = chunkRecordAt(chunk_, offset - first);
          const Fields h(rec.header);
          if (h.u8("op") != kMessageData || topicOf_.find(h.u32("conn")) == topicOf_.end() ||
              topicOf_.at(h.u32("conn")) != topic)
            throw Malformed{"the index puts a message of " + topics_[topic].name +
                            " here, but the record is not one"};
          message = Message{topic, h.time("time"), rec.data, c.pos};
        } catch (const Malformed& m) {
          recordError(pass, chunkError(c.pos, offset, topics_[topic].name, m.message));
        }
        if (message) (*pass.visit)(*message);
      }
    }
    return true;
  }

  // Whether a chunk with these (connection, count) pairs may hold a wanted topic: a connection
  // no record declares may be any (the read reports its messages).
  bool anyWanted(const std::vector<std::pair<std::uint32_t, std::uint32_t>>& counts,
                 const std::vector<bool>& wanted) const {
    for (const auto& c : counts) {
      const auto it = topicOf_.find(c.first);
      if (it == topicOf_.end()) return true;
      if (it->second < wanted.size() && wanted[it->second]) return true;
    }
    return false;
  }

  bool allDeclared(const std::vector<std::pair<std::uint32_t, std::uint32_t>>& counts) const {
    return std::all_of(counts.begin(), counts.end(),
                       [&](const auto& c) { return topicOf_.count(c.first) != 0; });
  }

  // The index data records right after the chunk record `chunk` (a bag without index has them
  // after every chunk the writer finished): its connections with their message counts, and each
  // message's (connection, log time). False when there are none, one does not parse, or no
  // record follows them (the file may end inside them, or before the last of them).
  bool indexAfter(const FileRecord& chunk,
                  std::vector<std::pair<std::uint32_t, std::uint32_t>>& counts,
                  std::vector<std::pair<std::uint32_t, std::int64_t>>& times) {
    try {
      std::uint64_t pos = chunk.end;
      while (pos < size_) {
        const std::optional<IndexData> d = indexDataAt(pos);
        if (!d) break;
        counts.emplace_back(d->conn, d->count);
        for (std::uint32_t e = 0; e < d->count; ++e) {
          times.emplace_back(d->conn, timeNs(data_.data() + std::size_t{12} * e));
        }
        pos = d->end;
      }
      if (counts.empty() || pos >= size_) return false;
      FileRecord next;
      readRecord(pos, next);
      return true;
    } catch (const BagError&) {
    } catch (const Malformed&) {
    }
    return false;
  }

  static bool isWanted(const Pass& pass, std::size_t topic) {
    return pass.wanted != nullptr && topic < pass.wanted->size() && (*pass.wanted)[topic];
  }

  // A message of topic `t` at `timeNs` seen by the constructor's walk.
  void count(std::size_t t, std::int64_t time) {
    Topic& topic = topics_[t];
    if (topic.count == 0 || time < topic.firstNs) topic.firstNs = time;
    if (topic.count == 0 || time > topic.lastNs) topic.lastNs = time;
    ++topic.count;
  }

  // The records of one decompressed chunk, in stored order. `seen` (the constructor's walk)
  // collects the connections of its messages.
  void walkChunk(std::string_view body, std::uint64_t chunkPos, const Pass& pass, ChunkRef* seen) {
    for (std::size_t pos = 0; pos < body.size();) {
      ChunkRecord rec;
      try {
        rec = chunkRecordAt(body, pos);
      } catch (const Malformed& m) {
        // The rest of the chunk cannot be framed.
        recordError(pass, chunkError(chunkPos, pos, "", m.message));
        if (seen != nullptr) seen->pos = 0;  // not complete: read() reads it again
        return;
      }
      std::string topic;
      std::optional<Message> message;
      try {
        const Fields f(rec.header);
        const std::uint8_t op = f.u8("op");
        if (op == kConnection) {
          topic = std::string(f.find("topic").value_or(""));
          connection(f, rec.data, pass.scanning);
        } else if (op == kMessageData) {
          const std::uint32_t conn = f.u32("conn");
          const auto it = topicOf_.find(conn);
          if (it == topicOf_.end()) {
            throw Malformed{"a message on connection " + std::to_string(conn) +
                            ", which no connection record declares"};
          }
          topic = topics_[it->second].name;
          const std::int64_t time = f.time("time");
          if (seen != nullptr) {
            count(it->second, time);
            const auto c = std::find_if(seen->counts.begin(), seen->counts.end(),
                                        [&](const auto& p) { return p.first == conn; });
            if (c == seen->counts.end()) {
              seen->counts.emplace_back(conn, 1);
            } else {
              ++c->second;
            }
          } else if (isWanted(pass, it->second)) {
            message = Message{it->second, time, rec.data, chunkPos};
          }
        }
      } catch (const Malformed& m) {
        recordError(pass, chunkError(chunkPos, pos, topic, m.message));
        if (seen != nullptr) seen->pos = 0;
      }
      if (message) (*pass.visit)(*message);
      pos = rec.end;
    }
  }

  // Progress and cancel after a chunk; `done` is where the next chunk starts.
  void step(const ReadOptions& options, std::uint64_t done) const {
    if (options.progress) options.progress(done, size_);
    if (options.cancel != nullptr && options.cancel->load()) throw sg::LoadCancelled(file());
  }

  // Every record from the first after the bag header to the end of the file: the read of a bag
  // without index, or (pass.scanning) the constructor's walk that collects its connections.
  void walkFile(const Pass& pass, const ReadOptions* options) {
    std::uint64_t reported = dataStart_;
    for (std::uint64_t pos = dataStart_; pos < size_;) {
      FileRecord r;
      try {
        readRecord(pos, r);
      } catch (const BagError& e) {
        recordError(pass, e);  // the records cannot be framed past here (a file cut short)
        return;
      }
      bool chunk = false, loaded = false;
      std::string_view body;
      std::optional<Message> message;
      try {
        const Fields f = fields(r);
        const std::uint8_t op = atRecord(pos, [&] { return f.u8("op"); });
        if (op == kChunk) {
          chunk = true;
          if (pass.scanning) {
            // The index data records after the chunk tell its connections, counts and times;
            // it is decompressed only when they are not there or name a connection not yet
            // declared (declared inside this chunk, then).
            std::vector<std::pair<std::uint32_t, std::uint32_t>> counts;
            std::vector<std::pair<std::uint32_t, std::int64_t>> times;
            if (indexAfter(r, counts, times) && allDeclared(counts)) {
              for (const auto& [conn, time] : times) count(topicOf_.at(conn), time);
              scannedChunks_[pos] = std::move(counts);
            } else {
              body = loadChunk(r, f);
              loaded = true;
            }
          } else if (const auto known = scannedChunks_.find(pos);
                     known == scannedChunks_.end() || anyWanted(known->second, *pass.wanted)) {
            body = loadChunk(r, f);
            loaded = true;
          }
        } else if (op == kConnection) {
          readData(r, kMaxHeaderBytes, data_);
          atRecord(pos, [&] {
            connection(f, data_, pass.scanning);
            return 0;
          });
        } else if (op == kMessageData) {
          std::string topic;
          std::size_t t = 0;
          const std::int64_t time = atRecord(pos, [&] {
            const std::uint32_t conn = f.u32("conn");
            const auto it = topicOf_.find(conn);
            if (it == topicOf_.end()) {
              throw Malformed{"a message on connection " + std::to_string(conn) +
                              ", which no connection record declares"};
            }
            t = it->second;
            topic = topics_[t].name;
            return f.time("time");
          });
          if (pass.scanning) {
            count(t, time);
          } else if (isWanted(pass, t)) {
            readData(r, kMaxChunkBytes, data_);
            message = Message{t, time, data_, pos};
          }
        }
      } catch (const BagError& e) {
        recordError(pass, e);
      }
      // Outside the try: what `visit` throws is the caller's, not a bad record.
      if (loaded) {
        ChunkRef seen;
        seen.pos = pos;
        walkChunk(body, pos, pass, pass.scanning ? &seen : nullptr);
        if (pass.scanning && seen.pos == pos) scannedChunks_[pos] = std::move(seen.counts);
      }
      if (message) (*pass.visit)(*message);
      pos = r.end;
      if (options != nullptr && (chunk || pos - reported >= kProgressStep || pos >= size_)) {
        step(*options, pos);
        reported = pos;
      }
    }
  }

  std::unique_ptr<ByteSource> src_;
  std::uint64_t size_ = 0;
  std::uint64_t dataStart_ = 0;  // the first record after the bag header
  std::uint64_t indexPos_ = 0;   // the bag header's index_pos
  bool indexed_ = false;
  std::vector<Topic> topics_;
  std::map<std::uint32_t, std::size_t> topicOf_;  // connection id -> index in topics_
  std::vector<ChunkRef> chunks_;                  // from the index, in file order
  // Without index: the connections of each chunk the constructor's walk read whole.
  std::map<std::uint64_t, std::vector<std::pair<std::uint32_t, std::uint32_t>>> scannedChunks_;
  Skipped skipped_;
  std::string scratch_, data_, stored_, chunk_;  // one chunk at a time
  std::string message_, messageData_;            // one message read on its own
};

}  // namespace

std::unique_ptr<Reader> openRos1(std::unique_ptr<ByteSource> source) {
  return std::make_unique<Ros1Reader>(std::move(source));
}

}  // namespace sg::bag
