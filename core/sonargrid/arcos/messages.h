// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The packets a robot sends (the handshake reply, the standard SIP, the simulator's SIMSTAT) and
// the commands a client sends, decoded from and encoded to packet payloads (docs/live-robot.md,
// "The protocol"). Decoders return nothing for a payload too short for its fixed fields or
// otherwise malformed; trailing bytes after the known fields are kept, never an error.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "sonargrid/arcos/packet.h"

namespace sg::arcos {

// The reply to SYNC2 (ID 2): three NUL-terminated strings.
struct ServerInfo {
  std::string name;        // e.g. the robot's own name, "MobileSim"
  std::string robotClass;  // e.g. "Pioneer"
  std::string subclass;    // e.g. "p3dx", "amigo"

  bool operator==(const ServerInfo&) const = default;
};
std::optional<ServerInfo> decodeServerInfo(std::span<const std::uint8_t> payload);
Bytes encodeServerInfo(const ServerInfo& info);

struct SonarEcho {
  std::uint8_t number = 0;  // transducer number
  std::uint16_t range = 0;  // sonar units (× RangeConvFactor = mm)

  bool operator==(const SonarEcho&) const = default;
};

// The standard server information packet (ID 0x32 stopped, 0x33 moving).
struct Sip {
  bool moving = false;
  std::uint16_t xpos = 0;     // 15 bits, wraps at 0x8000; × DistConvFactor = mm
  std::uint16_t ypos = 0;     // 15 bits
  std::int16_t thpos = 0;     // × 2π/4096 rad
  std::int16_t leftVel = 0;   // × VelConvFactor = mm/s
  std::int16_t rightVel = 0;  // × VelConvFactor = mm/s
  std::uint8_t battery = 0;   // 0.1 V
  std::uint16_t stallBump = 0;
  std::int16_t control = 0;
  std::uint16_t flags = 0;  // bit 0: motors on
  std::uint8_t compass = 0;
  std::vector<SonarEcho> sonars;  // the transducers fired since the last SIP
  Bytes trailing;                 // fields after the sonars, not interpreted

  bool operator==(const Sip&) const = default;
};
// The bytes of the fixed fields up to and including the sonar count.
inline constexpr std::size_t kSipFixedBytes = 19;
inline constexpr std::uint16_t kMotorsOnFlag = 0x0001;
std::optional<Sip> decodeSip(std::span<const std::uint8_t> payload, bool moving);
// Throws std::length_error when the frame would be too long (more than 58 sonars).
Bytes encodeSip(const Sip& sip);

// The simulator's true-pose packet (ID 0x62).
struct SimStat {
  std::uint32_t flags = 0;
  std::uint16_t simInterval = 0;   // ms of simulated time per cycle
  std::uint16_t realInterval = 0;  // ms of real time per cycle
  std::uint16_t lastInterval = 0;  // ms the last cycle took
  std::int32_t trueX = 0;          // mm
  std::int32_t trueY = 0;          // mm
  std::int32_t trueZ = 0;          // mm
  std::int32_t trueThetaDeg = 0;   // degrees
  Bytes trailing;                  // fields after the pose, not interpreted

  bool operator==(const SimStat&) const = default;
};
// Two reserved bytes, flags, three intervals, then X, Y, Z and Theta.
inline constexpr std::size_t kSimStatFixedBytes = 2 + 4 + 3 * 2 + 4 * 4;
std::optional<SimStat> decodeSimStat(std::span<const std::uint8_t> payload);
Bytes encodeSimStat(const SimStat& stat);

// A client command as the robot reads it.
struct Command {
  enum class Argument { None, Int, String };
  std::uint8_t number = 0;
  Argument argument = Argument::None;
  int value = 0;     // Int: the signed value
  std::string text;  // String: the characters

  bool operator==(const Command&) const = default;
};
std::optional<Command> decodeCommand(const Packet& packet);

// VEL2's argument as two signed wheel bytes: left (high byte), right (low byte), in Vel2Divisor
// units. A negative integer argument is read as its 16-bit two's complement.
struct WheelBytes {
  int left = 0;
  int right = 0;
};
WheelBytes vel2Wheels(int value);

}  // namespace sg::arcos
