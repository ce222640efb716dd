// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/arcos/messages.h"

#include <algorithm>
#include <stdexcept>

namespace sg::arcos {
namespace {

// Little-endian fields, read from a payload whose length was checked first.
class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}
  std::size_t left() const { return bytes_.size() - pos_; }
  std::uint8_t u8() { return bytes_[pos_++]; }
  std::uint16_t u16() {
    const auto v = static_cast<std::uint16_t>(bytes_[pos_] | (bytes_[pos_ + 1] << 8U));
    pos_ += 2;
    return v;
  }
  std::int16_t i16() { return static_cast<std::int16_t>(u16()); }
  std::uint32_t u32() {
    std::uint32_t v = 0;
    for (unsigned i = 0; i < 4; ++i) v |= static_cast<std::uint32_t>(bytes_[pos_ + i]) << (8U * i);
    pos_ += 4;
    return v;
  }
  std::int32_t i32() { return static_cast<std::int32_t>(u32()); }
  Bytes rest() {
    Bytes out(bytes_.begin() + static_cast<std::ptrdiff_t>(pos_), bytes_.end());
    pos_ = bytes_.size();
    return out;
  }

 private:
  std::span<const std::uint8_t> bytes_;
  std::size_t pos_ = 0;
};

class Writer {
 public:
  void u8(std::uint8_t v) { out.push_back(v); }
  void u16(std::uint16_t v) {
    out.push_back(static_cast<std::uint8_t>(v & 0xFFU));
    out.push_back(static_cast<std::uint8_t>(v >> 8U));
  }
  void i16(std::int16_t v) { u16(static_cast<std::uint16_t>(v)); }
  void u32(std::uint32_t v) {
    for (unsigned i = 0; i < 4; ++i)
      out.push_back(static_cast<std::uint8_t>((v >> (8U * i)) & 0xFFU));
  }
  void i32(std::int32_t v) { u32(static_cast<std::uint32_t>(v)); }
  Bytes out;
};

}  // namespace

std::optional<ServerInfo> decodeServerInfo(std::span<const std::uint8_t> payload) {
  std::string fields[3];
  std::size_t pos = 0;
  for (std::string& field : fields) {
    const auto begin = payload.begin() + static_cast<std::ptrdiff_t>(pos);
    const auto nul = std::find(begin, payload.end(), std::uint8_t{0});
    if (nul == payload.end()) return std::nullopt;
    field.assign(begin, nul);
    pos = static_cast<std::size_t>(nul - payload.begin()) + 1;
  }
  return ServerInfo{std::move(fields[0]), std::move(fields[1]), std::move(fields[2])};
}

Bytes encodeServerInfo(const ServerInfo& info) {
  Bytes payload;
  for (const std::string* s : {&info.name, &info.robotClass, &info.subclass}) {
    payload.insert(payload.end(), s->begin(), s->end());
    payload.push_back(0);
  }
  return framePacket(packet_id::kSync2, payload);
}

std::optional<Sip> decodeSip(std::span<const std::uint8_t> payload, bool moving) {
  if (payload.size() < kSipFixedBytes) return std::nullopt;
  Reader r(payload);
  Sip s;
  s.moving = moving;
  s.xpos = r.u16() & 0x7FFFU;
  s.ypos = r.u16() & 0x7FFFU;
  s.thpos = r.i16();
  s.leftVel = r.i16();
  s.rightVel = r.i16();
  s.battery = r.u8();
  s.stallBump = r.u16();
  s.control = r.i16();
  s.flags = r.u16();
  s.compass = r.u8();
  const std::size_t count = r.u8();
  if (r.left() < 3 * count) return std::nullopt;
  s.sonars.resize(count);
  for (SonarEcho& e : s.sonars) {
    e.number = r.u8();
    e.range = r.u16();
  }
  s.trailing = r.rest();
  return s;
}

Bytes encodeSip(const Sip& sip) {
  Writer w;
  w.u16(sip.xpos & 0x7FFFU);
  w.u16(sip.ypos & 0x7FFFU);
  w.i16(sip.thpos);
  w.i16(sip.leftVel);
  w.i16(sip.rightVel);
  w.u8(sip.battery);
  w.u16(sip.stallBump);
  w.i16(sip.control);
  w.u16(sip.flags);
  w.u8(sip.compass);
  if (sip.sonars.size() > 255) throw std::length_error("a SIP carries at most 255 sonar readings");
  w.u8(static_cast<std::uint8_t>(sip.sonars.size()));
  for (const SonarEcho& e : sip.sonars) {
    w.u8(e.number);
    w.u16(e.range);
  }
  w.out.insert(w.out.end(), sip.trailing.begin(), sip.trailing.end());
  return framePacket(sip.moving ? packet_id::kSipMoving : packet_id::kSipStopped, w.out);
}

std::optional<SimStat> decodeSimStat(std::span<const std::uint8_t> payload) {
  if (payload.size() < kSimStatFixedBytes) return std::nullopt;
  Reader r(payload);
  SimStat s;
  r.u16();  // reserved
  s.flags = r.u32();
  s.simInterval = r.u16();
  s.realInterval = r.u16();
  s.lastInterval = r.u16();
  s.trueX = r.i32();
  s.trueY = r.i32();
  s.trueZ = r.i32();
  s.trueThetaDeg = r.i32();
  s.trailing = r.rest();
  return s;
}

Bytes encodeSimStat(const SimStat& stat) {
  Writer w;
  w.u16(0);
  w.u32(stat.flags);
  w.u16(stat.simInterval);
  w.u16(stat.realInterval);
  w.u16(stat.lastInterval);
  w.i32(stat.trueX);
  w.i32(stat.trueY);
  w.i32(stat.trueZ);
  w.i32(stat.trueThetaDeg);
  w.out.insert(w.out.end(), stat.trailing.begin(), stat.trailing.end());
  return framePacket(packet_id::kSimStat, w.out);
}

std::optional<Command> decodeCommand(const Packet& packet) {
  Command c;
  c.number = packet.id;
  const Bytes& p = packet.payload;
  if (p.empty()) return c;
  if (p[0] == kArgInt || p[0] == kArgNegInt) {
    if (p.size() != 3) return std::nullopt;
    const int magnitude = p[1] | (p[2] << 8U);
    c.argument = Command::Argument::Int;
    c.value = p[0] == kArgInt ? magnitude : -magnitude;
    return c;
  }
  if (p[0] == kArgString) {
    if (p.size() < 2 || p.size() != 2U + p[1]) return std::nullopt;
    c.argument = Command::Argument::String;
    c.text.assign(p.begin() + 2, p.end());
    return c;
  }
  return std::nullopt;
}

WheelBytes vel2Wheels(int value) {
  const auto u = static_cast<std::uint16_t>(static_cast<unsigned>(value) & 0xFFFFU);
  return {static_cast<std::int8_t>(u >> 8U), static_cast<std::int8_t>(u & 0xFFU)};
}

}  // namespace sg::arcos
