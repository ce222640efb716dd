// SPDX-License-Identifier: GPL-3.0-or-later
// `sonargrid-cli record`: connects to a robot (TCP or serial), writes every reading with its
// odometry and, from a simulator, the true pose to a streamed .sglog as it arrives, and prints the
// link's statistics at the end (docs/cli.md, "record"; docs/live-robot.md). SIGINT, SIGTERM,
// --duration and a robot that vanishes all leave a complete log; SIGKILL leaves one that ends
// after its last complete scan.

#include <QCoreApplication>
#include <QTimer>
#include <csignal>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "commands.h"
#include "signal_watcher.h"
#include "sonargrid/io/sglog_recorder.h"
#include "sonargrid/io/start_pose.h"
#include "sonargrid/live/robot_link.h"
#include "sonargrid/live/wander.h"

namespace sg::cli {
namespace {

std::string fixed(double v, int decimals) {
  std::ostringstream s;
  s.precision(decimals);
  s << std::fixed << v;
  return s.str();
}

struct RecordResult {
  std::size_t scans = 0;
  std::size_t readings = 0;
  std::size_t echoes = 0;
  double firstTime = 0.0;
  double lastTime = 0.0;
};

nlohmann::ordered_json statsJson(const arcos::LinkCounters& c) {
  nlohmann::ordered_json o;
  o["bytes"] = c.framing.bytes;
  o["packets"] = c.framing.frames;
  o["sips"] = c.sips;
  o["simstats"] = c.simStats;
  o["readings"] = c.readings;
  o["bad_checksums"] = c.framing.badChecksums;
  o["bad_counts"] = c.framing.badCounts;
  o["skipped_bytes"] = c.framing.skippedBytes;
  o["malformed"] = {{"sip", c.malformedSips},
                    {"simstat", c.malformedSimStats},
                    {"server_info", c.malformedServerInfo}};
  o["other_packets"] = c.otherPackets;
  o["dropped_readings"] = c.droppedReadings;
  o["connections"] = c.handshakes;
  o["reconnects"] = c.reconnects;
  o["segments"] = c.segments;
  o["stitched"] = c.stitched;
  o["lost_connections"] = c.lostConnections;
  o["timeouts"] = c.timeouts;
  o["attempts"] = c.attempts;
  o["pulses"] = c.pulses;
  return o;
}

}  // namespace

int runRecord(Arguments& args) {
  const std::string connectTo = args.required("--connect");
  const std::string outPath = args.required("--out");
  const double duration = args.number("--duration", 0.0, 0.001, 1e7);
  const bool wander = args.flag("--wander");
  const std::optional<std::string> robotName = args.value("--robot");
  const bool json = args.flag("--json");
  std::optional<Pose2D> startPose;
  if (const auto start = args.value("--start-pose")) {
    std::string why;
    startPose = parseStartPose(*start, &why);
    if (!startPose) throw UsageError("--start-pose: " + why);
  }
  args.finish();

  live::LinkAddress address;
  try {
    address = live::parseLinkAddress(connectTo);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--connect ") + e.what());
  }
  live::RobotLink::Options options;
  if (robotName) {
    options.client.robot = arcos::robotPreset(*robotName);
    if (!options.client.robot) {
      throw UsageError("--robot expects " + arcos::robotPresetNames() + ", got '" + *robotName +
                       "'");
    }
  }

  static int argc = 1;
  static char name[] = "sonargrid-cli";
  static char* argv[] = {name, nullptr};
  QCoreApplication app(argc, argv);
  SignalWatcher stopSignals;
  live::RobotLink link(address, options);
  std::unique_ptr<SglogRecorder> log;
  std::optional<live::Wander> driver;
  RecordResult result;
  std::string stopReason;
  std::string failure;
  std::string lastProblem;
  auto say = [json](const std::string& line) {
    if (!json) std::cout << line << std::endl;
  };
  // Exceptions must not cross Qt's event loop: failures end the recording from here.
  auto fail = [&](const std::string& why) {
    if (failure.empty()) failure = why;
    app.quit();
  };

  QObject::connect(&link, &live::RobotLink::connected, &app,
                   [&](const QString& server, const QString& cls, const QString& sub) {
                     const arcos::RobotParameters& robot = *link.robot();
                     say("connected to " + server.toStdString() + " (" + cls.toStdString() + " " +
                         sub.toStdString() + ") at " + address.text() + "; reading it as " +
                         robot.preset);
                     if (log) {
                       if (!(robot.ring == log->ring())) {
                         fail("the robot at " + address.text() + " is now a " + robot.preset +
                              ", not the one the log was started with (" + log->ring().robot + ")");
                       }
                       return;
                     }
                     Dataset header;
                     header.name = "recorded from " + address.text() + ": " + server.toStdString() +
                                   " (" + cls.toStdString() + " " + sub.toStdString() + ")";
                     header.ring = robot.ring;
                     try {
                       log = std::make_unique<SglogRecorder>(outPath, header, 1.0, startPose);
                     } catch (const std::exception& e) {
                       fail(e.what());
                       return;
                     }
                     if (wander) driver.emplace(robot.ring);
                   });
  std::uint64_t loggedSegments = 0;
  std::uint64_t loggedStitched = 0;
  QObject::connect(&link, &live::RobotLink::scanReceived, &app, [&](const Scan& scan) {
    if (!log || !failure.empty()) return;
    try {
      // Each connection's scans are a segment (arcos/odometry_stitcher.h): the log says where one
      // begins and whether its odometry was stitched onto the one before.
      const arcos::LinkCounters& c = link.counters();
      if (c.segments != loggedSegments) {
        if (loggedSegments != 0) {
          log->comment("segment " + std::to_string(c.segments) +
                       " from t = " + fixed(scan.time, 3) + " s: " +
                       (c.stitched != loggedStitched
                            ? "odometry restarted by the robot, stitched onto the last pose of "
                              "segment " +
                                  std::to_string(loggedSegments)
                            : "odometry continues segment " + std::to_string(loggedSegments)));
        }
        loggedSegments = c.segments;
        loggedStitched = c.stitched;
      }
      log->append(scan);
    } catch (const std::exception& e) {
      fail(e.what());
      return;
    }
    if (result.scans == 0) result.firstTime = scan.time;
    result.lastTime = scan.time;
    ++result.scans;
    result.readings += scan.readings.size();
    for (const Reading& r : scan.readings) result.echoes += r.echo() ? 1 : 0;
    if (driver) {
      const auto [v, w] = driver->command(link.latestRanges(), scan.odometry, scan.time);
      link.setVelocity(v, w);
    }
  });
  QObject::connect(&link, &live::RobotLink::error, &app, [&](const QString& message) {
    lastProblem = message.toStdString();
    say(lastProblem);
  });
  QObject::connect(&link, &live::RobotLink::disconnected, &app, [&](const QString& reason) {
    lastProblem = reason.toStdString();
    say("connection to " + address.text() + " ended: " + lastProblem +
        (link.isActive() ? "; reconnecting" : ""));
  });
  QObject::connect(&stopSignals, &SignalWatcher::received, &app, [&](int number) {
    stopReason = number == SIGINT ? "SIGINT" : "SIGTERM";
    app.quit();
  });
  // What is appended reaches the disk at least once a second, also while no scan comes in.
  QTimer syncTimer;
  syncTimer.setInterval(1000);
  QObject::connect(&syncTimer, &QTimer::timeout, &app, [&] {
    try {
      if (log) log->sync();
    } catch (const std::exception& e) {
      fail(e.what());
    }
  });
  syncTimer.start();
  QTimer durationTimer;
  if (duration > 0.0) {
    durationTimer.setSingleShot(true);
    durationTimer.setTimerType(Qt::PreciseTimer);
    QObject::connect(&durationTimer, &QTimer::timeout, &app, [&] {
      stopReason = "--duration " + fixed(duration, 3) + " s";
      app.quit();
    });
    durationTimer.start(static_cast<int>(std::min(duration * 1000.0, 2.0e9)));
  }

  link.open();
  app.exec();
  link.close();
  if (log && failure.empty()) {
    try {
      log->finish();
    } catch (const std::exception& e) {
      failure = e.what();
    }
  }

  const arcos::LinkCounters& c = link.counters();
  const std::string robotPreset = link.robot() ? link.robot()->preset : "";
  if (json) {
    nlohmann::ordered_json o;
    o["connect"] = address.text();
    o["out"] = outPath;
    o["written"] = log != nullptr;
    if (link.server()) {
      o["server"] = {{"name", link.server()->name},
                     {"class", link.server()->robotClass},
                     {"subclass", link.server()->subclass}};
      o["robot"] = robotPreset;
    }
    o["scans"] = result.scans;
    o["readings"] = result.readings;
    o["echoes"] = result.echoes;
    o["duration_s"] = result.lastTime - result.firstTime;
    o["stopped_by"] = failure.empty() ? stopReason : std::string("error");
    o["link"] = statsJson(c);
    std::cout << o.dump() << std::endl;
  } else {
    if (log) {
      std::cout << outPath << ": " << result.scans << " scans, " << result.readings << " readings ("
                << result.echoes << " echoes) over " << fixed(result.lastTime - result.firstTime, 1)
                << " s\n";
    }
    std::cout << "link " << address.text() << ": " << c.framing.frames << " packets (" << c.sips
              << " SIPs, " << c.simStats << " SIMSTATs), " << c.framing.badChecksums
              << " bad checksums, " << c.errors() - c.framing.badChecksums
              << " other malformed packets, " << c.framing.skippedBytes << " bytes skipped, "
              << c.handshakes << " connections, " << c.reconnects << " reconnects, " << c.segments
              << " segments (" << c.stitched << " stitched), " << c.lostConnections << " lost, "
              << c.timeouts << " timed out, " << c.readings << " readings\n";
  }
  if (!failure.empty()) throw std::runtime_error(failure);
  if (!log) {
    throw std::runtime_error("never connected to " + address.text() +
                             (lastProblem.empty() ? std::string() : " (" + lastProblem + ")") +
                             "; nothing was written");
  }
  return 0;
}

}  // namespace sg::cli
