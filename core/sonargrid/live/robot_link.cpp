// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/live/robot_link.h"

#include <algorithm>

#include "sonargrid/live/transport.h"

namespace sg::live {
namespace {

// How long close() waits for STOP and CLOSE to leave.
constexpr int kCloseFlushMs = 500;

QString fromStd(const std::string& s) {
  return QString::fromStdString(s);
}

}  // namespace

RobotLink::RobotLink(LinkAddress address, QObject* parent)
    : RobotLink(std::move(address), Options{}, parent) {}

RobotLink::RobotLink(LinkAddress address, Options options, QObject* parent)
    : QObject(parent),
      address_(std::move(address)),
      options_(std::move(options)),
      session_(options_.client, *this),
      backoffMs_(options_.reconnectFirstMs) {
  qRegisterMetaType<sg::Scan>();
  qRegisterMetaType<sg::arcos::LinkCounters>();
  tick_.setInterval(options_.tickMs);
  connect(&tick_, &QTimer::timeout, this, &RobotLink::onTick);
  reconnect_.setSingleShot(true);
  connect(&reconnect_, &QTimer::timeout, this, &RobotLink::connectNow);
}

RobotLink::~RobotLink() {
  if (transport_) {
    QObject::disconnect(transport_.get(), nullptr, this, nullptr);
    transport_->close(0);
  }
}

double RobotLink::now() const {
  return clock_.isValid() ? static_cast<double>(clock_.nsecsElapsed()) * 1e-9 : 0.0;
}

void RobotLink::open() {
  if (active_) return;
  active_ = true;
  if (!clock_.isValid()) clock_.start();
  backoffMs_ = options_.reconnectFirstMs;
  tick_.start();
  connectNow();
}

void RobotLink::close() {
  if (!active_) return;
  active_ = false;
  reconnect_.stop();
  tick_.stop();
  const bool wasOpen = session_.isOpen();
  session_.close(now());
  if (transport_) {
    QObject::disconnect(transport_.get(), nullptr, this, nullptr);
    transport_->close(kCloseFlushMs);
    transport_.reset();
  }
  if (wasOpen) emit disconnected(QStringLiteral("closed by the client"));
  emit statsChanged(session_.counters());
}

void RobotLink::connectNow() {
  if (!active_) return;
  dropTransport();
  ++session_.counters().attempts;
  wasOpen_ = false;
  transport_ = Transport::create(address_);
  connect(transport_.get(), &Transport::opened, this, &RobotLink::onOpened);
  connect(transport_.get(), &Transport::readyRead, this, &RobotLink::onReadyRead);
  connect(transport_.get(), &Transport::failed, this, &RobotLink::onFailed);
  transport_->open();
}

void RobotLink::dropTransport() {
  if (!transport_) return;
  QObject::disconnect(transport_.get(), nullptr, this, nullptr);
  transport_->close(0);
  // It may be inside one of its own signals: delete it once control is back in the event loop.
  transport_.release()->deleteLater();
}

void RobotLink::onOpened() {
  session_.start(now());
}

void RobotLink::onReadyRead() {
  if (!transport_) return;
  const QByteArray bytes = transport_->device()->readAll();
  session_.receive(std::span(reinterpret_cast<const std::uint8_t*>(bytes.constData()),
                             static_cast<std::size_t>(bytes.size())),
                   now());
}

void RobotLink::onFailed(const QString& reason) {
  session_.disconnected();
  endConnection(reason);
}

void RobotLink::onLost(const std::string& reason) {
  endConnection(fromStd(reason));
}

void RobotLink::endConnection(const QString& reason) {
  dropTransport();
  if (wasOpen_) {
    ++session_.counters().lostConnections;
    emit disconnected(reason);
  } else {
    emit error(QStringLiteral("cannot connect to %1: %2").arg(fromStd(address_.text()), reason));
  }
  wasOpen_ = false;
  emit statsChanged(session_.counters());
  if (!active_) return;
  reconnect_.start(backoffMs_);
  backoffMs_ = std::min(2 * backoffMs_, options_.reconnectMaxMs);
}

void RobotLink::onTick() {
  session_.tick(now());
  if (!clock_.isValid()) return;
  const qint64 ms = clock_.elapsed();
  if (lastStatsMs_ < 0 || ms - lastStatsMs_ >= options_.statsMs) {
    lastStatsMs_ = ms;
    emit statsChanged(session_.counters());
  }
}

void RobotLink::sendBytes(std::span<const std::uint8_t> bytes) {
  if (!transport_) return;
  transport_->device()->write(reinterpret_cast<const char*>(bytes.data()),
                              static_cast<qint64>(bytes.size()));
}

void RobotLink::onConnected(const arcos::ServerInfo& server, const arcos::RobotParameters&) {
  wasOpen_ = true;
  if (everConnected_) ++session_.counters().reconnects;
  everConnected_ = true;
  backoffMs_ = options_.reconnectFirstMs;
  emit connected(fromStd(server.name), fromStd(server.robotClass), fromStd(server.subclass));
}

void RobotLink::onScan(const Scan& s) {
  emit scanReceived(s);
}

void RobotLink::onWarning(const std::string& message) {
  emit error(fromStd(message));
}

void RobotLink::setVelocity(double metresPerSecond, double radiansPerSecond) {
  session_.setVelocity(metresPerSecond, radiansPerSecond, now());
}

void RobotLink::setWheelVelocities(double leftMetresPerSecond, double rightMetresPerSecond) {
  session_.setWheelVelocities(leftMetresPerSecond, rightMetresPerSecond, now());
}

void RobotLink::setSpeedLimits(double metresPerSecond, double radiansPerSecond) {
  session_.setSpeedLimits(metresPerSecond, radiansPerSecond, now());
}

void RobotLink::stop() {
  session_.stop(now());
}

}  // namespace sg::live
