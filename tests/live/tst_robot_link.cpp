// SPDX-License-Identifier: BSD-3-Clause
// The robot link over loopback TCP (docs/live-robot.md, "The link"): against a fake robot that
// mixes valid SIPs with noise, corrupt, truncated and malformed packets (no crash; each error
// counted by kind, every valid SIP delivered), one that talks only noise, one that falls silent
// and one that hangs up (reported, reconnected); and against the virtual robot's server, which
// serves one client at a time and obeys the link's velocity commands.

#include <QSignalSpy>
#include <QTcpServer>
#include <QTcpSocket>
#include <QtTest>
#include <random>

#include "sonargrid/arcos/decoder.h"
#include "sonargrid/arcos/messages.h"
#include "sonargrid/engine/scan_source.h"
#include "sonargrid/live/arcos_server.h"
#include "sonargrid/live/robot_link.h"
#include "sonargrid/sim/ray_sonar.h"

namespace arcos = sg::arcos;
using arcos::Bytes;

namespace {

QByteArray bytes(const Bytes& b) {
  return QByteArray(reinterpret_cast<const char*>(b.data()), static_cast<qsizetype>(b.size()));
}

// A robot that answers the handshake like a real one (unless told not to) and then runs a
// script on the open connection.
class FakeRobot : public QObject {
 public:
  explicit FakeRobot(bool answersHandshake = true) : answers_(answersHandshake) {
    QVERIFY(server_.listen(QHostAddress::LocalHost, 0));
    connect(&server_, &QTcpServer::newConnection, this, [this] {
      while (QTcpSocket* s = server_.nextPendingConnection()) {
        ++connections;
        client = s;
        decoder_.reset();
        open_ = false;
        connect(s, &QTcpSocket::readyRead, this, [this, s] { onBytes(s); });
        if (onConnect) onConnect(s);
      }
    });
  }

  sg::live::LinkAddress address() const {
    sg::live::LinkAddress a;
    a.host = "127.0.0.1";
    a.port = server_.serverPort();
    return a;
  }

  std::function<void(QTcpSocket*)> onConnect;
  std::function<void(QTcpSocket*)> onOpen;
  QPointer<QTcpSocket> client;
  int connections = 0;
  int closes = 0;

 private:
  void onBytes(QTcpSocket* s) {
    const QByteArray in = s->readAll();
    if (!answers_) return;
    decoder_.feed(std::span(reinterpret_cast<const std::uint8_t*>(in.constData()),
                            static_cast<std::size_t>(in.size())),
                  [&](const arcos::Packet& p) {
                    if (p.id <= 2 && p.payload.empty() && !open_) {
                      if (p.id < 2) {
                        s->write(bytes(arcos::encodeCommand(p.id)));
                      } else {
                        s->write(bytes(arcos::encodeServerInfo({"FakeSim", "Pioneer", "p3dx"})));
                      }
                    } else if (p.id == arcos::command::kOpen && !open_) {
                      open_ = true;
                      if (onOpen) onOpen(s);
                    } else if (p.id == arcos::command::kClose) {
                      ++closes;
                      open_ = false;
                    }
                  });
  }

  bool answers_;
  bool open_ = false;
  QTcpServer server_;
  arcos::PacketDecoder decoder_;
};

Bytes sipFrame(int i) {
  arcos::Sip sip;
  sip.xpos = static_cast<std::uint16_t>(100 + 10 * i);
  sip.ypos = 200;
  sip.thpos = 0;
  sip.battery = 120;
  sip.sonars = {{static_cast<std::uint8_t>(i % 16), static_cast<std::uint16_t>(1000 + i)}};
  return arcos::encodeSip(sip);
}

void append(Bytes& to, const Bytes& b) {
  to.insert(to.end(), b.begin(), b.end());
}

sg::SonarWorld room() {
  const std::vector<sg::Position> corners{{0, 0}, {7, 0}, {7, 5}, {0, 5}};
  return sg::SonarWorld(sg::polygonSegments(corners, true));
}

}  // namespace

class TstRobotLink : public QObject {
  Q_OBJECT

 private slots:
  void parsesAddresses_data() {
    QTest::addColumn<QString>("text");
    QTest::addColumn<QString>("canonical");  // empty: an error
    QTest::newRow("tcp with port") << "tcp://127.0.0.1:8101"
                                   << "tcp://127.0.0.1:8101";
    QTest::newRow("tcp default port 8101") << "tcp://robot.local"
                                           << "tcp://robot.local:8101";
    QTest::newRow("tcp ipv6") << "tcp://[::1]:9000"
                              << "tcp://[::1]:9000";
    QTest::newRow("serial default 9600") << "serial:///dev/ttyUSB0"
                                         << "serial:///dev/ttyUSB0";
    QTest::newRow("serial 115200") << "serial:///dev/ttyS0?baud=115200"
                                   << "serial:///dev/ttyS0?baud=115200";
    QTest::newRow("port out of range") << "tcp://h:65536"
                                       << "";
    QTest::newRow("port not a number") << "tcp://h:80x"
                                       << "";
    QTest::newRow("no host") << "tcp://:8101"
                             << "";
    QTest::newRow("bare ipv6") << "tcp://::1:8101"
                               << "";
    QTest::newRow("unknown scheme") << "udp://h:1"
                                    << "";
    QTest::newRow("bad baud") << "serial:///dev/ttyS0?baud=fast"
                              << "";
    QTest::newRow("unknown option") << "serial:///dev/ttyS0?parity=even"
                                    << "";
  }
  void parsesAddresses() {
    QFETCH(QString, text);
    QFETCH(QString, canonical);
    try {
      const sg::live::LinkAddress a = sg::live::parseLinkAddress(text.toStdString());
      QCOMPARE(QString::fromStdString(a.text()), canonical);
      QCOMPARE(sg::live::parseLinkAddress(a.text()), a);
    } catch (const std::invalid_argument& e) {
      QVERIFY2(canonical.isEmpty(), e.what());
      QVERIFY(QString(e.what()).startsWith(text + ": "));
    }
  }

  // Valid SIPs among noise, corrupt, truncated and malformed packets: every valid SIP becomes a
  // scan, and each error is counted under its kind.
  void survivesAndCountsBadPackets() {
    FakeRobot fake;
    const int valid = 40;
    int badChecksums = 0;
    int badCounts = 0;
    int malformedSips = 0;
    int malformedSimStats = 0;
    int others = 0;
    fake.onOpen = [&](QTcpSocket* s) {
      std::mt19937 rng(11);
      Bytes stream;
      for (int i = 0; i < valid; ++i) {
        switch (i % 8) {
          case 0: {  // noise without a header byte, so that no frame can start in it
            for (int k = 0; k < 37; ++k) {
              auto b = static_cast<std::uint8_t>(rng());
              stream.push_back(b == 0xFA ? 0 : b);
            }
            break;
          }
          case 1: {  // a corrupt checksum
            Bytes bad = sipFrame(1000 + i);
            bad.back() ^= 0x55;
            append(stream, bad);
            ++badChecksums;
            break;
          }
          case 2: {  // a SIP cut short, then the next one: its count swallows part of that one
            const Bytes cut = sipFrame(2000 + i);
            stream.insert(stream.end(), cut.begin(), cut.begin() + 10);
            ++badChecksums;
            break;
          }
          case 3:  // a count below 3
            append(stream, {0xFA, 0xFB, 0x02});
            ++badCounts;
            break;
          case 4:  // a SIP too short for its fields
            append(stream, arcos::framePacket(0x32, Bytes(5, 1)));
            ++malformedSips;
            break;
          case 5:  // a SIMSTAT too short
            append(stream, arcos::framePacket(0x62, Bytes(10, 2)));
            ++malformedSimStats;
            break;
          case 6:  // a packet the client does not read
            append(stream, arcos::framePacket(0x99, Bytes(3, 3)));
            ++others;
            break;
          default:
            break;
        }
        append(stream, sipFrame(i));
      }
      s->write(bytes(stream));
    };
    sg::live::RobotLink link(fake.address());
    QSignalSpy scans(&link, &sg::live::RobotLink::scanReceived);
    link.open();
    QTRY_COMPARE_WITH_TIMEOUT(scans.size(), valid, 10000);
    const arcos::LinkCounters& c = link.counters();
    QCOMPARE(c.sips, std::uint64_t(valid));
    QCOMPARE(c.framing.badChecksums, std::uint64_t(badChecksums));
    QCOMPARE(c.framing.badCounts, std::uint64_t(badCounts));
    QCOMPARE(c.malformedSips, std::uint64_t(malformedSips));
    QCOMPARE(c.malformedSimStats, std::uint64_t(malformedSimStats));
    QCOMPARE(c.otherPackets, std::uint64_t(others));
    QVERIFY(c.framing.skippedBytes > 0);
    // Every valid SIP's reading arrived, in order: sonar i % 16 at 1000 + i mm.
    for (int i = 0; i < valid; ++i) {
      const auto scan = scans[i][0].value<sg::Scan>();
      QCOMPARE(scan.readings.size(), std::size_t{1});
      QCOMPARE(static_cast<int>(scan.readings[0].sonar), i % 16);
      QCOMPARE(scan.readings[0].range, (1000 + i) / 1000.0);
    }
    link.close();
    QTRY_COMPARE_WITH_TIMEOUT(fake.closes, 1, 5000);
  }

  // A peer that sends only noise: never a connection, no crash; the link keeps trying.
  void noiseOnlyPeer() {
    FakeRobot fake(false);
    std::mt19937 rng(5);
    fake.onConnect = [&rng](QTcpSocket* s) {
      QByteArray junk(64 * 1024, '\0');
      for (char& b : junk) b = static_cast<char>(rng());
      s->write(junk);
    };
    sg::live::RobotLink::Options o;
    o.client.syncRetry = 0.3;
    o.client.handshakeTimeout = 1.0;
    o.reconnectFirstMs = 100;
    sg::live::RobotLink link(fake.address(), o);
    QSignalSpy errors(&link, &sg::live::RobotLink::error);
    QSignalSpy connected(&link, &sg::live::RobotLink::connected);
    link.open();
    QTRY_VERIFY_WITH_TIMEOUT(fake.connections >= 2, 10000);
    QCOMPARE(connected.size(), 0);
    QVERIFY(errors.size() >= 1);
    QVERIFY2(errors[0][0].toString().contains("no answer to the handshake"),
             qPrintable(errors[0][0].toString()));
    const arcos::LinkCounters& c = link.counters();
    QVERIFY(c.framing.bytes >= 64 * 1024);
    QVERIFY(c.framing.skippedBytes > 0);
    QVERIFY(c.timeouts >= 1);
    QCOMPARE(c.handshakes, std::uint64_t{0});
    link.close();
  }

  // A robot that falls silent after the handshake: lost after 2 s, reported, reconnected.
  void silentRobotIsLostAndReconnected() {
    FakeRobot fake;
    sg::live::RobotLink link(fake.address());
    QSignalSpy connected(&link, &sg::live::RobotLink::connected);
    QSignalSpy disconnected(&link, &sg::live::RobotLink::disconnected);
    link.open();
    QTRY_COMPARE_WITH_TIMEOUT(connected.size(), 1, 5000);
    QTRY_COMPARE_WITH_TIMEOUT(disconnected.size(), 1, 10000);
    QVERIFY2(disconnected[0][0].toString().startsWith("no packet from the robot for"),
             qPrintable(disconnected[0][0].toString()));
    QTRY_COMPARE_WITH_TIMEOUT(connected.size(), 2, 10000);
    QCOMPARE(link.counters().timeouts, std::uint64_t{1});
    QCOMPARE(link.counters().lostConnections, std::uint64_t{1});
    QCOMPARE(link.counters().reconnects, std::uint64_t{1});
    link.close();
  }

  // A robot that hangs up mid-stream: reported with the transport's reason, reconnected, and the
  // scans go on in one time order, appended to a live ScanSource (DESIGN.md: RobotLink ->
  // ScanSource) as the app will append them, across the reconnection.
  void hangUpIsReportedAndReconnected() {
    FakeRobot fake;
    int sent = 0;
    QTimer stream;
    stream.setInterval(50);
    QObject::connect(&stream, &QTimer::timeout, [&] {
      if (fake.client && fake.client->state() == QAbstractSocket::ConnectedState)
        fake.client->write(bytes(sipFrame(sent++)));
    });
    fake.onOpen = [&](QTcpSocket*) { stream.start(); };
    sg::live::RobotLink link(fake.address());
    QSignalSpy scans(&link, &sg::live::RobotLink::scanReceived);
    QSignalSpy connected(&link, &sg::live::RobotLink::connected);
    QSignalSpy disconnected(&link, &sg::live::RobotLink::disconnected);
    sg::ScanSource source("live", arcos::pioneer3dxParameters().ring);
    std::string appendError;
    QObject::connect(&link, &sg::live::RobotLink::scanReceived, [&](const sg::Scan& s) {
      try {
        source.append({s});
      } catch (const sg::ScanSourceError& e) {
        appendError = e.what();
      }
    });
    link.open();
    QTRY_VERIFY_WITH_TIMEOUT(scans.size() >= 5, 5000);
    fake.client->abort();
    QTRY_COMPARE_WITH_TIMEOUT(disconnected.size(), 1, 5000);
    QVERIFY2(disconnected[0][0].toString().contains("closed"),
             qPrintable(disconnected[0][0].toString()));
    const qsizetype before = scans.size();
    QTRY_COMPARE_WITH_TIMEOUT(connected.size(), 2, 10000);
    QTRY_VERIFY_WITH_TIMEOUT(scans.size() >= before + 5, 5000);
    double last = -1.0;
    for (const QList<QVariant>& s : scans) {
      const double t = s[0].value<sg::Scan>().time;
      QVERIFY(t >= last);
      last = t;
    }
    QCOMPARE(link.counters().lostConnections, std::uint64_t{1});
    QCOMPARE(link.counters().reconnects, std::uint64_t{1});
    link.close();
    QVERIFY2(appendError.empty(), appendError.c_str());
    const sg::ScanPrefix all = source.prefix();
    QCOMPARE(static_cast<qsizetype>(all.size()), scans.size());
    QVERIFY(!all.complete());
    QVERIFY(all.readingsInTimeOrder());
  }

  // The virtual robot's server: one client at a time (a second is refused until the first
  // leaves), and the link's velocity commands drive it.
  void virtualRobotServesOneClientAtATime() {
    arcos::VirtualRobot robot(room(), sg::Pose2D(3.5, 2.5, 0.0), std::nullopt, {});
    sg::live::ArcosServer server(robot);
    QString error;
    QVERIFY2(server.listen(QHostAddress::LocalHost, 0, &error), qPrintable(error));
    QSignalSpy refused(&server, &sg::live::ArcosServer::clientRefused);
    sg::live::LinkAddress a;
    a.host = "127.0.0.1";
    a.port = server.port();
    sg::live::RobotLink first(a);
    QSignalSpy firstConnected(&first, &sg::live::RobotLink::connected);
    first.open();
    QTRY_COMPARE_WITH_TIMEOUT(firstConnected.size(), 1, 5000);
    QCOMPARE(firstConnected[0][0].toString(), QString("SonarGridSim"));
    QCOMPARE(firstConnected[0][2].toString(), QString("p3dx"));

    sg::live::RobotLink::Options o;
    o.reconnectFirstMs = 100;
    o.reconnectMaxMs = 200;
    sg::live::RobotLink second(a, o);
    QSignalSpy secondErrors(&second, &sg::live::RobotLink::error);
    QSignalSpy secondConnected(&second, &sg::live::RobotLink::connected);
    second.open();
    QTRY_VERIFY_WITH_TIMEOUT(refused.size() >= 1, 5000);
    QTRY_VERIFY_WITH_TIMEOUT(secondErrors.size() >= 1, 5000);
    QCOMPARE(secondConnected.size(), 0);

    first.setVelocity(0.3, 0.0);
    QTRY_VERIFY_WITH_TIMEOUT(robot.truePose().x() > 3.6, 5000);
    QVERIFY(robot.clientDriving());
    first.close();
    QTRY_COMPARE_WITH_TIMEOUT(secondConnected.size(), 1, 10000);
    second.close();
  }
};

QTEST_GUILESS_MAIN(TstRobotLink)
#include "tst_robot_link.moc"
