// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The streaming frame decoder: bytes in (any split, any garbage), valid frames out. It finds frames
// by their FA FB header, checks the count byte and the checksum, and after a bad frame resumes the
// search one byte after that frame's header, so that a real header hidden inside a corrupt frame
// is not lost. It never reads past what it was given and holds at most one unfinished frame plus
// one block of input.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>

#include "sonargrid/arcos/packet.h"

namespace sg::arcos {

struct FramingCounters {
  std::uint64_t bytes = 0;         // bytes fed
  std::uint64_t frames = 0;        // frames with a valid count and checksum
  std::uint64_t skippedBytes = 0;  // bytes in no valid frame (noise, corrupt frames)
  std::uint64_t badChecksums = 0;  // frames whose checksum did not match
  std::uint64_t badCounts = 0;     // headers followed by a count byte below 3

  bool operator==(const FramingCounters&) const = default;
};

class PacketDecoder {
 public:
  using Handler = std::function<void(const Packet&)>;

  PacketDecoder();

  // Calls `onPacket` for every valid frame completed by `bytes`, in order. An unfinished frame at
  // the end waits for the next call. The handler must not feed this decoder.
  void feed(std::span<const std::uint8_t> bytes, const Handler& onPacket);
  // Forgets an unfinished frame (a new connection starts clean); the counters stay.
  void reset();

  const FramingCounters& counters() const { return counters_; }
  // Bytes held back: at most kMaxFrameBytes - 1 between calls.
  std::size_t pendingBytes() const { return buffer_.size(); }

 private:
  // Input is taken in blocks of this size, which bounds the buffer.
  static constexpr std::size_t kBlockBytes = 1024;
  void parse(const Handler& onPacket);

  Bytes buffer_;
  Packet packet_;  // reused, so that a steady stream allocates nothing per frame
  FramingCounters counters_;
};

}  // namespace sg::arcos
