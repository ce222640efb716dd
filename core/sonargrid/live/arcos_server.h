// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The virtual robot (arcos/virtual_robot.h) served over TCP, one client at a time, as a
// MobileSim-style simulator is: a second client is refused (its connection is closed at once and
// the refusal reported), a client silent for longer than an ARCOS client may be is hung up, and
// the robot's clock runs `timeScale` simulated seconds per real second (docs/live-robot.md, "The
// virtual robot").

#include <QElapsedTimer>
#include <QHostAddress>
#include <QObject>
#include <QPointer>
#include <QString>
#include <QTcpServer>
#include <QTcpSocket>
#include <QTimer>

#include "sonargrid/arcos/virtual_robot.h"

namespace sg::live {

class ArcosServer : public QObject {
  Q_OBJECT

 public:
  // `robot` must outlive the server.
  explicit ArcosServer(arcos::VirtualRobot& robot, double timeScale = 1.0,
                       QObject* parent = nullptr);
  ~ArcosServer() override;

  // Starts listening (port 0: any free port) and the robot's clock; false with `error` set when
  // the address cannot be bound. After shutdown() it starts again where the clock stopped.
  bool listen(const QHostAddress& address, quint16 port, QString* error);
  quint16 port() const { return server_.serverPort(); }
  QHostAddress address() const { return server_.serverAddress(); }
  // Simulated seconds since listen().
  double simTime() const;
  bool hasClient() const { return client_ != nullptr; }
  // Hangs up the client (flushing what was sent to it), stops listening and stops the robot's
  // clock: a controller that is off does not drive, so the robot stands where it is.
  void shutdown();

 signals:
  void clientConnected(const QString& peer);
  void clientDisconnected(const QString& peer, const QString& reason);
  void clientRefused(const QString& peer);

 private:
  void onNewConnection();
  void onClientBytes();
  void onTick();
  void hangUp(const QString& reason);
  void flush(const arcos::Bytes& bytes);

  arcos::VirtualRobot& robot_;
  double timeScale_;
  QTcpServer server_;
  QPointer<QTcpSocket> client_;
  QString peer_;
  QElapsedTimer clock_;      // real time since listen()
  double clockStart_ = 0.0;  // simulated seconds at listen()
  QElapsedTimer lastHeard_;  // real time since the client last sent a byte
  QTimer tick_;
};

}  // namespace sg::live
