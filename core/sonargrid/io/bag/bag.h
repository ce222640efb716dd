// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Robot bags without a ROS installation (docs/formats.md, "ROS bags"): the containers (ROS 1 bag
// format 2.0, rosbag2 with the SQLite storage, rosbag2 with the MCAP storage) seen through one
// interface that lists a bag's topics and hands over the serialised messages of chosen topics,
// chunk by chunk, so that memory holds one chunk at a time. What the messages mean is bag_log.h's.

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace sg::bag {

// How a topic's messages are serialised.
enum class Encoding {
  Ros1,  // ROS 1: little-endian, packed, uint32-length strings and arrays
  Cdr,   // ROS 2: a 4-byte encapsulation header, then XCDR1 (either endianness, aligned)
};

struct Topic {
  std::string name;  // "/RosAria/sonar"
  std::string type;  // "sensor_msgs/Range"; ROS 2's "sensor_msgs/msg/Range" is given as is
  Encoding encoding = Encoding::Ros1;
  std::string definition;   // the message definition the bag carries (ROS 1, MCAP), or empty
  std::uint64_t count = 0;  // messages, from the index or summary; 0 when the bag has none
  std::int64_t firstNs = 0, lastNs = 0;  // log times of the first and last message (ns), or 0
};

struct Message {
  std::size_t topic = 0;       // index into Reader::topics()
  std::int64_t logTimeNs = 0;  // the container's receive time (ns since the epoch)
  std::string_view data;       // the serialised message; valid only during the callback
  std::uint64_t offset = 0;    // where its record starts in the file (for error messages)
};

// Thrown for a malformed container: names the file, the byte offset of the bad record and, when
// known, the topic. `what()` reads "FILE: offset N (topic T): MESSAGE".
class BagError : public std::runtime_error {
 public:
  BagError(std::string file, std::uint64_t offset, std::string topic, std::string message);
  const std::string& file() const { return file_; }
  std::uint64_t offset() const { return offset_; }
  const std::string& topic() const { return topic_; }
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  std::uint64_t offset_;
  std::string topic_;
  std::string message_;
};

// Where a container's bytes come from: a file read piece by piece, or bytes already in memory
// (the fuzz targets and tests).
class ByteSource {
 public:
  virtual ~ByteSource() = default;
  virtual std::uint64_t size() const = 0;
  // Exactly `n` bytes at `offset` into `out` (resized); throws BagError when they are not there.
  virtual void read(std::uint64_t offset, std::size_t n, std::string& out) const = 0;
  // The file's name for messages.
  virtual const std::string& name() const = 0;
};
std::unique_ptr<ByteSource> fileSource(const std::string& path);  // throws BagError if unreadable
std::unique_ptr<ByteSource> memorySource(std::string_view bytes, std::string name);

struct ReadOptions {
  // Skip a bad record or message (and count it) instead of stopping at the first.
  bool lenient = false;
  // Bytes of the file processed so far and its size; called after each chunk.
  std::function<void(std::uint64_t done, std::uint64_t total)> progress;
  // Checked after each chunk; when it turns true the read throws sg::LoadCancelled.
  const std::atomic<bool>* cancel = nullptr;
};

// Counts of what a lenient read skipped (record kind or reason -> count, first error's text).
struct Skipped {
  std::size_t count = 0;
  std::string firstError;
};

class Reader {
 public:
  virtual ~Reader() = default;
  // Every topic (connection, channel) of the bag, in the order the file declares them.
  virtual const std::vector<Topic>& topics() const = 0;
  // Calls `visit` for each message of the topics whose index `wanted[i]` is true, in file order
  // (chunk by chunk; messages within a chunk in the order stored). Only chunks that may hold a
  // wanted topic are read and decompressed when the container's index says which.
  virtual void read(const std::vector<bool>& wanted, const ReadOptions& options,
                    const std::function<void(const Message&)>& visit) = 0;
  // What the last lenient read skipped.
  virtual const Skipped& skipped() const = 0;
};

enum class Container { Unknown, Ros1, Mcap, Sqlite };

// The container a file's first bytes show ("#ROSBAG V2.0\n", the MCAP magic, "SQLite format 3").
Container detectContainer(std::string_view head);

}  // namespace sg::bag
