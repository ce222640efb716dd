// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/arcos/packet.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace sg::arcos {

std::uint16_t checksum(std::span<const std::uint8_t> body) {
  unsigned sum = 0;
  std::size_t i = 0;
  for (; i + 1 < body.size(); i += 2) {
    sum += (static_cast<unsigned>(body[i]) << 8U) | body[i + 1];
    sum &= 0xFFFFU;
  }
  if (i < body.size()) sum ^= body[i];
  return static_cast<std::uint16_t>(sum);
}

Bytes framePacket(std::uint8_t id, std::span<const std::uint8_t> payload) {
  const std::size_t count = 1 + payload.size() + 2;
  if (3 + count > kMaxSendBytes) {
    throw std::length_error("an ARCOS packet of " + std::to_string(3 + count) +
                            " bytes is longer than the " + std::to_string(kMaxSendBytes) +
                            " bytes a controller accepts");
  }
  Bytes out;
  out.reserve(3 + count);
  out.push_back(kHeader0);
  out.push_back(kHeader1);
  out.push_back(static_cast<std::uint8_t>(count));
  out.push_back(id);
  out.insert(out.end(), payload.begin(), payload.end());
  const std::uint16_t sum = checksum(std::span<const std::uint8_t>(out).subspan(3));
  out.push_back(static_cast<std::uint8_t>(sum >> 8U));
  out.push_back(static_cast<std::uint8_t>(sum & 0xFFU));
  return out;
}

Bytes framePacket(const Packet& packet) {
  return framePacket(packet.id, packet.payload);
}

Bytes encodeCommand(std::uint8_t number) {
  return framePacket(number, {});
}

Bytes encodeCommand(std::uint8_t number, int argument) {
  const long magnitude = std::labs(static_cast<long>(argument));
  if (magnitude > 0xFFFF) {
    throw std::out_of_range("ARCOS command " + std::to_string(number) + ": argument " +
                            std::to_string(argument) + " does not fit 2 bytes");
  }
  const auto m = static_cast<unsigned>(magnitude);
  const std::uint8_t payload[3] = {argument < 0 ? kArgNegInt : kArgInt,
                                   static_cast<std::uint8_t>(m & 0xFFU),
                                   static_cast<std::uint8_t>(m >> 8U)};
  return framePacket(number, payload);
}

Bytes encodeCommand(std::uint8_t number, std::string_view text) {
  if (text.size() > 255) {
    throw std::length_error("ARCOS command " + std::to_string(number) + ": a string of " +
                            std::to_string(text.size()) + " bytes is too long");
  }
  Bytes payload;
  payload.reserve(2 + text.size());
  payload.push_back(kArgString);
  payload.push_back(static_cast<std::uint8_t>(text.size()));
  payload.insert(payload.end(), text.begin(), text.end());
  return framePacket(number, payload);
}

Bytes encodeVel2(double leftMmPerS, double rightMmPerS, double divisor) {
  auto wheel = [divisor](double v) {
    const double units = std::isfinite(v) && divisor > 0.0 ? std::round(v / divisor) : 0.0;
    const auto clamped = static_cast<int>(std::clamp(units, -126.0, 126.0));
    return static_cast<std::uint8_t>(static_cast<unsigned>(clamped) & 0xFFU);
  };
  const std::uint8_t payload[3] = {kArgInt, wheel(rightMmPerS), wheel(leftMmPerS)};
  return framePacket(command::kVel2, payload);
}

}  // namespace sg::arcos
