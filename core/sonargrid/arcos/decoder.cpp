// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/arcos/decoder.h"

#include <algorithm>

namespace sg::arcos {

PacketDecoder::PacketDecoder() {
  buffer_.reserve(kMaxFrameBytes + kBlockBytes);
}

void PacketDecoder::reset() {
  counters_.skippedBytes += buffer_.size();
  buffer_.clear();
}

void PacketDecoder::feed(std::span<const std::uint8_t> bytes, const Handler& onPacket) {
  counters_.bytes += bytes.size();
  while (!bytes.empty()) {
    const std::size_t n = std::min(bytes.size(), kBlockBytes);
    buffer_.insert(buffer_.end(), bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(n));
    bytes = bytes.subspan(n);
    parse(onPacket);
  }
}

void PacketDecoder::parse(const Handler& onPacket) {
  const std::uint8_t* data = buffer_.data();
  const std::size_t size = buffer_.size();
  std::size_t pos = 0;  // everything before pos is consumed
  // Drops the consumed bytes however the loop ends, a throwing handler included, so that no frame
  // is delivered twice.
  struct Consume {
    Bytes& buffer;
    const std::size_t& pos;
    ~Consume() { buffer.erase(buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(pos)); }
  } consume{buffer_, pos};
  for (;;) {
    std::size_t start = pos;
    while (start + 1 < size && !(data[start] == kHeader0 && data[start + 1] == kHeader1)) ++start;
    if (start + 1 >= size) {
      // No header in what is left; a trailing FA may be the first half of one.
      const bool keepLast = start < size && data[start] == kHeader0;
      const std::size_t end = keepLast ? start : size;
      counters_.skippedBytes += end - pos;
      pos = end;
      break;
    }
    counters_.skippedBytes += start - pos;
    pos = start;
    if (size - pos < 3) break;
    const std::size_t count = data[pos + 2];
    if (count < kMinCount) {
      ++counters_.badCounts;
      ++counters_.skippedBytes;
      ++pos;
      continue;
    }
    const std::size_t total = 3 + count;
    if (size - pos < total) break;
    const std::span<const std::uint8_t> body(data + pos + 3, count - 2);
    const auto sent =
        static_cast<std::uint16_t>((data[pos + total - 2] << 8U) | data[pos + total - 1]);
    if (checksum(body) != sent) {
      ++counters_.badChecksums;
      ++counters_.skippedBytes;
      ++pos;
      continue;
    }
    ++counters_.frames;
    packet_.id = body[0];
    packet_.payload.assign(body.begin() + 1, body.end());
    pos += total;
    onPacket(packet_);
  }
}

}  // namespace sg::arcos
