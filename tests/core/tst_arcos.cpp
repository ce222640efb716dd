// SPDX-License-Identifier: BSD-3-Clause
// The ARCOS codec (docs/live-robot.md, "The protocol"): the checksum rule and every byte-exact
// example of the protocol description, the streaming decoder against noise and cuts, the SIP and
// SIMSTAT layouts, SIPs to scans (15-bit wrap, conversion factors, sonar ranges, true pose), and
// the client session against the virtual robot in memory (handshake, keep-alive, lost robot).

#include <QDir>
#include <QtTest>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "sonargrid/arcos/client_session.h"
#include "sonargrid/arcos/decoder.h"
#include "sonargrid/arcos/messages.h"
#include "sonargrid/arcos/packet.h"
#include "sonargrid/arcos/sip_tracker.h"
#include "sonargrid/arcos/virtual_robot.h"
#include "sonargrid/arcos/virtual_route.h"
#include "sonargrid/reference/reference_json.h"
#include "sonargrid/sim/ray_sonar.h"
#include "sonargrid/sim/route.h"
#include "sonargrid/sim/simulation.h"

using sg::arcos::Bytes;
namespace arcos = sg::arcos;

Q_DECLARE_METATYPE(Bytes)

namespace {

Bytes hex(const char* text) {
  Bytes out;
  const QList<QByteArray> parts = QByteArray(text).split(' ');
  for (const QByteArray& p : parts) {
    if (p.isEmpty()) continue;
    bool ok = false;
    out.push_back(static_cast<std::uint8_t>(p.toUInt(&ok, 16)));
    if (!ok) qFatal("bad hex byte %s", p.constData());
  }
  return out;
}

QByteArray show(const Bytes& b) {
  QByteArray out;
  for (const std::uint8_t v : b)
    out += QByteArray::number(v, 16).rightJustified(2, '0').toUpper() + ' ';
  return out.trimmed();
}

std::vector<arcos::Packet> decodeAll(arcos::PacketDecoder& d, const Bytes& bytes) {
  std::vector<arcos::Packet> out;
  d.feed(bytes, [&out](const arcos::Packet& p) { out.push_back(p); });
  return out;
}

// Walls of a 7 m x 5 m room, as datasets/raschke-single without its box.
sg::SonarWorld room() {
  const std::vector<sg::Position> corners{{0, 0}, {7, 0}, {7, 5}, {0, 5}};
  return sg::SonarWorld(sg::polygonSegments(corners, true));
}

// The client session and the virtual robot joined in memory, on one simulated clock.
struct MemoryLink : arcos::ClientSession::Listener {
  explicit MemoryLink(arcos::VirtualRobot& r, arcos::ClientSettings settings = {})
      : robot(r), session(std::move(settings), *this) {
    robot.onSip = [this](const sg::Scan& s) { served.push_back(s); };
  }

  void sendBytes(std::span<const std::uint8_t> bytes) override {
    toRobot.insert(toRobot.end(), bytes.begin(), bytes.end());
  }
  void onConnected(const arcos::ServerInfo& s, const arcos::RobotParameters&) override {
    server = s;
  }
  void onScan(const sg::Scan& s) override { scans.push_back(s); }
  void onLost(const std::string& reason) override { lostReason = reason; }

  // Runs both ends for `seconds` in steps of 10 ms; with `deaf` the robot's bytes are lost.
  void run(double seconds, bool deaf = false) {
    const int steps = static_cast<int>(std::lround(seconds / 0.01));
    for (int i = 0; i < steps; ++i) {
      t += 0.01;
      Bytes fromRobot;
      robot.advanceTo(t, fromRobot);
      const Bytes sent = std::exchange(toRobot, {});
      robot.receive(sent, t, fromRobot);
      if (!deaf) session.receive(fromRobot, t);
      session.tick(t);
    }
  }

  arcos::VirtualRobot& robot;
  arcos::ClientSession session;
  Bytes toRobot;
  std::vector<sg::Scan> scans;
  std::vector<sg::Scan> served;
  std::optional<arcos::ServerInfo> server;
  std::string lostReason;
  double t = 0.0;
};

}  // namespace

class TstArcos : public QObject {
  Q_OBJECT

 private slots:
  // ---------------------------------------------------------------------------------------------
  // Checksum and framing

  void checksum_data() {
    QTest::addColumn<Bytes>("body");
    QTest::addColumn<int>("expected");
    // Hand computation: big-endian words from the ID on, summed and masked to 16 bits, an odd
    // last byte XORed in.
    QTest::newRow("SYNC0: one byte 00") << hex("00") << 0x0000;
    QTest::newRow("SYNC2: one byte 02, XORed in") << hex("02") << 0x0002;
    QTest::newRow("OPEN 1: 013B + 0100") << hex("01 3B 01 00") << 0x023B;
    QTest::newRow("VEL -200: 0B1B + C800") << hex("0B 1B C8 00") << 0xD31B;
    QTest::newRow("odd: 0B1B, then C8 XORed") << hex("0B 1B C8") << 0x0BD3;
    QTest::newRow("overflow: FFFF + 0002 masked") << hex("FF FF 00 02") << 0x0001;
    QTest::newRow("empty") << Bytes{} << 0;
  }
  void checksum() {
    QFETCH(Bytes, body);
    QFETCH(int, expected);
    QCOMPARE(static_cast<int>(arcos::checksum(body)), expected);
  }

  // Every byte-exact example of the protocol description, and a few more computed by hand.
  void commandBytes_data() {
    QTest::addColumn<Bytes>("encoded");
    QTest::addColumn<Bytes>("expected");
    using namespace arcos::command;
    QTest::newRow("SYNC0") << arcos::encodeCommand(arcos::packet_id::kSync0)
                           << hex("FA FB 03 00 00 00");
    QTest::newRow("SYNC1") << arcos::encodeCommand(arcos::packet_id::kSync1)
                           << hex("FA FB 03 01 00 01");
    QTest::newRow("SYNC2") << arcos::encodeCommand(arcos::packet_id::kSync2)
                           << hex("FA FB 03 02 00 02");
    QTest::newRow("OPEN") << arcos::encodeCommand(kOpen, 1) << hex("FA FB 06 01 3B 01 00 02 3B");
    QTest::newRow("ENABLE 1") << arcos::encodeCommand(kEnable, 1)
                              << hex("FA FB 06 04 3B 01 00 05 3B");
    QTest::newRow("SONAR 1") << arcos::encodeCommand(kSonar, 1)
                             << hex("FA FB 06 1C 3B 01 00 1D 3B");
    QTest::newRow("VEL -200") << arcos::encodeCommand(kVel, -200)
                              << hex("FA FB 06 0B 1B C8 00 D3 1B");
    // PULSE is SYNC0's bytes: the state of the connection tells them apart.
    QTest::newRow("PULSE") << arcos::encodeCommand(kPulse) << hex("FA FB 03 00 00 00");
    // STOP 29 = 0x1D: one byte, XORed into 0.
    QTest::newRow("STOP") << arcos::encodeCommand(kStop) << hex("FA FB 03 1D 00 1D");
    // SIM_STAT 2: EDh 3Bh 02h 00h -> ED3B + 0200 = EF3B.
    QTest::newRow("SIM_STAT 2") << arcos::encodeCommand(kSimStat, 2)
                                << hex("FA FB 06 ED 3B 02 00 EF 3B");
    // RVEL 300 (012C): 153B + 2C01 = 413C.
    QTest::newRow("RVEL 300") << arcos::encodeCommand(kRVel, 300)
                              << hex("FA FB 06 15 3B 2C 01 41 3C");
    // A string argument: 0F2B + 0261 = 118C, then 62 XORed -> 11EE; N = 1 + 4 + 2 = 7.
    QTest::newRow("string 'ab'") << arcos::encodeCommand(0x0F, std::string_view("ab"))
                                 << hex("FA FB 07 0F 2B 02 61 62 11 EE");
    // VEL2 left 200 mm/s, right -100 mm/s at divisor 20: left 10 = 0A high, right -5 = FB low;
    // 203B + FB0A = 11B45, masked 1B45.
    QTest::newRow("VEL2 200 -100")
        << arcos::encodeVel2(200.0, -100.0, 20.0) << hex("FA FB 06 20 3B FB 0A 1B 45");
    // Clamped to +-126 wheel units, as Player's p2os driver does: 7E and 82; 203B + 827E = A2B9.
    QTest::newRow("VEL2 clamped") << arcos::encodeVel2(5000.0, -5000.0, 20.0)
                                  << hex("FA FB 06 20 3B 82 7E A2 B9");
  }
  void commandBytes() {
    QFETCH(Bytes, encoded);
    QFETCH(Bytes, expected);
    QVERIFY2(encoded == expected, show(encoded) + " != " + show(expected));
  }

  void encodeRefusesWhatDoesNotFit() {
    QVERIFY_THROWS_EXCEPTION(std::out_of_range, arcos::encodeCommand(11, 65536));
    QVERIFY_THROWS_EXCEPTION(std::out_of_range, arcos::encodeCommand(11, -65536));
    QCOMPARE(arcos::encodeCommand(11, -65535).size(), std::size_t{9});
    QVERIFY_THROWS_EXCEPTION(std::length_error, arcos::encodeCommand(15, std::string(200, 'x')));
  }

  // ---------------------------------------------------------------------------------------------
  // The streaming decoder

  void decodesEveryExampleAndSplit() {
    // All of the examples back to back, fed one byte at a time: the same packets in order.
    Bytes stream;
    std::vector<Bytes> frames{hex("FA FB 03 00 00 00"), hex("FA FB 06 01 3B 01 00 02 3B"),
                              hex("FA FB 06 0B 1B C8 00 D3 1B"),
                              hex("FA FB 07 0F 2B 02 61 62 11 EE")};
    for (const Bytes& f : frames) stream.insert(stream.end(), f.begin(), f.end());
    arcos::PacketDecoder d;
    std::vector<arcos::Packet> got;
    for (const std::uint8_t b : stream) {
      d.feed(std::span(&b, 1), [&](const arcos::Packet& p) { got.push_back(p); });
    }
    QCOMPARE(got.size(), frames.size());
    for (std::size_t i = 0; i < got.size(); ++i) QVERIFY(arcos::framePacket(got[i]) == frames[i]);
    QCOMPARE(got[2].payload, hex("1B C8 00"));
    QCOMPARE(d.counters().frames, std::uint64_t{4});
    QCOMPARE(d.counters().skippedBytes, std::uint64_t{0});
    QCOMPARE(d.pendingBytes(), std::size_t{0});
  }

  void decoderRecovers_data() {
    QTest::addColumn<Bytes>("stream");
    QTest::addColumn<int>("packets");
    QTest::addColumn<int>("badChecksums");
    QTest::addColumn<int>("badCounts");
    QTest::addColumn<int>("skipped");
    // Noise before a frame: 3 bytes skipped (the lone FA too, as FB does not follow it).
    QTest::newRow("noise, then SYNC1") << hex("01 FA 02 FA FB 03 01 00 01") << 1 << 0 << 0 << 3;
    // A checksum off by one: the frame's 6 bytes are skipped one by one after the search resumes
    // behind its FA; the good frame after it is read.
    QTest::newRow("bad checksum, then SYNC1")
        << hex("FA FB 03 01 00 02 FA FB 03 01 00 01") << 1 << 1 << 0 << 6;
    // A count below 3 cannot hold ID and checksum.
    QTest::newRow("count 2, then SYNC0") << hex("FA FB 02 FA FB 03 00 00 00") << 1 << 0 << 1 << 3;
    // A header with count 16 swallows a real SYNC0 and 13 zeros; its checksum fails, and the
    // search, resumed one byte after its FA, finds the SYNC0 inside it.
    QTest::newRow("frame hidden in a corrupt one")
        << hex("FA FB 10 FA FB 03 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00") << 1 << 1
        << 0 << 17;
    // A truncated SIP followed by a whole SYNC2: the SIP's count covers the SYNC2; the checksum
    // fails and SYNC2 is found again.
    QTest::newRow("truncated packet")
        << hex("FA FB 0A 32 10 00 FA FB 03 02 00 02 00 00 00 00") << 1 << 1 << 0 << 10;
  }
  void decoderRecovers() {
    QFETCH(Bytes, stream);
    QFETCH(int, packets);
    QFETCH(int, badChecksums);
    QFETCH(int, badCounts);
    QFETCH(int, skipped);
    arcos::PacketDecoder d;
    const auto got = decodeAll(d, stream);
    QCOMPARE(static_cast<int>(got.size()), packets);
    QCOMPARE(static_cast<int>(d.counters().badChecksums), badChecksums);
    QCOMPARE(static_cast<int>(d.counters().badCounts), badCounts);
    QCOMPARE(static_cast<int>(d.counters().skippedBytes), skipped);
    QCOMPARE(d.counters().bytes, static_cast<std::uint64_t>(stream.size()));
  }

  // A megabyte of noise with valid frames sprinkled in: every frame is found (noise may, rarely,
  // also hold a valid one), and the decoder never holds more than one unfinished frame.
  void decoderBoundedOnNoise() {
    std::mt19937_64 rng(7);
    arcos::PacketDecoder d;
    const Bytes frame = arcos::encodeCommand(arcos::command::kVel, -200);
    std::size_t inserted = 0;
    std::size_t found = 0;
    std::size_t maxPending = 0;
    for (int block = 0; block < 1024; ++block) {
      Bytes chunk(1024);
      for (std::uint8_t& b : chunk) b = static_cast<std::uint8_t>(rng());
      // One frame in every other block, after a full frame's length of quiet so that no
      // corrupt header can still be waiting to swallow it.
      if (block % 2 == 0) {
        std::fill(chunk.end() - 300, chunk.end(), std::uint8_t{0});
        chunk.insert(chunk.end(), frame.begin(), frame.end());
        ++inserted;
      }
      d.feed(chunk, [&](const arcos::Packet& p) {
        if (arcos::framePacket(p) == frame) ++found;
      });
      maxPending = std::max(maxPending, d.pendingBytes());
    }
    QVERIFY(found >= inserted);
    QVERIFY2(maxPending < arcos::kMaxFrameBytes, QByteArray::number(qulonglong(maxPending)));
    QVERIFY(d.counters().badChecksums > 0);
  }

  // ---------------------------------------------------------------------------------------------
  // Messages

  void serverInfo_data() {
    QTest::addColumn<Bytes>("payload");
    QTest::addColumn<bool>("valid");
    QTest::addColumn<QString>("subclass");
    QTest::newRow("three strings") << hex("41 00 50 00 70 33 64 78 00") << true << "p3dx";
    QTest::newRow("empty strings") << hex("00 00 00") << true << "";
    QTest::newRow("trailing bytes tolerated") << hex("00 00 61 00 FF") << true << "a";
    QTest::newRow("subclass without NUL") << hex("41 00 50 00 70 33") << false << "";
    QTest::newRow("empty payload") << Bytes{} << false << "";
  }
  void serverInfo() {
    QFETCH(Bytes, payload);
    QFETCH(bool, valid);
    QFETCH(QString, subclass);
    const auto info = arcos::decodeServerInfo(payload);
    QCOMPARE(info.has_value(), valid);
    if (info) QCOMPARE(QString::fromStdString(info->subclass), subclass);
  }

  void sipLayout() {
    // Built by hand after the SIP layout: XPOS 0010, YPOS 7FF0, THPOS 1024, LVEL 100, RVEL -100,
    // battery 125, stall 0, control 0, flags 1, compass 0, 2 sonars (3: 500, 15: 5000), then two
    // bytes of an optional field.
    const Bytes payload =
        hex("10 00 F0 7F 00 04 64 00 9C FF 7D 00 00 00 00 01 00 00 02 03 F4 01 0F 88 13 AA BB");
    const auto sip = arcos::decodeSip(payload, true);
    QVERIFY(sip);
    QCOMPARE(sip->xpos, std::uint16_t{0x10});
    QCOMPARE(sip->ypos, std::uint16_t{0x7FF0});
    QCOMPARE(sip->thpos, std::int16_t{1024});
    QCOMPARE(sip->leftVel, std::int16_t{100});
    QCOMPARE(sip->rightVel, std::int16_t{-100});
    QCOMPARE(sip->battery, std::uint8_t{125});
    QCOMPARE(sip->flags, arcos::kMotorsOnFlag);
    QCOMPARE(sip->sonars.size(), std::size_t{2});
    QCOMPARE(sip->sonars[0], (arcos::SonarEcho{3, 500}));
    QCOMPARE(sip->sonars[1], (arcos::SonarEcho{15, 5000}));
    QCOMPARE(sip->trailing, hex("AA BB"));
    // Encoding gives the same bytes back, in a frame of ID 0x33 (moving).
    const Bytes frame = arcos::encodeSip(*sip);
    QCOMPARE(frame[3], arcos::packet_id::kSipMoving);
    QVERIFY(Bytes(frame.begin() + 4, frame.end() - 2) == payload);
    // The 16th bit of a position counter is not part of it.
    Bytes high = payload;
    high[1] = 0x80;
    QCOMPARE(arcos::decodeSip(high, false)->xpos, std::uint16_t{0x10});
  }

  void sipMalformed_data() {
    QTest::addColumn<Bytes>("payload");
    QTest::addColumn<bool>("valid");
    const Bytes fixed = hex("00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00 00");
    Bytes noSonars = fixed;
    noSonars.push_back(0);
    Bytes twoClaimedOneSent = fixed;
    for (const std::uint8_t b : hex("02 01 10 00")) twoClaimedOneSent.push_back(b);
    QTest::newRow("fixed fields only, no count") << fixed << false;
    QTest::newRow("no sonars") << noSonars << true;
    QTest::newRow("count 2, one reading") << twoClaimedOneSent << false;
    QTest::newRow("empty") << Bytes{} << false;
  }
  void sipMalformed() {
    QFETCH(Bytes, payload);
    QFETCH(bool, valid);
    QCOMPARE(arcos::decodeSip(payload, false).has_value(), valid);
  }

  void simStatLayout() {
    arcos::SimStat s;
    s.flags = 0x01020304;
    s.simInterval = 100;
    s.realInterval = 101;
    s.lastInterval = 102;
    s.trueX = -1500;
    s.trueY = 2500;
    s.trueZ = 0;
    s.trueThetaDeg = -90;
    s.trailing = hex("01 02 03");
    const Bytes frame = arcos::encodeSimStat(s);
    QCOMPARE(frame[3], arcos::packet_id::kSimStat);
    const Bytes payload(frame.begin() + 4, frame.end() - 2);
    // 2 reserved, flags (LE), three intervals, X = -1500 = FFFFFA24 (LE 24 FA FF FF), ...
    QVERIFY2(payload == hex("00 00 04 03 02 01 64 00 65 00 66 00 24 FA FF FF C4 09 00 00 00 00 00 "
                            "00 A6 FF FF FF 01 02 03"),
             show(payload));
    QCOMPARE(arcos::decodeSimStat(payload), std::optional(s));
    QVERIFY(!arcos::decodeSimStat(Bytes(payload.begin(), payload.begin() + 27)));
  }

  void commandsDecoded_data() {
    QTest::addColumn<Bytes>("frame");
    QTest::addColumn<bool>("valid");
    QTest::addColumn<int>("number");
    QTest::addColumn<int>("value");
    QTest::newRow("VEL -200") << hex("FA FB 06 0B 1B C8 00 D3 1B") << true << 11 << -200;
    QTest::newRow("OPEN 1") << hex("FA FB 06 01 3B 01 00 02 3B") << true << 1 << 1;
    QTest::newRow("PULSE") << hex("FA FB 03 00 00 00") << true << 0 << 0;
    QTest::newRow("int argument cut short")
        << arcos::framePacket(11, hex("3B 01")) << false << 11 << 0;
    QTest::newRow("unknown argument type")
        << arcos::framePacket(11, hex("3C 01 00")) << false << 11 << 0;
    QTest::newRow("string longer than said")
        << arcos::framePacket(15, hex("2B 01 61 62")) << false << 15 << 0;
  }
  void commandsDecoded() {
    QFETCH(Bytes, frame);
    QFETCH(bool, valid);
    QFETCH(int, number);
    QFETCH(int, value);
    arcos::PacketDecoder d;
    const auto packets = decodeAll(d, frame);
    QCOMPARE(packets.size(), std::size_t{1});
    const auto c = arcos::decodeCommand(packets[0]);
    QCOMPARE(c.has_value(), valid);
    if (!c) return;
    QCOMPARE(static_cast<int>(c->number), number);
    QCOMPARE(c->value, value);
  }

  void vel2Wheels_data() {
    QTest::addColumn<int>("value");
    QTest::addColumn<int>("left");
    QTest::addColumn<int>("right");
    QTest::newRow("0A FB as sent") << 0x0AFB << 10 << -5;
    QTest::newRow("both negative") << 0xFBFB << -5 << -5;
    // A client that sent left << 8 | right & FF as a negative integer: -251 = FF05.
    QTest::newRow("negative int") << -251 << -1 << 5;
  }
  void vel2Wheels() {
    QFETCH(int, value);
    QFETCH(int, left);
    QFETCH(int, right);
    const arcos::WheelBytes w = arcos::vel2Wheels(value);
    QCOMPARE(w.left, left);
    QCOMPARE(w.right, right);
  }

  // ---------------------------------------------------------------------------------------------
  // SIPs to scans

  void wrap15_data() {
    QTest::addColumn<int>("from");
    QTest::addColumn<int>("to");
    QTest::addColumn<int>("delta");
    QTest::newRow("no change") << 100 << 100 << 0;
    QTest::newRow("forward") << 100 << 164 << 64;
    QTest::newRow("across the wrap, forward") << 0x7FF0 << 0x0010 << 32;
    QTest::newRow("across the wrap, backward") << 0x0010 << 0x7FF0 << -32;
    QTest::newRow("half the range reads backward") << 0 << 0x4000 << -0x4000;
    QTest::newRow("just under half forward") << 0 << 0x3FFF << 0x3FFF;
  }
  void wrap15() {
    QFETCH(int, from);
    QFETCH(int, to);
    QFETCH(int, delta);
    QCOMPARE(
        arcos::wrappedDelta15(static_cast<std::uint16_t>(from), static_cast<std::uint16_t>(to)),
        delta);
  }

  void signExtend15() {
    QCOMPARE(arcos::signExtend15(0x7FFF), -1);
    QCOMPARE(arcos::signExtend15(0x3FFF), 16383);
    QCOMPARE(arcos::signExtend15(0x4000), -16384);
    QCOMPARE(arcos::signExtend15(0x0010), 16);
  }

  void trackerIntegratesWrappedDeltas_data() {
    QTest::addColumn<QString>("robot");
    QTest::addColumn<double>("factor");
    QTest::newRow("p3dx 0.485 mm") << "p3dx" << 0.485;
    QTest::newRow("amigobot 0.5083 mm") << "amigobot" << 0.5083;
  }
  void trackerIntegratesWrappedDeltas() {
    QFETCH(QString, robot);
    QFETCH(double, factor);
    arcos::SipTracker t(*arcos::robotPreset(robot.toStdString()));
    arcos::Sip sip;
    sip.xpos = 0x7FF0;  // -16 units: the first SIP is read as a signed position
    sip.ypos = 1000;
    sip.thpos = 1024;  // a quarter turn: 1024 x 2 pi / 4096
    sg::Scan s = t.apply(sip, 0.0);
    QCOMPARE(s.odometry.x(), -16 * factor / 1000.0);
    QCOMPARE(s.odometry.y(), 1000 * factor / 1000.0);
    QCOMPARE(s.odometry.heading, std::numbers::pi / 2);
    // Forward across the wrap: 0x7FF0 -> 0x0010 is +32 units.
    sip.xpos = 0x0010;
    s = t.apply(sip, 0.1);
    QCOMPARE(s.odometry.x(), (-16 * factor + 32 * factor) / 1000.0);
    // Forty thousand units onward in steps of 1000 (beyond one wrap of the counter): the pose
    // keeps counting.
    std::uint16_t x = 0x0010;
    for (int i = 0; i < 40; ++i) {
      x = static_cast<std::uint16_t>((x + 1000) & 0x7FFF);
      sip.xpos = x;
      s = t.apply(sip, 0.2 + i);
    }
    QVERIFY(std::abs(s.odometry.x() - (16 + 40000) * factor / 1000.0) < 1e-9);
    // THPOS -2048 is half a turn, wrapped to [-pi, pi).
    sip.thpos = -2048;
    QCOMPARE(t.apply(sip, 50.0).odometry.heading, -std::numbers::pi);
  }

  void trackerReadsSonars() {
    arcos::SipTracker t(arcos::pioneer3dxParameters());
    arcos::Sip sip;
    sip.sonars = {{3, 500}, {15, 5000}, {7, 4999}, {16, 100}};
    const sg::Scan s = t.apply(sip, 2.5);
    // Sonar 16 is not on a 16-sonar ring: dropped and counted.
    QCOMPARE(s.readings.size(), std::size_t{3});
    QCOMPARE(t.droppedReadings(), std::uint64_t{1});
    QCOMPARE(s.readings[0], (sg::Reading{3, 0.5, 2.5}));
    // 5000 mm, the maximum range: no echo.
    QCOMPARE(s.readings[1], (sg::Reading{15, sg::Reading::kNoEcho, 2.5}));
    QCOMPARE(s.readings[2], (sg::Reading{7, 4.999, 2.5}));
    // The latest range per transducer; the others have not reported yet.
    QCOMPARE(t.latestRanges()[3], 0.5);
    QVERIFY(std::isinf(t.latestRanges()[15]));
    QVERIFY(std::isnan(t.latestRanges()[0]));
    // A later SIP with only sonar 3 updates it and keeps the rest.
    sip.sonars = {{3, 750}};
    QCOMPARE(t.apply(sip, 2.6).readings.size(), std::size_t{1});
    QCOMPARE(t.latestRanges()[3], 0.75);
    QCOMPARE(t.latestRanges()[7], 4.999);
  }

  void trackerPairsTruthWithNextSip() {
    arcos::SipTracker t(arcos::pioneer3dxParameters());
    arcos::SimStat stat;
    stat.trueX = 1500;
    stat.trueY = -250;
    stat.trueThetaDeg = 270;  // wrapped to -90 degrees
    t.setTruth(stat);
    const sg::Scan first = t.apply(arcos::Sip{}, 1.0);
    QVERIFY(first.truth);
    QCOMPARE(first.truth->x(), 1.5);
    QCOMPARE(first.truth->y(), -0.25);
    QVERIFY(std::abs(first.truth->heading + std::numbers::pi / 2) < 1e-12);
    // Without a new SIMSTAT the next SIP has no true pose.
    QVERIFY(!t.apply(arcos::Sip{}, 1.1).truth);
  }

  void subclasses_data() {
    QTest::addColumn<QString>("subclass");
    QTest::addColumn<QString>("preset");
    QTest::newRow("p3dx") << "p3dx"
                          << "p3dx";
    QTest::newRow("p3dx-sh") << "p3dx-sh"
                             << "p3dx";
    QTest::newRow("P3DX upper case") << "P3DX"
                                     << "p3dx";
    QTest::newRow("amigo") << "amigo"
                           << "amigobot";
    QTest::newRow("amigo-sh") << "amigo-sh"
                              << "amigobot";
    QTest::newRow("unknown") << "p3at"
                             << "";
  }
  void subclasses() {
    QFETCH(QString, subclass);
    QFETCH(QString, preset);
    const auto p = arcos::parametersForSubclass(subclass.toStdString());
    QCOMPARE(p ? QString::fromStdString(p->preset) : QString(), preset);
    if (p) QCOMPARE(p->ring.maxRange, 5.0);
  }

  // ---------------------------------------------------------------------------------------------
  // The virtual robot and the client session, in memory

  // The firing schedule: each bank fires one sonar every 40 ms from OPEN, SIPs leave every 100 ms
  // with what fired since the last one. Per 200 ms, 5 firing times (0, 40, ..., 160): the SIPs at
  // 100, 200, 300, 400 ms carry the firings at {0, 40, 80}, {120, 160, 200}, {240, 280},
  // {320, 360, 400}: 3, 3, 2, 3 firing times.
  void firingSchedule_data() {
    QTest::addColumn<QString>("robot");
    QTest::addColumn<int>("banks");
    QTest::newRow("p3dx: two banks of 8") << "p3dx" << 2;
    QTest::newRow("amigobot: one bank of 8") << "amigobot" << 1;
  }
  void firingSchedule() {
    QFETCH(QString, robot);
    QFETCH(int, banks);
    arcos::VirtualRobotSettings settings;
    settings.robot = *arcos::robotPreset(robot.toStdString());
    arcos::VirtualRobot r(room(), sg::Pose2D(3.5, 2.5, 0.0), std::nullopt, settings);
    MemoryLink link(r);
    link.session.start(0.0);
    link.run(0.05);  // handshake
    QVERIFY(link.session.isOpen());
    link.served.clear();
    link.run(1.0);
    QVERIFY(link.served.size() >= 9);
    const int expected[] = {3, 3, 2, 3};
    for (int k = 0; k < 4; ++k) {
      QCOMPARE(static_cast<int>(link.served[static_cast<std::size_t>(k)].readings.size()),
               expected[k] * banks);
    }
    // Order: bank 0 fires 0, 1, 2, ...; bank 1 fires 8, 9, 10, ... at the same moments.
    std::vector<int> order;
    for (const sg::Scan& s : link.served) {
      for (const sg::Reading& rd : s.readings) order.push_back(rd.sonar);
    }
    for (std::size_t i = 0; i < 20; ++i) {
      const int tick = static_cast<int>(i) / banks;
      const int bank = static_cast<int>(i) % banks;
      QCOMPARE(order[i], bank * 8 + tick % 8);
    }
  }

  // The whole session in memory: the client's scans are the robot's, reading for reading, and
  // its poses are the robot's to within the SIP's units (0.485 mm, 2 pi / 4096 rad).
  void sessionMatchesServedScans() {
    arcos::VirtualRobotSettings settings;
    settings.physics.seed = 3;
    arcos::VirtualRobot r(room(), sg::Pose2D(1.0, 1.0, 0.3), std::nullopt, settings);
    MemoryLink link(r);
    link.session.start(0.0);
    link.run(0.1);
    QVERIFY(link.server);
    QCOMPARE(QString::fromStdString(link.server->subclass), QString("p3dx"));
    link.session.setVelocity(0.3, 0.2, link.t);
    link.run(3.0);
    QVERIFY(r.clientDriving());
    QVERIFY(link.scans.size() >= 29);
    QCOMPARE(link.scans.size(), link.served.size());
    const double quantum = 0.485e-3;
    for (std::size_t i = 0; i < link.scans.size(); ++i) {
      const sg::Scan& got = link.scans[i];
      const sg::Scan& sent = link.served[i];
      QCOMPARE(got.readings.size(), sent.readings.size());
      for (std::size_t k = 0; k < got.readings.size(); ++k) {
        QCOMPARE(got.readings[k].sonar, sent.readings[k].sonar);
        QCOMPARE(got.readings[k].range, sent.readings[k].range);
      }
      QVERIFY(std::abs(got.odometry.x() - sent.odometry.x()) <= quantum);
      QVERIFY(std::abs(got.odometry.y() - sent.odometry.y()) <= quantum);
      QVERIFY(std::abs(sg::wrapAngle(got.odometry.heading - sent.odometry.heading)) <=
              std::numbers::pi / 4096 + 1e-12);
      // "SonarGridSim" is a simulator: SIM_STAT 2 gives every SIP a true pose, in whole mm and
      // degrees.
      QVERIFY(got.truth);
      QVERIFY(std::abs(got.truth->x() - sent.truth->x()) <= 0.0005 + 1e-12);
      QVERIFY(std::abs(sg::wrapAngle(got.truth->heading - sent.truth->heading)) <=
              sg::degToRad(0.5) + 1e-12);
    }
    // It drove: 3 s at 0.3 m/s on an arc.
    QVERIFY((link.scans.back().odometry.position - sg::Position(1.0, 1.0)).norm() > 0.6);
    QCOMPARE(link.session.counters().readings, r.counters().readings);
    QCOMPARE(link.session.counters().errors(), std::uint64_t{0});
  }

  // A client that only listened leaves a self-driving robot on its route when it closes; one
  // that drove it stops it first.
  void closeLeavesARouteAlone() {
    const sg::Pose2D start(1.0, 2.5, 0.0);
    const sg::Trajectory path(start, {sg::PathPiece{5.0, 0.0, 0.0}}, sg::DriveLimits{});
    for (const bool drive : {false, true}) {
      arcos::VirtualRobot r(room(), start, arcos::RoutePlan{path, {}, 0.0}, {});
      MemoryLink link(r);
      link.session.start(0.0);
      link.run(1.0);
      QVERIFY(r.truePose().x() > 1.2);  // on its way along the route at 0.3 m/s
      if (drive) link.session.setVelocity(0.1, 0.0, link.t);
      link.run(0.1);
      link.session.close(link.t);
      link.run(0.1);
      QVERIFY(r.closeRequested());
      QCOMPARE(r.clientDriving(), drive);
      const double x = r.truePose().x();
      Bytes none;
      r.advanceTo(link.t + 1.0, none);
      // Still driving its route at 0.3 m/s, or stopped.
      QCOMPARE(r.truePose().x() > x + 0.25, !drive);
    }
  }

  // Nothing sent for half a second: PULSE. Nothing heard for two: the connection is lost.
  void keepAliveAndLoss() {
    arcos::VirtualRobot r(room(), sg::Pose2D(3.5, 2.5, 0.0), std::nullopt, {});
    MemoryLink link(r);
    link.session.start(0.0);
    link.run(2.0);
    // OPEN at 0.03 s; PULSE at 0.53, 1.03, 1.53 (each after 0.5 s of silence, checked every
    // 10 ms: at most one step late).
    QCOMPARE(link.session.counters().pulses, std::uint64_t{3});
    QVERIFY(link.lostReason.empty());
    // The last SIP came at most 0.1 s before the robot went deaf.
    link.run(1.8, true);
    QVERIFY(link.lostReason.empty());
    link.run(0.4, true);
    QVERIFY2(link.lostReason.starts_with("no packet from the robot"), link.lostReason.c_str());
    QVERIFY(!link.session.isOpen());
    QCOMPARE(link.session.counters().timeouts, std::uint64_t{1});
  }

  // A robot that never answers: the handshake starts over every second, and gives up after 5.
  void handshakeTimesOut() {
    struct Silent : arcos::ClientSession::Listener {
      int syncs = 0;
      std::string lost;
      void sendBytes(std::span<const std::uint8_t> b) override {
        if (Bytes(b.begin(), b.end()) == arcos::encodeCommand(arcos::packet_id::kSync0)) ++syncs;
      }
      void onLost(const std::string& reason) override { lost = reason; }
    } silent;
    arcos::ClientSession s({}, silent);
    s.start(0.0);
    for (int i = 1; i <= 600; ++i) s.tick(i * 0.01);
    QCOMPARE(silent.syncs, 5);  // at 0, 1, 2, 3 and 4 s
    QVERIFY2(silent.lost.starts_with("no answer to the handshake"), silent.lost.c_str());
    QVERIFY2(silent.lost.ends_with(": nothing came back (is the robot on, and the port or "
                                   "address right?)"),
             silent.lost.c_str());
  }

  // Issue 50 item 9: a handshake that fails on garbage says what came back and the likely
  // cause. Every 10 ms the line brings 8 bytes: the header FA FB, count 5 (three payload bytes
  // and the two of the checksum), 01 02 03 and a checksum of 0; ARCOS sums the payload as
  // big-endian byte pairs and XORs an odd last byte in, 0x0102 ^ 0x03 = 0x0101, so no packet is
  // valid. The tick at 5 s gives up after that tick's bytes: 500 ticks of 8 bytes.
  void handshakeOnGarbageSaysWhatCameBack() {
    struct Listener : arcos::ClientSession::Listener {
      std::string lost;
      void sendBytes(std::span<const std::uint8_t>) override {}
      void onLost(const std::string& reason) override { lost = reason; }
    } listener;
    arcos::ClientSession s({}, listener);
    s.start(0.0);
    const Bytes noise{0xFA, 0xFB, 0x05, 0x01, 0x02, 0x03, 0x00, 0x00};
    for (int i = 1; i <= 600 && listener.lost.empty(); ++i) {
      s.receive(noise, i * 0.01);
      s.tick(i * 0.01);
    }
    const std::string& why = listener.lost;
    QVERIFY2(why.starts_with("no answer to the handshake within 5.0 s: 4000 bytes came back, 0 "
                             "valid packets, "),
             why.c_str());
    QVERIFY2(why.ends_with(" (wrong baud rate, or not an ARCOS robot?)"), why.c_str());
    QVERIFY(s.counters().framing.badChecksums > 0);
  }

  // The robot obeys motion commands, refuses to drive into a wall and stops when its client
  // goes quiet; unknown commands are ignored.
  void everyBundledWorldHasARouteEveryRobotDrives_data() {
    QTest::addColumn<QString>("world");
    QTest::addColumn<QString>("robot");
    QTest::addColumn<QString>("route");
    // The Robot dock's chooser: every datasets/*/world.json, both robots, the three routes.
    const QDir root(QStringLiteral(SONARGRID_DATASETS));
    for (const QString& d : root.entryList(QDir::Dirs | QDir::NoDotAndDotDot, QDir::Name)) {
      const QString world = root.filePath(d + QStringLiteral("/world.json"));
      if (!QFileInfo::exists(world)) continue;
      for (const char* robot : {"p3dx", "amigobot"})
        for (const char* route : {"in-motion", "stop-and-scan", "u-turn"})
          QTest::addRow("%s %s %s", qPrintable(d), robot, route) << world << robot << route;
    }
  }

  void everyBundledWorldHasARouteEveryRobotDrives() {
    // Issue 49 item 10: the virtual robot's defaults failed on arafat-room ("the route passes
    // 0.002 m from a surface"), office and raschke-multi: the route planned from a world's bounds
    // crosses its furniture. A world's own route.txt (worldRoute()) keeps clear for both robots.
    QFETCH(QString, world);
    QFETCH(QString, robot);
    QFETCH(QString, route);
    const std::string path = world.toStdString();
    const std::vector<sg::Position> waypoints = sg::worldRoute(path);
    QVERIFY2(!waypoints.empty(), "the world has no route.txt beside it");
    const std::optional<sg::arcos::RobotParameters> preset =
        sg::arcos::robotPreset(robot.toStdString());
    QVERIFY(preset);
    sg::SimulationSettings sim;
    sim.route = *sg::routeKindFromName(route.toStdString());
    const sg::arcos::VirtualRoute planned =
        sg::arcos::planVirtualRoute(sg::readReferenceJson(path), preset->ring, sim, waypoints);
    QVERIFY(planned.plan);
    QVERIFY(planned.plan->path.length() > 1.0);
  }

  void virtualRobotCommands() {
    arcos::VirtualRobot r(room(), sg::Pose2D(5.0, 2.5, 0.0), std::nullopt, {});
    MemoryLink link(r);
    link.session.start(0.0);
    link.run(0.1);
    link.session.setVelocity(0.2, 0.0, link.t);
    link.run(1.0);
    // 1 s at 0.2 m/s, give or take a 10 ms step either side.
    QVERIFY(std::abs(r.truePose().x() - 5.2) <= 0.2 * 0.02);
    link.session.setVelocity(0.5, 0.0, link.t);
    link.run(6.0);
    // The wall at x = 7; the body (radius: the farthest sonar, 0.256 m) stops short of it, by
    // less than one 10 ms step at 0.5 m/s.
    const double radius = sg::robotBody(sg::SonarRing::pioneer3dx()).radius;
    QVERIFY(r.counters().stalls > 0);
    QVERIFY(r.truePose().x() < 7.0 - radius);
    QVERIFY(r.truePose().x() >= 7.0 - radius - 0.005);
    // SETV 100 mm/s: a later VEL 500 drives at 100 mm/s (half a second: 5 cm back).
    link.session.setSpeedLimits(0.1, 1.0, link.t);
    link.session.setVelocity(-0.5, 0.0, link.t);
    const double before5 = r.truePose().x();
    link.run(0.5);
    QVERIFY(std::abs(r.truePose().x() - (before5 - 0.05)) <= 0.1 * 0.02);
    link.session.setSpeedLimits(1.2, 1.0, link.t);
    // Unknown command 99: ignored, the robot keeps streaming.
    const std::size_t before = link.served.size();
    link.session.sendCommand(arcos::encodeCommand(99, 1), link.t);
    link.run(0.5);
    QCOMPARE(r.counters().ignoredCommands, std::uint64_t{1});
    QVERIFY(link.served.size() > before);
    // Back off, then silence: the watchdog stops the robot after 2 s.
    link.session.setVelocity(-0.2, 0.0, link.t);
    link.run(0.5);
    const double x0 = r.truePose().x();
    // The robot's bytes are lost from here; the client keeps sending PULSE until it gives the
    // connection up after 2 s, and PULSE alone keeps a client-driven robot going.
    link.run(3.0, true);
    QVERIFY(r.truePose().x() < x0 - 0.5);
    arcos::VirtualRobot quiet(room(), sg::Pose2D(3.5, 2.5, 0.0), std::nullopt, {});
    Bytes out;
    quiet.clientConnected(0.0);
    for (const Bytes& b : {arcos::encodeCommand(0), arcos::encodeCommand(1),
                           arcos::encodeCommand(2), arcos::encodeCommand(arcos::command::kOpen, 1),
                           arcos::encodeCommand(arcos::command::kVel, 200)}) {
      quiet.receive(b, 0.0, out);
    }
    QVERIFY(quiet.isOpen());
    quiet.advanceTo(1.0, out);
    QVERIFY(std::abs(quiet.truePose().x() - 3.7) < 1e-9);
    quiet.advanceTo(5.0, out);
    // Stopped once 2 s passed without a packet: at most 2 s x 0.2 m/s more.
    QVERIFY(std::abs(quiet.truePose().x() - (3.5 + 0.2 * 2.0)) < 0.2 * 0.011);
  }
};

QTEST_GUILESS_MAIN(TstArcos)
#include "tst_arcos.moc"
