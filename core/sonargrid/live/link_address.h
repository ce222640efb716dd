// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Where a robot is: `tcp://HOST[:PORT]` (a MobileSim-style simulator, the virtual robot, or a
// robot behind a serial-to-network bridge; port 8101 by default) or `serial://DEVICE[?baud=N]`
// (`serial:///dev/ttyUSB0?baud=115200`; 9600 baud by default). docs/live-robot.md, "Addresses".

#include <cstdint>
#include <string>
#include <string_view>

namespace sg::live {

inline constexpr std::uint16_t kDefaultArcosPort = 8101;
inline constexpr int kDefaultBaud = 9600;

struct LinkAddress {
  enum class Kind { Tcp, Serial };
  Kind kind = Kind::Tcp;
  std::string host;  // Tcp: a name or an address (IPv6 without brackets)
  std::uint16_t port = kDefaultArcosPort;
  std::string device;  // Serial: "/dev/ttyUSB0", "COM3"
  int baud = kDefaultBaud;

  // The canonical text, which parses back to the same address.
  std::string text() const;
  bool operator==(const LinkAddress&) const = default;
};

// Throws std::invalid_argument saying what is wrong, e.g. "tcp://robot:99999: the port must be a
// number from 1 to 65535".
LinkAddress parseLinkAddress(std::string_view text);

}  // namespace sg::live
