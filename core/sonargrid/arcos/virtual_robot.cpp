// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/arcos/virtual_robot.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sonargrid/sim/simulation.h"

namespace sg::arcos {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// The odometry noise has its own engine, as in the simulator (simulation.cpp), so that drift on or
// off leaves the sonar readings of a seed unchanged. The salt is the 64-bit golden-ratio constant.
constexpr std::uint64_t kOdometrySeedSalt = 0x9E3779B97F4A7C15ULL;
// 13.0 V, a charged Pioneer battery, in the SIP's 0.1 V units.
constexpr std::uint8_t kBatteryDecivolts = 130;
// STALL/BUMP: bit 0 the left wheel stalled, bit 8 the right wheel stalled.
constexpr std::uint16_t kBothWheelsStalled = 0x0101;
// A 15-bit position counter holds this many units.
constexpr long kCounterRange = 0x8000;

std::uint16_t counter15(double units) {
  const long v = std::lround(units) % kCounterRange;
  return static_cast<std::uint16_t>(v < 0 ? v + kCounterRange : v);
}

std::int16_t clamp16(double v) {
  if (!std::isfinite(v)) return 0;
  return static_cast<std::int16_t>(std::clamp(std::round(v), -32768.0, 32767.0));
}

std::int32_t clamp32(double v) {
  return static_cast<std::int32_t>(std::clamp(std::round(v), -2147483648.0, 2147483647.0));
}

double segmentDistance(const Position& p, const Position& a, const Position& b) {
  const Position ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

}  // namespace

double VirtualRobot::clearance(const SonarWorld& world, const Position& p) {
  double d = kInf;
  for (const Segment& s : world.segments) d = std::min(d, segmentDistance(p, s.a, s.b));
  for (const Circle& c : world.circles) d = std::min(d, std::abs((p - c.centre).norm() - c.radius));
  return d;
}

VirtualRobot::VirtualRobot(SonarWorld world, const Pose2D& start, std::optional<RoutePlan> route,
                           VirtualRobotSettings settings)
    : world_(std::move(world)),
      route_(std::move(route)),
      settings_(std::move(settings)),
      bodyRadius_(robotBody(settings_.robot.ring).radius),
      wheelbase_(settings_.robot.wheelbase),
      true_(start),
      odometry_(start),
      following_(route_.has_value()),
      maxSpeed_(settings_.maxSpeed),
      maxTurnRate_(settings_.maxTurnRate),
      rng_(settings_.physics.seed) {
  if (settings_.drift) {
    drifting_.emplace(start, wheelbase_, *settings_.drift,
                      settings_.physics.seed ^ kOdometrySeedSalt);
  }
  if (settings_.bankSize == 0) settings_.bankSize = 1;
}

void VirtualRobot::clientConnected(double now) {
  state_ = State::WaitSync0;
  closeRequested_ = false;
  decoder_.reset();
  pending_.clear();
  simStatMode_ = 0;
  lastClientPacket_ = now;
}

void VirtualRobot::resetOdometry() {
  // The counters restart where the robot stands: the pose they measure from is the current one.
  const Pose2D measured = drifting_ ? drifting_->pose() : true_;
  odometryOrigin_ = measured;
  odometry_ = Pose2D();
}

void VirtualRobot::clientDisconnected(double now) {
  clientConnected(now);
}

void VirtualRobot::receive(std::span<const std::uint8_t> bytes, double now, Bytes& out) {
  decoder_.feed(bytes, [&](const Packet& p) { onPacket(p, now, out); });
}

void VirtualRobot::onPacket(const Packet& p, double now, Bytes& out) {
  lastClientPacket_ = now;
  const bool bare = p.payload.empty();
  // SYNC0 restarts the handshake from any state but open (where ID 0 is PULSE).
  if (state_ != State::Open && p.id == packet_id::kSync0 && bare) {
    const Bytes echo = encodeCommand(packet_id::kSync0);
    out.insert(out.end(), echo.begin(), echo.end());
    state_ = State::WaitSync1;
    return;
  }
  switch (state_) {
    case State::WaitSync0:
      return;
    case State::WaitSync1:
      if (p.id == packet_id::kSync1 && bare) {
        const Bytes echo = encodeCommand(packet_id::kSync1);
        out.insert(out.end(), echo.begin(), echo.end());
        state_ = State::WaitSync2;
      }
      return;
    case State::WaitSync2:
      if (p.id == packet_id::kSync2 && bare) {
        const Bytes info = encodeServerInfo(settings_.server);
        out.insert(out.end(), info.begin(), info.end());
        state_ = State::WaitOpen;
      }
      return;
    case State::WaitOpen:
      if (p.id == command::kOpen) open(now);
      return;
    case State::Open:
      break;
  }
  if (const std::optional<Command> c = decodeCommand(p)) {
    onCommand(*c, now);
  } else {
    ++counters_.badCommands;
  }
}

void VirtualRobot::open(double now) {
  // The robot reaches `now` before its sonars start, so that the first firing is not in its past.
  Bytes none;
  advanceTo(now, none);
  state_ = State::Open;
  ++counters_.sessions;
  openTime_ = now;
  firings_ = 0;
  sipCount_ = 0;
  pending_.clear();
  if (following_ && !routeStart_) routeStart_ = now;
}

void VirtualRobot::onCommand(const Command& c, double now) {
  using Arg = Command::Argument;
  const bool isInt = c.argument == Arg::Int;
  auto needInt = [&]() {
    if (!isInt) ++counters_.badCommands;
    return isInt;
  };
  switch (c.number) {
    case command::kPulse:
      break;
    case command::kClose:
      closeRequested_ = true;
      state_ = State::WaitSync0;
      speed_ = turnRate_ = 0.0;
      pending_.clear();
      break;
    case command::kEnable:
      if (!needInt()) return;
      motorsOn_ = c.value != 0;
      break;
    case command::kSonar:
      if (!needInt()) return;
      if (c.value != 0 && !sonarsOn_) {
        // Resume the firing schedule from now rather than catching up on the time it was off.
        firings_ = static_cast<std::uint64_t>(
            std::ceil(std::max(0.0, now - openTime_) / settings_.firingInterval - 1e-9));
      }
      sonarsOn_ = c.value != 0;
      break;
    case command::kVel:
      if (!needInt()) return;
      following_ = false;
      speed_ = std::clamp(c.value / 1000.0, -maxSpeed_, maxSpeed_);
      break;
    case command::kRVel:
      if (!needInt()) return;
      following_ = false;
      turnRate_ = std::clamp(degToRad(c.value), -maxTurnRate_, maxTurnRate_);
      break;
    case command::kVel2: {
      if (!needInt()) return;
      following_ = false;
      const WheelBytes w = vel2Wheels(c.value);
      const double left = w.left * settings_.robot.vel2Divisor / 1000.0;
      const double right = w.right * settings_.robot.vel2Divisor / 1000.0;
      speed_ = std::clamp(0.5 * (left + right), -maxSpeed_, maxSpeed_);
      turnRate_ = std::clamp((right - left) / wheelbase_, -maxTurnRate_, maxTurnRate_);
      break;
    }
    case command::kSetV:
      if (!needInt()) return;
      maxSpeed_ = std::clamp(c.value / 1000.0, 0.0, settings_.maxSpeed);
      speed_ = std::clamp(speed_, -maxSpeed_, maxSpeed_);
      break;
    case command::kSetRv:
      if (!needInt()) return;
      maxTurnRate_ = std::clamp(degToRad(c.value), 0.0, settings_.maxTurnRate);
      turnRate_ = std::clamp(turnRate_, -maxTurnRate_, maxTurnRate_);
      break;
    case command::kStop:
    case command::kEStop:
      following_ = false;
      speed_ = turnRate_ = 0.0;
      break;
    case command::kSimStat:
      if (!needInt()) return;
      if (c.value < 0 || c.value > 2) {
        ++counters_.ignoredCommands;
        return;
      }
      simStatMode_ = c.value;
      break;
    default:
      ++counters_.ignoredCommands;
      return;
  }
  ++counters_.commands;
}

Pose2D VirtualRobot::routePose(double t) const {
  // Elapsed route time to trajectory time: the clock of the trajectory stops during each hold.
  double tt = t - *routeStart_;
  for (const double stop : route_->stops) {
    if (tt <= stop) break;
    tt = tt <= stop + route_->hold ? stop : tt - route_->hold;
  }
  const double lap = route_->path.duration();
  if (route_->repeat && lap > 0.0) tt = std::fmod(tt, lap);
  return route_->path.poseAt(tt);
}

void VirtualRobot::moveTo(double t) {
  while (time_ < t) {
    const double dt = std::min(settings_.step, t - time_);
    const double next = time_ + dt;
    Pose2D target = true_;
    stalled_ = false;
    if (following_) {
      if (routeStart_) target = routePose(next);
    } else {
      // A real controller stops when its client has gone quiet (the ARCOS watchdog).
      if (next - lastClientPacket_ > settings_.watchdog) speed_ = turnRate_ = 0.0;
      const double v = motorsOn_ ? speed_ : 0.0;
      const double w = motorsOn_ ? turnRate_ : 0.0;
      if (v != 0.0 || w != 0.0) {
        target = integrateUnicycle(true_, v, w, dt);
        const double after = clearance(world_, target.position);
        // A step into a surface is refused (the wheels stall); one that backs away is allowed.
        if (after < bodyRadius_ && after < clearance(world_, true_.position)) {
          target = true_;
          stalled_ = true;
          ++counters_.stalls;
        }
      }
    }
    const Position d = target.position - true_.position;
    lastSpeed_ = (d.x() * std::cos(true_.heading) + d.y() * std::sin(true_.heading)) / dt;
    lastTurnRate_ = wrapAngle(target.heading - true_.heading) / dt;
    if (drifting_) {
      drifting_->step(true_, target);
      odometry_ = drifting_->pose();
    } else {
      odometry_ = target;
    }
    if (odometryOrigin_) odometry_ = relativePose(*odometryOrigin_, odometry_);
    true_ = target;
    time_ = next;
  }
}

void VirtualRobot::fireBanks(double t) {
  const SonarRing& ring = settings_.robot.ring;
  const std::size_t n = ring.size();
  const double rangeConv = settings_.robot.rangeConvFactor;
  for (std::size_t first = 0; first < n; first += settings_.bankSize) {
    const std::size_t len = std::min(settings_.bankSize, n - first);
    const std::size_t sonar = first + static_cast<std::size_t>(firings_ % len);
    const Pose2D sensor = true_.compose(ring.sonars[sonar].pose);
    const double range = fireSonar(world_, sensor, ring, settings_.physics, rng_);
    // The SIP carries whole sonar units; the reading is what a client reads back from them, so
    // that the server's log and a client's agree exactly.
    double raw = std::isfinite(range) ? std::round(range * 1000.0 / rangeConv) : kInf;
    if (!(raw * rangeConv < settings_.robot.maxRangeMm)) {
      raw = std::round(settings_.robot.maxRangeMm / rangeConv);
    }
    raw = std::min(raw, 65535.0);
    Reading r;
    r.sonar = static_cast<std::uint16_t>(sonar);
    const double mm = raw * rangeConv;
    r.range = mm >= settings_.robot.maxRangeMm ? Reading::kNoEcho : mm / 1000.0;
    r.time = t;
    pending_.push_back(r);
  }
}

void VirtualRobot::sendSip(double t, Bytes& out) {
  const RobotParameters& rp = settings_.robot;
  if (simStatMode_ != 0) {
    SimStat stat;
    stat.simInterval = static_cast<std::uint16_t>(std::lround(settings_.sipInterval * 1000.0));
    stat.realInterval = stat.simInterval;
    stat.lastInterval = stat.simInterval;
    stat.trueX = clamp32(true_.x() * 1000.0);
    stat.trueY = clamp32(true_.y() * 1000.0);
    stat.trueThetaDeg = clamp32(radToDeg(wrapAngle(true_.heading)));
    const Bytes bytes = encodeSimStat(stat);
    out.insert(out.end(), bytes.begin(), bytes.end());
    ++counters_.simStats;
    if (simStatMode_ == 1) simStatMode_ = 0;
  }
  // A SIP frame holds at most 58 readings; more can only pile up after a long stall of the
  // caller's clock, and then the oldest are the ones left out.
  constexpr std::size_t kMaxSipSonars = (kMaxSendBytes - 3 - 1 - kSipFixedBytes - 2) / 3;
  if (pending_.size() > kMaxSipSonars) {
    pending_.erase(pending_.begin(), pending_.end() - static_cast<std::ptrdiff_t>(kMaxSipSonars));
  }
  Sip sip;
  sip.moving = std::abs(lastSpeed_) > 1e-9 || std::abs(lastTurnRate_) > 1e-9;
  sip.xpos = counter15(odometry_.x() * 1000.0 / rp.distConvFactor);
  sip.ypos = counter15(odometry_.y() * 1000.0 / rp.distConvFactor);
  sip.thpos = clamp16(wrapAngle(odometry_.heading) / rp.angleConvFactor);
  const double half = 0.5 * lastTurnRate_ * wheelbase_;
  sip.leftVel = clamp16((lastSpeed_ - half) * 1000.0 / rp.velConvFactor);
  sip.rightVel = clamp16((lastSpeed_ + half) * 1000.0 / rp.velConvFactor);
  sip.battery = kBatteryDecivolts;
  sip.stallBump = stalled_ ? kBothWheelsStalled : 0;
  sip.flags = motorsOn_ ? kMotorsOnFlag : 0;
  sip.sonars.reserve(pending_.size());
  for (const Reading& r : pending_) {
    const double mm = r.echo() ? r.range * 1000.0 : rp.maxRangeMm;
    sip.sonars.push_back(
        SonarEcho{static_cast<std::uint8_t>(r.sonar),
                  static_cast<std::uint16_t>(std::lround(mm / rp.rangeConvFactor))});
  }
  const Bytes bytes = encodeSip(sip);
  out.insert(out.end(), bytes.begin(), bytes.end());
  ++counters_.sips;
  counters_.readings += pending_.size();
  if (onSip) {
    Scan scan;
    scan.time = t;
    scan.odometry = odometry_;
    scan.truth = true_;
    scan.readings = pending_;
    onSip(scan);
  }
  pending_.clear();
}

void VirtualRobot::advanceTo(double now, Bytes& out) {
  if (!(now > time_)) return;
  // The schedule is kept in whole microseconds since OPEN, so that a firing and a SIP due at the
  // same moment are recognised as such (the firing goes first and its reading is in that SIP).
  const auto fireUs = std::max<std::int64_t>(1, std::llround(settings_.firingInterval * 1e6));
  const auto sipUs = std::max<std::int64_t>(1, std::llround(settings_.sipInterval * 1e6));
  while (state_ == State::Open) {
    const std::int64_t nextFire = sonarsOn_ ? static_cast<std::int64_t>(firings_) * fireUs
                                            : std::numeric_limits<std::int64_t>::max();
    const std::int64_t nextSip = static_cast<std::int64_t>(sipCount_ + 1) * sipUs;
    const std::int64_t nextUs = std::min(nextFire, nextSip);
    const double t = openTime_ + static_cast<double>(nextUs) * 1e-6;
    if (t > now) break;
    moveTo(t);
    if (nextFire <= nextSip) {
      fireBanks(t);
      ++firings_;
    } else {
      sendSip(t, out);
      ++sipCount_;
    }
  }
  moveTo(now);
}

}  // namespace sg::arcos
