// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The robot side of ARCOS, simulated and without any I/O of its own: a differential-drive robot in
// a world of the project's simulator (core/sonargrid/sim/), its sonar ring fired bank by bank as a
// Pioneer's controller fires it, and the server's half of the protocol. Bytes from the client and
// the passing of (simulated) time go in; the bytes to send come out. `sonargrid-cli robot` serves
// it over TCP (core/sonargrid/live/arcos_server.h); tests serve it over anything
// (docs/live-robot.md, "The virtual robot").

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "sonargrid/arcos/decoder.h"
#include "sonargrid/arcos/messages.h"
#include "sonargrid/arcos/robot_params.h"
#include "sonargrid/data/dataset.h"
#include "sonargrid/sim/differential_drive.h"
#include "sonargrid/sim/ray_sonar.h"

namespace sg::arcos {

struct VirtualRobotSettings {
  RobotParameters robot = pioneer3dxParameters();
  ServerInfo server{"SonarGridSim", "Pioneer", "p3dx"};
  SonarPhysics physics;
  std::optional<OdometryErrors> drift;   // none: the odometry is the true pose
  double sipInterval = 0.1;              // s between SIPs
  double firingInterval = 0.04;          // s between two sonars of one bank
  std::size_t bankSize = 8;              // consecutive transducers per bank; banks fire together
  double watchdog = 2.0;                 // s without a client packet: a client-driven robot stops
  double maxSpeed = 1.2;                 // m/s: VEL is clamped to it (SETV lowers it)
  double maxTurnRate = degToRad(300.0);  // rad/s: RVEL is clamped to it (SETRV lowers it)
  double step = 0.01;                    // s: the longest motion step
};

// How the robot drives itself until a client sends a motion command: a trajectory, with the robot
// standing still for `hold` seconds at each of `stops` (trajectory times, ascending), driven once
// or, with `repeat`, over and over (a lap that ends as it begins).
struct RoutePlan {
  Trajectory path;
  std::vector<double> stops;
  double hold = 0.0;
  bool repeat = false;
};

struct VirtualRobotCounters {
  std::uint64_t sessions = 0;  // handshakes completed
  std::uint64_t sips = 0;
  std::uint64_t simStats = 0;
  std::uint64_t readings = 0;
  std::uint64_t commands = 0;         // commands obeyed
  std::uint64_t ignoredCommands = 0;  // unknown or not applicable
  std::uint64_t badCommands = 0;      // valid frames with a malformed argument
  std::uint64_t stalls = 0;           // motion steps refused because the body would hit something
};

class VirtualRobot {
 public:
  VirtualRobot(SonarWorld world, const Pose2D& start, std::optional<RoutePlan> route,
               VirtualRobotSettings settings);

  // A client connected or left (times in simulated seconds). A new client must shake hands.
  void clientConnected(double now);
  void clientDisconnected(double now);
  // The controller restarts its odometry at (0, 0, 0) where the robot stands, as AMRISim does for
  // every new session and a Pioneer when it is switched on again.
  void resetOdometry();
  // Bytes from the client; the replies are appended to `out`.
  void receive(std::span<const std::uint8_t> bytes, double now, Bytes& out);
  // Moves the robot to `now` (never backwards), firing its sonars and appending the SIPs (and
  // SIMSTATs) due on the way while a client is open.
  void advanceTo(double now, Bytes& out);

  bool isOpen() const { return state_ == State::Open; }
  // The client sent CLOSE: the server should hang up.
  bool closeRequested() const { return closeRequested_; }
  bool clientDriving() const { return !following_; }
  double time() const { return time_; }
  const Pose2D& truePose() const { return true_; }
  const Pose2D& odometry() const { return odometry_; }
  const VirtualRobotCounters& counters() const { return counters_; }
  const FramingCounters& framing() const { return decoder_.counters(); }
  const VirtualRobotSettings& settings() const { return settings_; }

  // Called for every SIP sent, with the scan it stands for: the exact odometry and true poses at
  // the SIP and the readings it carries, each at its firing time (the server's own log).
  std::function<void(const Scan&)> onSip;

  // The distance from `p` to the nearest surface of the world (infinity for an empty world).
  static double clearance(const SonarWorld& world, const Position& p);

 private:
  enum class State { WaitSync0, WaitSync1, WaitSync2, WaitOpen, Open };

  void onPacket(const Packet& p, double now, Bytes& out);
  void onCommand(const Command& c, double now);
  void open(double now);
  void moveTo(double t);
  Pose2D routePose(double t) const;
  void fireBanks(double t);
  void sendSip(double t, Bytes& out);

  SonarWorld world_;
  std::optional<RoutePlan> route_;
  VirtualRobotSettings settings_;
  double bodyRadius_;
  double wheelbase_;

  State state_ = State::WaitSync0;
  PacketDecoder decoder_;
  bool closeRequested_ = false;
  VirtualRobotCounters counters_;
  double lastClientPacket_ = 0.0;
  int simStatMode_ = 0;  // 0 off, 1 once, 2 before every SIP

  // Motion.
  double time_ = 0.0;
  Pose2D true_;
  Pose2D odometry_;
  std::optional<Pose2D> odometryOrigin_;  // resetOdometry(): where the counters restarted
  std::optional<Odometry> drifting_;
  bool following_ = false;  // driving the route
  std::optional<double> routeStart_;
  bool motorsOn_ = true;
  double speed_ = 0.0;     // commanded, m/s
  double turnRate_ = 0.0;  // commanded, rad/s
  double maxSpeed_;
  double maxTurnRate_;
  double lastSpeed_ = 0.0;  // achieved in the last step (for LVEL, RVEL and the SIP ID)
  double lastTurnRate_ = 0.0;
  bool stalled_ = false;

  // Sonar.
  bool sonarsOn_ = true;
  SimRng rng_;
  double openTime_ = 0.0;
  std::uint64_t firings_ = 0;     // bank firings since OPEN
  std::uint64_t sipCount_ = 0;    // SIPs since OPEN
  std::vector<Reading> pending_;  // fired since the last SIP
};

}  // namespace sg::arcos
