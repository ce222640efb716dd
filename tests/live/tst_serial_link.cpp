// SPDX-License-Identifier: BSD-3-Clause
// The robot link's serial path (docs/live-robot.md, "Serial"): a pseudo-terminal pair stands for
// the cable; the test serves the virtual robot on the master side, the link opens the slave as a
// serial port, shakes hands, streams SIPs (the readings are the robot's, reading for reading),
// drives the robot and closes the session; and when the device goes away the link says so.

#include <fcntl.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <QElapsedTimer>
#include <QSignalSpy>
#include <QSocketNotifier>
#include <QTimer>
#include <QtTest>
#include <cerrno>
#include <cstring>

#include "sonargrid/arcos/virtual_robot.h"
#include "sonargrid/live/robot_link.h"
#include "sonargrid/sim/ray_sonar.h"

namespace arcos = sg::arcos;

namespace {

sg::SonarWorld room() {
  const std::vector<sg::Position> corners{{0, 0}, {7, 0}, {7, 5}, {0, 5}};
  return sg::SonarWorld(sg::polygonSegments(corners, true));
}

// The robot's end of the cable: the virtual robot behind the pty master.
class PtyRobot {
 public:
  explicit PtyRobot(arcos::VirtualRobot& robot) : robot_(robot) {
    termios raw{};
    cfmakeraw(&raw);
    char name[256] = {};
    if (::openpty(&master_, &slave_, name, &raw, nullptr) != 0) {
      error = std::string("openpty: ") + std::strerror(errno);
      return;
    }
    device = name;
    ::fcntl(master_, F_SETFL, ::fcntl(master_, F_GETFL) | O_NONBLOCK);
    notifier_ = std::make_unique<QSocketNotifier>(master_, QSocketNotifier::Read);
    QObject::connect(notifier_.get(), &QSocketNotifier::activated, [this] { onBytes(); });
    clock_.start();
    robot_.clientConnected(0.0);
    tick_.setInterval(10);
    QObject::connect(&tick_, &QTimer::timeout, [this] {
      arcos::Bytes out;
      robot_.advanceTo(now(), out);
      write(out);
    });
    tick_.start();
  }
  ~PtyRobot() { hangUp(); }

  // The cable is pulled: both ends of the pair close.
  void hangUp() {
    tick_.stop();
    notifier_.reset();
    if (master_ >= 0) ::close(master_);
    if (slave_ >= 0) ::close(slave_);
    master_ = slave_ = -1;
  }

  std::string device;
  std::string error;

 private:
  double now() const { return static_cast<double>(clock_.nsecsElapsed()) * 1e-9; }

  void onBytes() {
    char buf[4096];
    for (;;) {
      const ssize_t n = ::read(master_, buf, sizeof buf);
      if (n <= 0) return;
      arcos::Bytes out;
      robot_.advanceTo(now(), out);
      robot_.receive(
          std::span(reinterpret_cast<const std::uint8_t*>(buf), static_cast<std::size_t>(n)), now(),
          out);
      write(out);
    }
  }

  void write(const arcos::Bytes& out) {
    std::size_t done = 0;
    while (done < out.size() && master_ >= 0) {
      const ssize_t n = ::write(master_, out.data() + done, out.size() - done);
      if (n <= 0) return;  // the far end is not reading: drop the rest, as a full UART would
      done += static_cast<std::size_t>(n);
    }
  }

  arcos::VirtualRobot& robot_;
  int master_ = -1;
  int slave_ = -1;  // held open so that the master never reads a hang-up before the link opens
  std::unique_ptr<QSocketNotifier> notifier_;
  QElapsedTimer clock_;
  QTimer tick_;
};

}  // namespace

class TstSerialLink : public QObject {
  Q_OBJECT

 private slots:
  void sessionOverAPseudoTerminal() {
    arcos::VirtualRobotSettings settings;
    settings.robot = arcos::amigobotParameters();
    settings.server = {"SonarGridSim", "Pioneer", "amigo"};
    arcos::VirtualRobot robot(room(), sg::Pose2D(3.5, 2.5, 0.0), std::nullopt, settings);
    std::vector<sg::Scan> served;
    robot.onSip = [&served](const sg::Scan& s) { served.push_back(s); };
    PtyRobot cable(robot);
    QVERIFY2(cable.error.empty(), cable.error.c_str());

    const sg::live::LinkAddress address =
        sg::live::parseLinkAddress("serial://" + cable.device + "?baud=115200");
    sg::live::RobotLink link(address);
    QSignalSpy connected(&link, &sg::live::RobotLink::connected);
    QSignalSpy scans(&link, &sg::live::RobotLink::scanReceived);
    link.open();
    QTRY_COMPARE_WITH_TIMEOUT(connected.size(), 1, 10000);
    QCOMPARE(connected[0][2].toString(), QString("amigo"));
    QCOMPARE(QString::fromStdString(link.robot()->preset), QString("amigobot"));
    QTRY_VERIFY_WITH_TIMEOUT(scans.size() >= 10, 10000);
    link.setVelocity(0.2, 0.0);
    QTRY_VERIFY_WITH_TIMEOUT(robot.truePose().x() > 3.6, 10000);
    link.close();
    // CLOSE reached the robot: it stopped serving.
    QTRY_VERIFY_WITH_TIMEOUT(robot.closeRequested(), 5000);

    // Every scan the link delivered is one the robot served, reading for reading.
    QVERIFY(static_cast<std::size_t>(scans.size()) <= served.size());
    std::size_t readings = 0;
    for (qsizetype i = 0; i < scans.size(); ++i) {
      const auto got = scans[i][0].value<sg::Scan>();
      const sg::Scan& sent = served[static_cast<std::size_t>(i)];
      QCOMPARE(got.readings.size(), sent.readings.size());
      for (std::size_t k = 0; k < got.readings.size(); ++k) {
        QCOMPARE(got.readings[k].sonar, sent.readings[k].sonar);
        QCOMPARE(got.readings[k].range, sent.readings[k].range);
      }
      readings += got.readings.size();
    }
    QVERIFY(readings > 0);
    QCOMPARE(link.counters().readings, std::uint64_t(readings));
    QCOMPARE(link.counters().errors(), std::uint64_t{0});
  }

  // The device goes away mid-session (a USB adapter pulled): reported, and no crash while the
  // link keeps trying a device that is not there.
  void deviceGoesAway() {
    arcos::VirtualRobot robot(room(), sg::Pose2D(3.5, 2.5, 0.0), std::nullopt, {});
    auto cable = std::make_unique<PtyRobot>(robot);
    QVERIFY2(cable->error.empty(), cable->error.c_str());
    sg::live::RobotLink::Options o;
    o.reconnectFirstMs = 100;
    o.reconnectMaxMs = 200;
    sg::live::RobotLink link(sg::live::parseLinkAddress("serial://" + cable->device), o);
    QSignalSpy connected(&link, &sg::live::RobotLink::connected);
    QSignalSpy disconnected(&link, &sg::live::RobotLink::disconnected);
    QSignalSpy errors(&link, &sg::live::RobotLink::error);
    link.open();
    QTRY_COMPARE_WITH_TIMEOUT(connected.size(), 1, 10000);
    cable.reset();
    QTRY_COMPARE_WITH_TIMEOUT(disconnected.size(), 1, 10000);
    QTRY_VERIFY_WITH_TIMEOUT(errors.size() >= 2, 10000);
    QCOMPARE(connected.size(), 1);
    QVERIFY(link.counters().attempts >= 3);
    link.close();
  }
};

QTEST_GUILESS_MAIN(TstSerialLink)
#include "tst_serial_link.moc"
