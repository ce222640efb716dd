// SPDX-License-Identifier: GPL-3.0-or-later
// `sonargrid-cli robot`: the virtual robot, an ARCOS server that simulates a Pioneer 3-DX or an
// AmigoBot and its sonar in a world (docs/cli.md, "robot"; docs/live-robot.md, "The virtual
// robot"). It serves one client at a time until --duration or SIGINT/SIGTERM.

#include <QCoreApplication>
#include <QHostAddress>
#include <QTimer>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "commands.h"
#include "signal_watcher.h"
#include "sonargrid/arcos/virtual_robot.h"
#include "sonargrid/arcos/virtual_route.h"
#include "sonargrid/base/log_error.h"
#include "sonargrid/io/sglog_recorder.h"
#include "sonargrid/live/arcos_server.h"
#include "sonargrid/reference/reference_json.h"
#include "sonargrid/sim/simulation.h"

namespace sg::cli {
namespace {

std::string fixed(double v, int decimals) {
  std::ostringstream s;
  s.precision(decimals);
  s << std::fixed << v;
  return s.str();
}

bool onOff(Arguments& args, const std::string& name, bool fallback) {
  const auto v = args.value(name);
  if (!v) return fallback;
  if (*v == "on") return true;
  if (*v == "off") return false;
  throw UsageError(name + " expects on or off, got '" + *v + "'");
}

}  // namespace

int runRobot(Arguments& args) {
  const std::string worldPath = args.required("--world");
  const std::string robotName = args.value("--robot").value_or("p3dx");
  const int port = args.integer("--port", 8101, 0, 65535);
  const std::string bind = args.value("--bind").value_or("127.0.0.1");
  const bool teleop = args.flag("--teleop");
  const std::optional<std::string> routeName = args.value("--route");
  const std::optional<std::string> routeFile = args.value("--route-file");
  const int stops = args.integer("--stops", 0, 1, 10000);
  const double duration = args.number("--duration", 0.0, 0.001, 1e7);
  const double timeScale = args.number("--time-scale", 1.0, 0.01, 100.0);
  const std::optional<std::string> logOut = args.value("--log-out");
  std::optional<std::uint64_t> seed;
  if (const auto text = args.value("--seed")) seed = parseSeed(*text);
  const bool drift = onOff(args, "--drift", false);
  args.finish();

  const std::optional<arcos::RobotParameters> robot = arcos::robotPreset(robotName);
  if (!robot) {
    throw UsageError("--robot expects " + arcos::robotPresetNames() + ", got '" + robotName + "'");
  }
  arcos::VirtualRobotSettings settings = arcos::virtualRobotSettings(*robot, timeScale);
  SonarPhysics& p = settings.physics;
  if (seed) p.seed = *seed;
  if (drift) settings.drift = defaultDrift();
  if (teleop && (routeName || routeFile || stops != 0))
    throw UsageError(
        "--teleop drives by the client's commands: give no --route, --route-file or --stops");
  SimulationSettings sim;
  if (routeName) {
    const std::optional<RouteKind> kind = routeKindFromName(*routeName);
    if (!kind)
      throw UsageError("--route expects in-motion, stop-and-scan or u-turn, got '" + *routeName +
                       "'");
    sim.route = *kind;
  }
  if (stops != 0 && sim.route != RouteKind::StopAndScan)
    throw UsageError("--stops is only for --route stop-and-scan");
  if (stops != 0) sim.stops = stops;
  QHostAddress bindAddress;
  if (!bindAddress.setAddress(QString::fromStdString(bind)))
    throw UsageError("--bind expects an IP address such as 127.0.0.1 or 0.0.0.0, got '" + bind +
                     "'");

  ReferenceMap map;
  std::vector<Position> waypoints;
  try {
    map = readReferenceJson(worldPath);
    if (routeFile)
      waypoints = readRouteFile(*routeFile);
    else if (!teleop)
      waypoints = worldRoute(worldPath);  // the world's own route.txt, if it has one
  } catch (const LogError& e) {
    throw InputError(e.what());
  }
  const SonarWorld world = sonarWorld(map);
  arcos::VirtualRoute route;
  try {
    route = arcos::planVirtualRoute(map, settings.robot.ring, sim, waypoints, teleop);
  } catch (const arcos::RouteClearanceError& e) {
    throw InputError(e.what());
  } catch (const std::invalid_argument& e) {
    throw InputError(worldPath + ": " + e.what());
  }

  arcos::VirtualRobot virtualRobot(world, route.start, route.plan, settings);
  std::unique_ptr<SglogRecorder> log;
  if (logOut) {
    Dataset header;
    header.name = "virtual " + robotName + " in " +
                  std::filesystem::path(worldPath).filename().string() + " (ground truth), seed " +
                  std::to_string(p.seed);
    header.ring = settings.robot.ring;
    log = std::make_unique<SglogRecorder>(*logOut, header);
  }

  static int argc = 1;
  static char name[] = "sonargrid-cli";
  static char* argv[] = {name, nullptr};
  QCoreApplication app(argc, argv);
  SignalWatcher stopSignals;
  live::ArcosServer server(virtualRobot, timeScale);
  QString error;
  if (!server.listen(bindAddress, static_cast<quint16>(port), &error)) {
    throw std::runtime_error("cannot listen on " + bind + ":" + std::to_string(port) + ": " +
                             error.toStdString());
  }
  const std::string mode = teleop ? std::string("driven by the client")
                                  : std::string(routeKindName(sim.route)) + " route";
  std::cout << "sonargrid-cli robot: listening on " << server.address().toString().toStdString()
            << ':' << server.port() << " (" << robotName << " in " << worldPath << ", " << mode
            << ")" << std::endl;

  auto say = [](const std::string& line) { std::cout << line << std::endl; };
  QObject::connect(&server, &live::ArcosServer::clientConnected, &app, [&](const QString& peer) {
    say("client " + peer.toStdString() + " connected");
  });
  QObject::connect(&server, &live::ArcosServer::clientDisconnected, &app,
                   [&](const QString& peer, const QString& reason) {
                     say("client " + peer.toStdString() + " left: " + reason.toStdString());
                   });
  QObject::connect(&server, &live::ArcosServer::clientRefused, &app, [&](const QString& peer) {
    say("refused client " + peer.toStdString() + ": this robot serves one client at a time");
  });
  std::string stopReason;
  std::string failure;
  if (log) {
    // Exceptions must not cross Qt's event loop: a log that can no longer be written stops the
    // server from here.
    virtualRobot.onSip = [&](const Scan& s) {
      if (!failure.empty()) return;
      try {
        log->append(s);
      } catch (const std::exception& e) {
        failure = e.what();
        app.quit();
      }
    };
  }
  QObject::connect(&stopSignals, &SignalWatcher::received, &app, [&](int number) {
    stopReason = number == SIGINT ? "SIGINT" : "SIGTERM";
    app.quit();
  });
  QTimer clock;
  if (duration > 0.0) {
    clock.setInterval(10);
    QObject::connect(&clock, &QTimer::timeout, &app, [&] {
      if (server.simTime() >= duration) {
        stopReason = "--duration " + fixed(duration, 3) + " s";
        app.quit();
      }
    });
    clock.start();
  }
  app.exec();
  server.shutdown();
  virtualRobot.onSip = nullptr;
  if (log && failure.empty()) log->finish();
  const arcos::VirtualRobotCounters& c = virtualRobot.counters();
  say("stopped by " + (failure.empty() ? stopReason : std::string("an error")) + " after " +
      fixed(server.simTime(), 1) + " s: sessions " + std::to_string(c.sessions) + ", SIPs " +
      std::to_string(c.sips) + ", readings " + std::to_string(c.readings) + ", commands " +
      std::to_string(c.commands) + " (ignored " + std::to_string(c.ignoredCommands) + ")");
  if (!failure.empty()) throw std::runtime_error(failure);
  return 0;
}

}  // namespace sg::cli
