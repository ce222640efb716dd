// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/arcos/client_session.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>
#include <utility>
#include <vector>

namespace sg::arcos {
namespace {

bool looksLikeSimulator(const std::string& name) {
  std::string s = name;
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s.find("sim") != std::string::npos;
}

std::string seconds(double s) {
  std::ostringstream out;
  out.precision(1);
  out << std::fixed << s;
  return out.str();
}

// A value in robot units for a 2-byte argument.
int clampedUnits(double v) {
  if (!std::isfinite(v)) return 0;
  return static_cast<int>(std::clamp(std::round(v), -32767.0, 32767.0));
}

}  // namespace

ClientSession::ClientSession(ClientSettings settings, Listener& listener)
    : settings_(std::move(settings)), listener_(listener) {}

void ClientSession::start(double now) {
  flushScans();
  decoder_.reset();
  tracker_.reset();
  handshakeStart_ = now;
  framingAtStart_ = decoder_.counters();
  lastReceived_ = now;
  restartHandshake(now);
}

void ClientSession::restartHandshake(double now) {
  state_ = State::Sync0;
  attemptStart_ = now;
  closeSent_ = false;
  send(encodeCommand(packet_id::kSync0), now);
}

void ClientSession::disconnected() {
  flushScans();
  state_ = State::Idle;
  decoder_.reset();
  counters_.framing = decoder_.counters();
}

void ClientSession::lose(const std::string& reason) {
  flushScans();
  state_ = State::Idle;
  ++counters_.timeouts;
  listener_.onLost(reason);
}

std::string ClientSession::handshakeFailure() const {
  const FramingCounters& n = decoder_.counters();
  const FramingCounters& s = framingAtStart_;
  const std::uint64_t bytes = n.bytes - s.bytes, frames = n.frames - s.frames;
  const std::uint64_t badChecksums = n.badChecksums - s.badChecksums;
  const std::uint64_t skipped = n.skippedBytes - s.skippedBytes;
  std::string why =
      "no answer to the handshake within " + seconds(settings_.handshakeTimeout) + " s: ";
  if (bytes == 0)
    return why + "nothing came back (is the robot on, and the port or address right?)";
  why += std::to_string(bytes) + " bytes came back, " + std::to_string(frames) +
         " valid packets, " + std::to_string(badChecksums) + " bad checksums, " +
         std::to_string(skipped) + " bytes in no packet";
  // Noise without a packet: the line speed or the device is wrong. Packets that are not the
  // SYNC answers: a robot that talks, to someone else.
  if (frames == 0) return why + " (wrong baud rate, or not an ARCOS robot?)";
  return why +
         " (the robot sends packets but does not answer SYNC: is another client connected, "
         "or does it need a reset?)";
}

void ClientSession::send(std::span<const std::uint8_t> bytes, double now) {
  lastSent_ = now;
  listener_.sendBytes(bytes);
}

void ClientSession::receive(std::span<const std::uint8_t> bytes, double now) {
  if (state_ == State::Idle) return;
  decoder_.feed(bytes, [this, now](const Packet& p) {
    // A packet may end the session (CLOSE was answered, a lost robot); the rest is dropped.
    if (state_ != State::Idle) onPacket(p, now);
  });
  counters_.framing = decoder_.counters();
}

void ClientSession::onPacket(const Packet& p, double now) {
  lastReceived_ = now;
  switch (state_) {
    case State::Idle:
      return;
    case State::Sync0:
    case State::Sync1:
      if (p.id == packet_id::kSipStopped || p.id == packet_id::kSipMoving) {
        // The robot still serves an earlier client: close that session, then sync again.
        if (!closeSent_) {
          listener_.onWarning("the robot is still streaming to an earlier connection: closing it");
          send(encodeCommand(command::kClose), now);
          closeSent_ = true;
        }
        ++counters_.otherPackets;
        return;
      }
      if (state_ == State::Sync0 && p.id == packet_id::kSync0 && p.payload.empty()) {
        state_ = State::Sync1;
        attemptStart_ = now;
        send(encodeCommand(packet_id::kSync1), now);
      } else if (state_ == State::Sync1 && p.id == packet_id::kSync1 && p.payload.empty()) {
        state_ = State::Sync2;
        attemptStart_ = now;
        send(encodeCommand(packet_id::kSync2), now);
      } else {
        ++counters_.otherPackets;
      }
      return;
    case State::Sync2:
      if (p.id == packet_id::kSync2) {
        onServerInfo(p, now);
      } else {
        ++counters_.otherPackets;
      }
      return;
    case State::Open:
      break;
  }
  if (p.id == packet_id::kSipStopped || p.id == packet_id::kSipMoving) {
    const std::optional<Sip> sip = decodeSip(p.payload, p.id == packet_id::kSipMoving);
    if (!sip) {
      ++counters_.malformedSips;
      return;
    }
    ++counters_.sips;
    const std::uint64_t droppedBefore = tracker_->droppedReadings();
    Scan scan = tracker_->apply(*sip, now);
    counters_.droppedReadings += tracker_->droppedReadings() - droppedBefore;
    counters_.readings += scan.readings.size();
    std::vector<Scan> ready;
    stitcher_.add(std::move(scan), simulator_, ready);
    deliver(ready);
  } else if (p.id == packet_id::kSimStat) {
    const std::optional<SimStat> stat = decodeSimStat(p.payload);
    if (!stat) {
      ++counters_.malformedSimStats;
      return;
    }
    ++counters_.simStats;
    tracker_->setTruth(*stat);
  } else {
    ++counters_.otherPackets;
  }
}

RobotParameters ClientSession::chooseRobot(const ServerInfo& info, bool valid) {
  if (settings_.robot) return *settings_.robot;
  if (const auto p = parametersForSubclass(info.subclass)) return *p;
  listener_.onWarning(
      (valid ? "the robot reports subclass '" + info.subclass + "', which SonarGrid does not know"
             : std::string("the robot's handshake reply names no subclass")) +
      ": reading it as a Pioneer 3-DX (give the robot to override)");
  return pioneer3dxParameters();
}

void ClientSession::onServerInfo(const Packet& p, double now) {
  std::optional<ServerInfo> info = decodeServerInfo(p.payload);
  const bool valid = info.has_value();
  if (!valid) {
    ++counters_.malformedServerInfo;
    info = ServerInfo{};
  }
  flushScans();
  stitcher_.newSegment();
  server_ = *info;
  robot_ = chooseRobot(*info, valid);
  tracker_.emplace(*robot_);
  drove_ = false;
  state_ = State::Open;
  ++counters_.handshakes;
  send(encodeCommand(command::kOpen, 1), now);
  send(encodeCommand(command::kEnable, 1), now);
  send(encodeCommand(command::kSonar, 1), now);
  const bool simulator =
      settings_.simStat == SimStatRequest::Always ||
      (settings_.simStat == SimStatRequest::Auto && looksLikeSimulator(info->name));
  if (simulator) send(encodeCommand(command::kSimStat, 2), now);
  simulator_ = simulator;
  listener_.onConnected(*server_, *robot_);
}

void ClientSession::tick(double now) {
  switch (state_) {
    case State::Idle:
      return;
    case State::Sync0:
    case State::Sync1:
    case State::Sync2:
      if (now - handshakeStart_ >= settings_.handshakeTimeout) {
        lose(handshakeFailure());
      } else if (now - attemptStart_ >= settings_.syncRetry) {
        restartHandshake(now);
      }
      return;
    case State::Open:
      if (now - lastReceived_ >= settings_.lostAfter) {
        lose("no packet from the robot for " + seconds(now - lastReceived_) + " s");
        return;
      }
      if (now - lastSent_ >= settings_.pulseAfter) {
        ++counters_.pulses;
        send(encodeCommand(command::kPulse), now);
      }
      return;
  }
}

void ClientSession::sendCommand(std::span<const std::uint8_t> bytes, double now) {
  if (state_ == State::Open) send(bytes, now);
}

void ClientSession::setVelocity(double metresPerSecond, double radiansPerSecond, double now) {
  if (state_ != State::Open) return;
  drove_ = true;
  send(encodeCommand(command::kVel, clampedUnits(metresPerSecond * 1000.0)), now);
  send(encodeCommand(command::kRVel, clampedUnits(radToDeg(radiansPerSecond))), now);
}

void ClientSession::setWheelVelocities(double leftMetresPerSecond, double rightMetresPerSecond,
                                       double now) {
  if (state_ != State::Open) return;
  drove_ = true;
  send(encodeVel2(leftMetresPerSecond * 1000.0, rightMetresPerSecond * 1000.0, robot_->vel2Divisor),
       now);
}

void ClientSession::setSpeedLimits(double metresPerSecond, double radiansPerSecond, double now) {
  if (state_ != State::Open) return;
  send(encodeCommand(command::kSetV, std::abs(clampedUnits(metresPerSecond * 1000.0))), now);
  send(encodeCommand(command::kSetRv, std::abs(clampedUnits(radToDeg(radiansPerSecond)))), now);
}

void ClientSession::stop(double now) {
  if (state_ == State::Open) send(encodeCommand(command::kStop), now);
}

void ClientSession::close(double now) {
  if (state_ == State::Open) {
    if (drove_) send(encodeCommand(command::kStop), now);
    send(encodeCommand(command::kClose), now);
  }
  flushScans();
  state_ = State::Idle;
}

void ClientSession::deliver(std::vector<Scan>& scans) {
  counters_.segments = stitcher_.segments();
  counters_.stitched = stitcher_.stitched();
  for (const Scan& scan : scans) listener_.onScan(scan);
  scans.clear();
}

void ClientSession::flushScans() {
  std::vector<Scan> ready;
  stitcher_.flush(ready);
  deliver(ready);
}

std::span<const double> ClientSession::latestRanges() const {
  if (!tracker_) return {};
  return tracker_->latestRanges();
}

}  // namespace sg::arcos
