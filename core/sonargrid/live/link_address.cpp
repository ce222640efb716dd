// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/live/link_address.h"

#include <charconv>
#include <stdexcept>

namespace sg::live {
namespace {

constexpr std::string_view kTcp = "tcp://";
constexpr std::string_view kSerial = "serial://";
// Far above any UART a robot has; it only keeps the number sane.
constexpr long kMaxBaud = 4000000;

bool wholeNumber(std::string_view s, long& v) {
  if (s.empty() || s.size() > 9) return false;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

}  // namespace

std::string LinkAddress::text() const {
  if (kind == Kind::Serial) {
    std::string out = std::string(kSerial) + device;
    if (baud != kDefaultBaud) out += "?baud=" + std::to_string(baud);
    return out;
  }
  const bool v6 = host.find(':') != std::string::npos;
  return std::string(kTcp) + (v6 ? "[" + host + "]" : host) + ":" + std::to_string(port);
}

LinkAddress parseLinkAddress(std::string_view text) {
  auto bad = [text](const std::string& why) {
    throw std::invalid_argument(std::string(text) + ": " + why);
  };
  LinkAddress a;
  if (text.starts_with(kTcp)) {
    a.kind = LinkAddress::Kind::Tcp;
    std::string_view rest = text.substr(kTcp.size());
    if (!rest.empty() && rest.back() == '/') rest.remove_suffix(1);
    std::string_view portText;
    if (rest.starts_with('[')) {
      const auto close = rest.find(']');
      if (close == std::string_view::npos) bad("an IPv6 address needs its closing ']'");
      a.host = std::string(rest.substr(1, close - 1));
      rest = rest.substr(close + 1);
      if (!rest.empty()) {
        if (rest[0] != ':') bad("expected ':PORT' after the IPv6 address");
        portText = rest.substr(1);
        if (portText.empty()) bad("expected a port number after ':'");
      }
    } else {
      const auto colon = rest.rfind(':');
      if (colon != std::string_view::npos) {
        if (rest.find(':') != colon) bad("write an IPv6 address in brackets: tcp://[::1]:8101");
        a.host = std::string(rest.substr(0, colon));
        portText = rest.substr(colon + 1);
        if (portText.empty()) bad("expected a port number after ':'");
      } else {
        a.host = std::string(rest);
      }
    }
    if (a.host.empty()) bad("expected a host name or address after tcp://");
    if (a.host.find_first_of("/?#@ ") != std::string::npos) bad("the host name is not valid");
    if (!portText.empty()) {
      long port = 0;
      if (!wholeNumber(portText, port) || port < 1 || port > 65535)
        bad("the port must be a number from 1 to 65535");
      a.port = static_cast<std::uint16_t>(port);
    }
    return a;
  }
  if (text.starts_with(kSerial)) {
    a.kind = LinkAddress::Kind::Serial;
    std::string_view rest = text.substr(kSerial.size());
    const auto q = rest.find('?');
    a.device = std::string(rest.substr(0, q));
    if (a.device.empty()) bad("expected a device after serial://, e.g. serial:///dev/ttyUSB0");
    if (q != std::string_view::npos) {
      const std::string_view query = rest.substr(q + 1);
      if (!query.starts_with("baud=")) bad("the only option is ?baud=N");
      long baud = 0;
      if (!wholeNumber(query.substr(5), baud) || baud < 1 || baud > kMaxBaud)
        bad("baud must be a number from 1 to 4000000");
      a.baud = static_cast<int>(baud);
    }
    return a;
  }
  bad("expected tcp://HOST[:PORT] or serial://DEVICE[?baud=N]");
  return a;
}

}  // namespace sg::live
