// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/live/transport.h"

#include <QSerialPort>
#include <QTcpSocket>
#include <QTimer>

namespace sg::live {
namespace {

class TcpTransport final : public Transport {
 public:
  explicit TcpTransport(const LinkAddress& a) : address_(a) {
    connect(&socket_, &QTcpSocket::connected, this, [this] {
      // ARCOS packets are small and time-critical: a command must not wait for Nagle's timer.
      socket_.setSocketOption(QAbstractSocket::LowDelayOption, 1);
      emit opened();
    });
    connect(&socket_, &QTcpSocket::readyRead, this, &Transport::readyRead);
    connect(&socket_, &QTcpSocket::errorOccurred, this, [this](QAbstractSocket::SocketError e) {
      fail(e == QAbstractSocket::RemoteHostClosedError
               ? QStringLiteral("the robot closed the connection")
               : socket_.errorString());
    });
    connect(&socket_, &QTcpSocket::disconnected, this,
            [this] { fail(QStringLiteral("the robot closed the connection")); });
  }

  void open() override {
    socket_.connectToHost(QString::fromStdString(address_.host), address_.port);
  }

  void close(int flushMs) override {
    done_ = true;
    if (socket_.state() == QAbstractSocket::ConnectedState) {
      socket_.flush();
      if (socket_.bytesToWrite() > 0) socket_.waitForBytesWritten(flushMs);
      socket_.disconnectFromHost();
    }
    socket_.abort();
  }

  QIODevice* device() override { return &socket_; }

 private:
  void fail(const QString& reason) {
    if (done_) return;
    // Bytes that came before the end are the robot's last packets: deliver them first.
    if (socket_.bytesAvailable() > 0) emit readyRead();
    done_ = true;
    emit failed(reason);
  }

  LinkAddress address_;
  QTcpSocket socket_;
  bool done_ = false;
};

class SerialTransport final : public Transport {
 public:
  explicit SerialTransport(const LinkAddress& a) : address_(a) {
    connect(&port_, &QSerialPort::readyRead, this, &Transport::readyRead);
    connect(&port_, &QSerialPort::errorOccurred, this, [this](QSerialPort::SerialPortError e) {
      // Opening errors are reported by open(); after that, a resource error is a lost device.
      if (e == QSerialPort::NoError || !port_.isOpen()) return;
      if (e == QSerialPort::ResourceError || e == QSerialPort::PermissionError ||
          e == QSerialPort::DeviceNotFoundError) {
        fail(port_.errorString());
      }
    });
  }

  void open() override {
    // ARCOS serial links are 8 data bits, no parity, 1 stop bit, no flow control.
    port_.setPortName(QString::fromStdString(address_.device));
    port_.setBaudRate(address_.baud);
    port_.setDataBits(QSerialPort::Data8);
    port_.setParity(QSerialPort::NoParity);
    port_.setStopBits(QSerialPort::OneStop);
    port_.setFlowControl(QSerialPort::NoFlowControl);
    const bool ok = port_.open(QIODevice::ReadWrite);
    const QString reason = ok ? QString() : port_.errorString();
    QTimer::singleShot(0, this, [this, ok, reason] {
      if (done_) return;
      if (ok) {
        port_.clear();
        emit opened();
      } else {
        fail(reason);
      }
    });
  }

  void close(int flushMs) override {
    done_ = true;
    if (port_.isOpen()) {
      port_.flush();
      if (port_.bytesToWrite() > 0) port_.waitForBytesWritten(flushMs);
      port_.close();
    }
  }

  QIODevice* device() override { return &port_; }

 private:
  void fail(const QString& reason) {
    if (done_) return;
    if (port_.isOpen() && port_.bytesAvailable() > 0) emit readyRead();
    done_ = true;
    emit failed(reason);
  }

  LinkAddress address_;
  QSerialPort port_;
  bool done_ = false;
};

}  // namespace

std::unique_ptr<Transport> Transport::create(const LinkAddress& address) {
  if (address.kind == LinkAddress::Kind::Serial) return std::make_unique<SerialTransport>(address);
  return std::make_unique<TcpTransport>(address);
}

}  // namespace sg::live
