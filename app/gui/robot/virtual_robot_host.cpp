// SPDX-License-Identifier: GPL-3.0-or-later
#include "robot/virtual_robot_host.h"

#include <QDir>
#include <QHostAddress>
#include <QThread>

#include "sonargrid/arcos/virtual_robot.h"
#include "sonargrid/arcos/virtual_route.h"
#include "sonargrid/live/arcos_server.h"
#include "sonargrid/reference/reference_json.h"
#include "sonargrid/sim/route.h"

namespace sg::app {

VirtualRobotHost::VirtualRobotHost(QObject* parent) : QObject(parent) {}

VirtualRobotHost::~VirtualRobotHost() {
  stop();
}

bool VirtualRobotHost::start(const Options& options, QString* error) {
  stop();
  auto fail = [error](const QString& why) {
    if (error) *error = why;
    return false;
  };
  const std::optional<arcos::RobotParameters> robot = arcos::robotPreset(options.robot);
  if (!robot)
    return fail(tr("unknown robot '%1'; choose one of %2")
                    .arg(QString::fromStdString(options.robot),
                         QString::fromStdString(arcos::robotPresetNames())));
  const std::string path = QDir::toNativeSeparators(options.world).toStdString();
  arcos::VirtualRobotSettings settings = arcos::virtualRobotSettings(*robot, options.timeScale);
  settings.physics.seed = options.seed;
  try {
    const ReferenceMap map = readReferenceJson(path);
    SimulationSettings sim;
    if (options.route) sim.route = *options.route;
    // The world's own route (route.txt beside it) where it has one: the route planned from the
    // world's bounds alone crosses the bundled worlds' furniture (issue 49).
    const arcos::VirtualRoute route = arcos::planVirtualRoute(
        map, settings.robot.ring, sim, options.route ? worldRoute(path) : std::vector<Position>{},
        !options.route);
    robot_ =
        std::make_unique<arcos::VirtualRobot>(sonarWorld(map), route.start, route.plan, settings);
  } catch (const std::exception& e) {
    // The reader's messages name the file; the planner's do not.
    const QString what = QString::fromStdString(e.what());
    return fail(what.contains(QString::fromStdString(path))
                    ? what
                    : QString::fromStdString(path) + QStringLiteral(": ") + what);
  }

  options_ = options;
  thread_ = new QThread;
  thread_->setObjectName(QStringLiteral("virtual robot"));
  context_ = new QObject;
  context_->moveToThread(thread_);
  thread_->start();
  QString listenError;
  QMetaObject::invokeMethod(
      context_,
      [this, &listenError] {
        server_ = std::make_unique<live::ArcosServer>(*robot_, options_.timeScale);
        // Its signals reach this object on the GUI thread (queued: another thread emits them).
        connect(server_.get(), &live::ArcosServer::clientConnected, this,
                &VirtualRobotHost::clientConnected);
        connect(server_.get(), &live::ArcosServer::clientDisconnected, this,
                &VirtualRobotHost::clientDisconnected);
        if (!server_->listen(QHostAddress::LocalHost, 0, &listenError)) server_.reset();
        port_ = server_ ? server_->port() : 0;
      },
      Qt::BlockingQueuedConnection);
  if (port_ == 0) {
    stop();
    return fail(tr("cannot listen on 127.0.0.1: %1").arg(listenError));
  }
  return true;
}

void VirtualRobotHost::stop() {
  if (!thread_) return;
  QMetaObject::invokeMethod(
      context_,
      [this] {
        if (server_) server_->shutdown();
        server_.reset();
      },
      Qt::BlockingQueuedConnection);
  thread_->quit();
  thread_->wait();
  delete context_;
  context_ = nullptr;
  delete thread_;
  thread_ = nullptr;
  robot_.reset();
  port_ = 0;
  emit stopped();
}

}  // namespace sg::app
