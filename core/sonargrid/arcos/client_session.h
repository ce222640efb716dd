// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The client side of one ARCOS connection, without any I/O of its own: bytes from the robot and
// the passing of time go in; bytes to send, the handshake's result, scans and a lost connection
// come out through a Listener. The robot link (core/sonargrid/live/robot_link.h) drives it from a
// socket or a serial port; tests drive it directly.
//
// Handshake: SYNC0, SYNC1 (each echoed), SYNC2, answered by ID 2 with name, class and subclass;
// then OPEN, ENABLE 1, SONAR 1 and, from a simulator, SIM_STAT 2. Open: every SIP is a scan;
// PULSE goes out when nothing was sent for `pulseAfter`; no packet for `lostAfter` is a lost
// connection (docs/live-robot.md, "The link").

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "sonargrid/arcos/decoder.h"
#include "sonargrid/arcos/messages.h"
#include "sonargrid/arcos/odometry_stitcher.h"
#include "sonargrid/arcos/robot_params.h"
#include "sonargrid/arcos/sip_tracker.h"
#include "sonargrid/data/dataset.h"

namespace sg::arcos {

// Everything counted over the life of a link (all connections).
struct LinkCounters {
  FramingCounters framing;
  std::uint64_t sips = 0;
  std::uint64_t simStats = 0;
  std::uint64_t readings = 0;         // readings delivered in scans
  std::uint64_t droppedReadings = 0;  // readings of transducers the ring does not have
  std::uint64_t malformedSips = 0;    // valid frames too short for their fields
  std::uint64_t malformedSimStats = 0;
  std::uint64_t malformedServerInfo = 0;
  std::uint64_t otherPackets = 0;  // valid frames of IDs the client does not read
  std::uint64_t handshakes = 0;    // connections that reached OPEN
  std::uint64_t timeouts = 0;      // connections given up: the robot fell silent or never answered
  std::uint64_t lostConnections = 0;  // open connections that ended (counted by the link)
  std::uint64_t attempts = 0;         // connections tried (counted by the link)
  std::uint64_t reconnects = 0;       // handshakes after the first (counted by the link)
  std::uint64_t pulses = 0;
  std::uint64_t segments = 0;  // connections that delivered a scan (odometry_stitcher.h)
  std::uint64_t stitched = 0;  // of them, those whose odometry was placed onto the one before

  // Every malformed or corrupt packet, whatever its kind.
  std::uint64_t errors() const {
    return framing.badChecksums + framing.badCounts + malformedSips + malformedSimStats +
           malformedServerInfo;
  }
  bool operator==(const LinkCounters&) const = default;
};

enum class SimStatRequest {
  Auto,    // when the server's name says it is a simulator ("MobileSim", "AMRISim", ...)
  Always,  // real robots ignore the command
  Never,
};

struct ClientSettings {
  std::optional<RobotParameters> robot;  // overrides what the reported subclass implies
  SimStatRequest simStat = SimStatRequest::Auto;
  double syncRetry = 1.0;         // s without the next handshake reply: start again from SYNC0
  double handshakeTimeout = 5.0;  // s from the first SYNC0 to giving up on this connection
  double pulseAfter = 0.5;        // s without sending anything: send PULSE
  double lostAfter = 2.0;         // s without a packet from an open robot: the connection is lost
};

class ClientSession {
 public:
  class Listener {
   public:
    virtual ~Listener() = default;
    virtual void sendBytes(std::span<const std::uint8_t> bytes) = 0;
    virtual void onConnected(const ServerInfo& /*server*/, const RobotParameters& /*robot*/) {}
    virtual void onScan(const Scan& /*scan*/) {}
    virtual void onWarning(const std::string& /*message*/) {}
    // The connection is lost; the session is idle until start() is called again.
    virtual void onLost(const std::string& /*reason*/) {}
  };

  enum class State { Idle, Sync0, Sync1, Sync2, Open };

  ClientSession(ClientSettings settings, Listener& listener);

  // A new connection (`now` in seconds, any monotonic clock): sends SYNC0.
  void start(double now);
  void receive(std::span<const std::uint8_t> bytes, double now);
  // Handshake retries, keep-alive and loss detection; call it every few tens of milliseconds.
  void tick(double now);
  // The transport closed by itself: idle, without calling lost().
  void disconnected();

  // When open (ignored otherwise): VEL (mm/s) and RVEL (deg/s) from metres and radians per second;
  // STOP; any encoded command; CLOSE (after STOP if this session sent a motion command: a robot
  // left to drive itself, like the virtual robot on its route, is not taken over), after which
  // the session is idle.
  void setVelocity(double metresPerSecond, double radiansPerSecond, double now);
  void setWheelVelocities(double leftMetresPerSecond, double rightMetresPerSecond, double now);
  void stop(double now);
  // SETV (mm/s) and SETRV (deg/s): the robot's own limits on later velocity commands.
  void setSpeedLimits(double metresPerSecond, double radiansPerSecond, double now);
  void sendCommand(std::span<const std::uint8_t> bytes, double now);
  void close(double now);

  State state() const { return state_; }
  bool isOpen() const { return state_ == State::Open; }
  const LinkCounters& counters() const { return counters_; }
  LinkCounters& counters() { return counters_; }
  // The server and robot of the current (or last) connection; empty before the first handshake.
  const std::optional<ServerInfo>& server() const { return server_; }
  const std::optional<RobotParameters>& robot() const { return robot_; }
  std::span<const double> latestRanges() const;

 private:
  void onPacket(const Packet& p, double now);
  void onServerInfo(const Packet& p, double now);
  void restartHandshake(double now);
  void send(std::span<const std::uint8_t> bytes, double now);
  void lose(const std::string& reason);
  // Why the handshake failed, in words: what came back since it began and the likely cause.
  std::string handshakeFailure() const;
  RobotParameters chooseRobot(const ServerInfo& info, bool valid);
  // Hands the stitcher's ready scans to the listener.
  void deliver(std::vector<Scan>& scans);
  // The connection ended: the scans the stitcher still holds are delivered.
  void flushScans();

  ClientSettings settings_;
  Listener& listener_;
  State state_ = State::Idle;
  PacketDecoder decoder_;
  LinkCounters counters_;
  std::optional<ServerInfo> server_;
  std::optional<RobotParameters> robot_;
  std::optional<SipTracker> tracker_;
  OdometryStitcher stitcher_;
  bool simulator_ = false;  // SIMSTATs were asked for: true poses will come
  double handshakeStart_ = 0.0;
  FramingCounters framingAtStart_;  // the decoder's counts when the handshake began
  double attemptStart_ = 0.0;
  double lastSent_ = 0.0;
  double lastReceived_ = 0.0;
  bool closeSent_ = false;  // CLOSE sent to a robot still streaming to an earlier client
  bool drove_ = false;      // this connection sent a motion command
};

}  // namespace sg::arcos
