// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: the ARCOS codec (tests/fuzz/README.md). The input is a byte stream from the
// wire, fed to the frame decoder in pieces whose sizes the input's first byte chooses; every
// frame is decoded as each kind of packet, SIPs become scans, and the same bytes are read by the
// client session (as a robot's replies) and by the virtual robot (as a client's commands).
// Invariants: the decoder never holds a whole frame's worth unfinished, a decoded SIP encodes
// back to itself, and nothing but std::length_error (a SIP too long to send) escapes.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <stdexcept>

#include "sonargrid/arcos/client_session.h"
#include "sonargrid/arcos/decoder.h"
#include "sonargrid/arcos/messages.h"
#include "sonargrid/arcos/sip_tracker.h"
#include "sonargrid/arcos/virtual_robot.h"

namespace {

struct Quiet : sg::arcos::ClientSession::Listener {
  void sendBytes(std::span<const std::uint8_t>) override {}
  void onScan(const sg::Scan& s) override {
    for (const sg::Reading& r : s.readings) {
      if (r.sonar >= 16) std::abort();  // the tracker let a reading name no sonar
    }
  }
};

void checkPacket(const sg::arcos::Packet& p, sg::arcos::SipTracker& tracker, double time) {
  using namespace sg::arcos;
  if (const auto sip = decodeSip(p.payload, p.id == packet_id::kSipMoving)) {
    tracker.apply(*sip, time);
    try {
      const Bytes frame = encodeSip(*sip);
      PacketDecoder again;
      int n = 0;
      again.feed(frame, [&](const Packet& q) {
        ++n;
        if (decodeSip(q.payload, sip->moving) != sip) std::abort();
      });
      if (n != 1) std::abort();
    } catch (const std::length_error&) {
      // More than a controller accepts in one frame: not sendable, and said so.
    }
  }
  if (const auto stat = decodeSimStat(p.payload)) tracker.setTruth(*stat);
  (void)decodeServerInfo(p.payload);
  (void)decodeCommand(p);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sg::arcos;
  if (size == 0) return 0;
  const std::size_t piece = 1 + data[0] % 64;
  const std::span<const std::uint8_t> bytes(data + 1, size - 1);

  PacketDecoder decoder;
  SipTracker tracker(pioneer3dxParameters());
  double time = 0.0;
  for (std::size_t at = 0; at < bytes.size(); at += piece) {
    decoder.feed(bytes.subspan(at, std::min(piece, bytes.size() - at)),
                 [&](const Packet& p) { checkPacket(p, tracker, time += 0.1); });
    if (decoder.pendingBytes() >= kMaxFrameBytes) std::abort();
  }
  const FramingCounters& c = decoder.counters();
  if (c.bytes != bytes.size() || c.skippedBytes > c.bytes) std::abort();

  // The client session reads the bytes as a robot's, from the first SYNC0 on.
  Quiet quiet;
  ClientSession session({}, quiet);
  session.start(0.0);
  for (std::size_t at = 0; at < bytes.size(); at += piece) {
    session.receive(bytes.subspan(at, std::min(piece, bytes.size() - at)),
                    0.01 * static_cast<double>(at));
    session.tick(0.01 * static_cast<double>(at));
  }

  // The virtual robot reads them as a client's commands, between short steps of its simulation.
  static const std::vector<sg::Position> corners{{0, 0}, {4, 0}, {4, 3}, {0, 3}};
  VirtualRobotSettings settings;
  settings.physics.raysPerCone = 3;
  VirtualRobot robot(sg::SonarWorld(sg::polygonSegments(corners, true)), sg::Pose2D(2, 1.5, 0),
                     std::nullopt, settings);
  Bytes out;
  robot.clientConnected(0.0);
  double t = 0.0;
  for (std::size_t at = 0; at < bytes.size(); at += piece) {
    robot.receive(bytes.subspan(at, std::min(piece, bytes.size() - at)), t, out);
    t += 0.02;
    robot.advanceTo(t, out);
    out.clear();
  }
  return 0;
}
