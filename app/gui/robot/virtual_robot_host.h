// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The app's "Start Virtual Robot": the virtual robot of `sonargrid-cli robot` (an ARCOS server
// simulating a Pioneer 3-DX or an AmigoBot in a world file) served in-process on a free loopback
// port, in a thread of its own, so that the GUI's work never delays its SIPs (docs/live-robot.md,
// "In the app").

#include <QObject>
#include <QString>
#include <memory>
#include <optional>
#include <string>

#include "sonargrid/sim/simulation.h"

class QThread;

namespace sg::arcos {
class VirtualRobot;
}
namespace sg::live {
class ArcosServer;
}

namespace sg::app {

class VirtualRobotHost : public QObject {
  Q_OBJECT

 public:
  struct Options {
    QString world;               // a reference-map JSON (datasets/*/world.json)
    std::string robot = "p3dx";  // p3dx or amigobot
    std::optional<RouteKind> route = RouteKind::InMotion;  // none: wait for the client's commands
    double timeScale = 1.0;  // simulated seconds per real second (tests run it faster)
    std::uint64_t seed = 1;
  };

  explicit VirtualRobotHost(QObject* parent = nullptr);
  ~VirtualRobotHost() override;  // stops the robot

  // Reads the world, plans the route and starts serving on 127.0.0.1 at a port the system picks.
  // False with `error` saying why (the file and what is wrong with it).
  bool start(const Options& options, QString* error);
  // Hangs up the client and ends the robot's thread.
  void stop();
  bool running() const { return thread_ != nullptr; }
  quint16 port() const { return port_; }
  const Options& options() const { return options_; }

 signals:
  void clientConnected(const QString& peer);
  void clientDisconnected(const QString& peer, const QString& reason);
  void stopped();

 private:
  Options options_;
  QThread* thread_ = nullptr;
  QObject* context_ = nullptr;  // lives in thread_: the robot's work is queued to it
  std::unique_ptr<arcos::VirtualRobot> robot_;
  std::unique_ptr<live::ArcosServer> server_;  // created, used and destroyed in thread_
  quint16 port_ = 0;
};

}  // namespace sg::app
