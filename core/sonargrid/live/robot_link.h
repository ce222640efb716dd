// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The live robot as a source of scans (DESIGN.md, "Data flow": RobotLink → ScanSource). It opens a
// TCP or serial connection, runs the ARCOS client session over it (arcos/client_session.h), emits
// every SIP as an sg::Scan, and when the connection is lost (a transport error, or no packet for
// two seconds) reports it and connects again after a pause that doubles up to a cap. Scan times
// are seconds since open() on one monotonic clock, so the scans of all connections form one
// time-ordered stream that a consumer appends. Everything runs on the thread that owns the link.

#include <QElapsedTimer>
#include <QMetaType>
#include <QObject>
#include <QString>
#include <QTimer>
#include <memory>
#include <optional>
#include <span>

#include "sonargrid/arcos/client_session.h"
#include "sonargrid/data/dataset.h"
#include "sonargrid/live/link_address.h"

namespace sg::live {

class Transport;

class RobotLink : public QObject, private arcos::ClientSession::Listener {
  Q_OBJECT

 public:
  struct Options {
    arcos::ClientSettings client;
    int reconnectFirstMs = 500;  // the first pause after a lost connection
    int reconnectMaxMs = 8000;   // pauses double up to this
    int tickMs = 20;             // how often timeouts and keep-alive are checked
    int statsMs = 500;           // statsChanged() at most this often
  };

  explicit RobotLink(LinkAddress address, QObject* parent = nullptr);
  RobotLink(LinkAddress address, Options options, QObject* parent = nullptr);
  ~RobotLink() override;

  // Starts connecting, and keeps reconnecting until close().
  void open();
  // Closes the session (STOP if this link sent motion commands, then CLOSE) and the connection;
  // no reconnect follows.
  void close();

  const LinkAddress& address() const { return address_; }
  bool isOpen() const { return session_.isOpen(); }
  bool isActive() const { return active_; }
  const arcos::LinkCounters& counters() const { return session_.counters(); }
  // The server and robot of the current or last connection.
  const std::optional<arcos::ServerInfo>& server() const { return session_.server(); }
  const std::optional<arcos::RobotParameters>& robot() const { return session_.robot(); }
  // The latest range of each transducer of the current connection (metres, kNoEcho, or NaN).
  std::span<const double> latestRanges() const { return session_.latestRanges(); }
  // Seconds since open(): the clock of the scan times.
  double now() const;

 public slots:
  // Translational (m/s) and rotational (rad/s) velocity: VEL and RVEL. Ignored while not open.
  void setVelocity(double metresPerSecond, double radiansPerSecond);
  // Wheel velocities (m/s): VEL2.
  void setWheelVelocities(double leftMetresPerSecond, double rightMetresPerSecond);
  // The robot's limits on later velocity commands: SETV and SETRV.
  void setSpeedLimits(double metresPerSecond, double radiansPerSecond);
  void stop();

 signals:
  void connected(const QString& name, const QString& robotClass, const QString& subclass);
  void scanReceived(const sg::Scan& scan);
  void statsChanged(const sg::arcos::LinkCounters& counters);
  // Something worth telling the user that does not end the connection by itself (a connection
  // attempt that failed, an unknown robot subclass).
  void error(const QString& message);
  // An open connection ended; `reason` says why. A reconnect follows unless close() was called.
  void disconnected(const QString& reason);

 private:
  // ClientSession::Listener
  void sendBytes(std::span<const std::uint8_t> bytes) override;
  void onConnected(const arcos::ServerInfo& server, const arcos::RobotParameters& robot) override;
  void onScan(const Scan& scan) override;
  void onWarning(const std::string& message) override;
  void onLost(const std::string& reason) override;

  void connectNow();
  void onOpened();
  void onReadyRead();
  void onFailed(const QString& reason);
  void onTick();
  void endConnection(const QString& reason);
  void dropTransport();

  LinkAddress address_;
  Options options_;
  arcos::ClientSession session_;
  std::unique_ptr<Transport> transport_;
  QElapsedTimer clock_;
  QTimer tick_;
  QTimer reconnect_;
  int backoffMs_;
  bool active_ = false;
  bool wasOpen_ = false;  // the current connection reached OPEN
  bool everConnected_ = false;
  qint64 lastStatsMs_ = -1;
};

}  // namespace sg::live

Q_DECLARE_METATYPE(sg::Scan)
Q_DECLARE_METATYPE(sg::arcos::LinkCounters)
