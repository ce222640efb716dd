// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// ARCOS packets, the protocol of Pioneer, AmigoBot and PeopleBot controllers and of MobileSim-style
// simulators (docs/live-robot.md, "The protocol"): framing, checksum and the client commands.
//
//   FA FB | N | ID | payload | CHK_hi CHK_lo
//
// N counts ID, payload and the two checksum bytes. The checksum is the sum of the big-endian 16-bit
// words from ID on, masked to 16 bits, with an odd last byte XORed in; it is sent high byte first.
// Data fields inside payloads are little-endian.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace sg::arcos {

using Bytes = std::vector<std::uint8_t>;

inline constexpr std::uint8_t kHeader0 = 0xFA;
inline constexpr std::uint8_t kHeader1 = 0xFB;
// The count byte covers ID + two checksum bytes at least.
inline constexpr std::size_t kMinCount = 3;
// Two header bytes, the count byte and at most 255 counted bytes.
inline constexpr std::size_t kMaxFrameBytes = 3 + 255;
// What we send stays within the 200 bytes the controllers accept.
inline constexpr std::size_t kMaxSendBytes = 200;

// Argument types of a command.
inline constexpr std::uint8_t kArgInt = 0x3B;     // a non-negative integer, 2 bytes LE magnitude
inline constexpr std::uint8_t kArgNegInt = 0x1B;  // a negative integer, 2 bytes LE magnitude
inline constexpr std::uint8_t kArgString = 0x2B;  // a length byte, then the characters

// Client command numbers (the packet ID of a command).
namespace command {
inline constexpr std::uint8_t kPulse = 0;
inline constexpr std::uint8_t kOpen = 1;
inline constexpr std::uint8_t kClose = 2;
inline constexpr std::uint8_t kEnable = 4;
inline constexpr std::uint8_t kSetV = 6;
inline constexpr std::uint8_t kSetO = 7;
inline constexpr std::uint8_t kSetRv = 10;
inline constexpr std::uint8_t kVel = 11;
inline constexpr std::uint8_t kHead = 12;
inline constexpr std::uint8_t kConfig = 18;
inline constexpr std::uint8_t kRVel = 21;
inline constexpr std::uint8_t kSonar = 28;
inline constexpr std::uint8_t kStop = 29;
inline constexpr std::uint8_t kVel2 = 32;
inline constexpr std::uint8_t kEStop = 55;
inline constexpr std::uint8_t kSoundTog = 92;
// Simulators only.
inline constexpr std::uint8_t kSimSetPose = 224;
inline constexpr std::uint8_t kSimReset = 225;
inline constexpr std::uint8_t kSimStat = 237;
}  // namespace command

// Server packet IDs. The handshake's SYNC0..2 share IDs 0..2 with PULSE, OPEN and CLOSE: which one
// a packet is depends on the state of the connection.
namespace packet_id {
inline constexpr std::uint8_t kSync0 = 0;
inline constexpr std::uint8_t kSync1 = 1;
inline constexpr std::uint8_t kSync2 = 2;
inline constexpr std::uint8_t kSipStopped = 0x32;
inline constexpr std::uint8_t kSipMoving = 0x33;
inline constexpr std::uint8_t kSimStat = 0x62;
}  // namespace packet_id

// One decoded frame: its ID and the bytes between the ID and the checksum.
struct Packet {
  std::uint8_t id = 0;
  Bytes payload;

  bool operator==(const Packet&) const = default;
};

// The checksum of `body` (ID and payload).
std::uint16_t checksum(std::span<const std::uint8_t> body);

// The whole frame of a packet. Throws std::length_error when it would exceed kMaxSendBytes.
Bytes framePacket(std::uint8_t id, std::span<const std::uint8_t> payload);
Bytes framePacket(const Packet& packet);

// Client commands: no argument, an integer argument (magnitude at most 65535, else
// std::out_of_range) or a string argument (std::length_error when the frame would be too long).
Bytes encodeCommand(std::uint8_t number);
Bytes encodeCommand(std::uint8_t number, int argument);
Bytes encodeCommand(std::uint8_t number, std::string_view text);

// VEL2: the left and right wheel velocities (mm/s) divided by `divisor` and rounded, each a signed
// byte clamped to ±126 (as Player's p2os driver does), left in the high byte, right in the low
// byte, always with the non-negative integer type.
Bytes encodeVel2(double leftMmPerS, double rightMmPerS, double divisor);

}  // namespace sg::arcos
