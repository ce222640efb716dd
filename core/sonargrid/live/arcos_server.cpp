// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/live/arcos_server.h"

namespace sg::live {
namespace {

// The robot moves and fires in steps of at most this much real time.
constexpr int kTickMs = 10;
// A client sends PULSE every half second at least (ARCOS); one silent this long has gone.
constexpr qint64 kSilentClientMs = 5000;

QString peerOf(const QTcpSocket& s) {
  QHostAddress a = s.peerAddress();
  bool v4 = false;
  const quint32 ip4 = a.toIPv4Address(&v4);
  if (v4) a = QHostAddress(ip4);
  return QStringLiteral("%1:%2").arg(a.toString()).arg(s.peerPort());
}

}  // namespace

ArcosServer::ArcosServer(arcos::VirtualRobot& robot, double timeScale, QObject* parent)
    : QObject(parent), robot_(robot), timeScale_(timeScale) {
  connect(&server_, &QTcpServer::newConnection, this, &ArcosServer::onNewConnection);
  tick_.setInterval(kTickMs);
  tick_.setTimerType(Qt::PreciseTimer);
  connect(&tick_, &QTimer::timeout, this, &ArcosServer::onTick);
}

ArcosServer::~ArcosServer() {
  if (client_) {
    client_->disconnect(this);
    client_->abort();
  }
}

bool ArcosServer::listen(const QHostAddress& address, quint16 port, QString* error) {
  if (!server_.listen(address, port)) {
    if (error) *error = server_.errorString();
    return false;
  }
  clock_.start();
  tick_.start();
  return true;
}

double ArcosServer::simTime() const {
  return clockStart_ +
         (clock_.isValid() ? static_cast<double>(clock_.nsecsElapsed()) * 1e-9 * timeScale_ : 0.0);
}

void ArcosServer::onNewConnection() {
  while (QTcpSocket* s = server_.nextPendingConnection()) {
    const QString peer = peerOf(*s);
    if (client_) {
      // One client at a time, as a real controller's single serial port: the newcomer is told
      // nothing in ARCOS (it has no refusal packet) and sees its connection closed at once.
      s->abort();
      s->deleteLater();
      emit clientRefused(peer);
      continue;
    }
    client_ = s;
    peer_ = peer;
    s->setSocketOption(QAbstractSocket::LowDelayOption, 1);
    connect(s, &QTcpSocket::readyRead, this, &ArcosServer::onClientBytes);
    connect(s, &QTcpSocket::disconnected, this,
            [this] { hangUp(QStringLiteral("the client closed the connection")); });
    connect(s, &QTcpSocket::errorOccurred, this, [this](QAbstractSocket::SocketError e) {
      if (e != QAbstractSocket::RemoteHostClosedError) hangUp(client_->errorString());
    });
    lastHeard_.start();
    robot_.clientConnected(simTime());
    emit clientConnected(peer);
  }
}

void ArcosServer::onClientBytes() {
  if (!client_) return;
  lastHeard_.start();
  const QByteArray bytes = client_->readAll();
  const double now = simTime();
  arcos::Bytes out;
  // The robot catches up first, so that a command takes effect from now on.
  robot_.advanceTo(now, out);
  robot_.receive(std::span(reinterpret_cast<const std::uint8_t*>(bytes.constData()),
                           static_cast<std::size_t>(bytes.size())),
                 now, out);
  flush(out);
  if (robot_.closeRequested()) hangUp(QStringLiteral("the client sent CLOSE"));
}

void ArcosServer::flush(const arcos::Bytes& bytes) {
  if (client_ && !bytes.empty()) {
    client_->write(reinterpret_cast<const char*>(bytes.data()), static_cast<qint64>(bytes.size()));
  }
}

void ArcosServer::onTick() {
  arcos::Bytes out;
  robot_.advanceTo(simTime(), out);
  flush(out);
  if (client_ && lastHeard_.elapsed() > kSilentClientMs) {
    hangUp(QStringLiteral("the client sent nothing for %1 s").arg(kSilentClientMs / 1000));
  }
}

void ArcosServer::hangUp(const QString& reason) {
  if (!client_) return;
  QTcpSocket* s = client_;
  client_ = nullptr;
  s->disconnect(this);
  if (s->state() == QAbstractSocket::ConnectedState) {
    s->flush();
    s->disconnectFromHost();
  }
  s->deleteLater();
  robot_.clientDisconnected(simTime());
  emit clientDisconnected(peer_, reason);
}

void ArcosServer::shutdown() {
  hangUp(QStringLiteral("the server is shutting down"));
  server_.close();
  tick_.stop();
  clockStart_ = simTime();
  clock_.invalidate();
}

}  // namespace sg::live
