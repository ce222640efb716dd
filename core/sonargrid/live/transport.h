// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The byte pipe to a robot: a QTcpSocket or a QSerialPort behind one interface, so that the link
// has a single code path for both (each is a QIODevice; only opening and failing differ).

#include <QIODevice>
#include <QObject>
#include <QString>
#include <memory>

#include "sonargrid/live/link_address.h"

namespace sg::live {

class Transport : public QObject {
  Q_OBJECT

 public:
  static std::unique_ptr<Transport> create(const LinkAddress& address);
  ~Transport() override = default;

  // Starts opening; emits opened() or failed() later, never from inside this call.
  virtual void open() = 0;
  // Writes what is still buffered (waiting at most `flushMs`), then closes. No signal follows.
  virtual void close(int flushMs) = 0;
  virtual QIODevice* device() = 0;

 signals:
  void opened();
  // Could not open, or the open pipe broke (the peer closed it, the cable was pulled).
  void failed(const QString& reason);
  void readyRead();

 protected:
  Transport() = default;
};

}  // namespace sg::live
