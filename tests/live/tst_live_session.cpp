// SPDX-License-Identifier: GPL-3.0-or-later
// `sonargrid-cli robot` and `sonargrid-cli record` in whole sessions over loopback (docs/cli.md,
// "robot" and "record"): the recorded log is the virtual robot's own ground-truth log, reading
// for reading, and maps to the same grid; a robot killed and restarted costs nothing recorded
// before the kill; SIGINT and SIGTERM leave a complete log and SIGKILL one that loads with the
// readings up to its last second; a second client is refused; bad arguments exit 2.

#include <signal.h>

#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QRegularExpression>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QtTest>
#include <cmath>
#include <numbers>

#include "growing_log.h"
#include "sonargrid/data/dataset.h"
#include "sonargrid/engine/mapper.h"
#include "sonargrid/io/log_reader.h"
#include "sonargrid/io/sglog.h"

namespace {

const QString kCli = QStringLiteral(SONARGRID_CLI);
const QString kWorld = QStringLiteral(SONARGRID_DATASETS) + "/raschke-single/world.json";
// A Pioneer 3-DX fires two sonars every 40 ms: 50 readings a second.
constexpr int kReadingsPerSecond = 50;

// A `sonargrid-cli robot` on a port the system picks (or a given one).
class Robot {
 public:
  // Starts it; false (with `error`) when it does not report listening within 20 s.
  bool start(const QStringList& extra, quint16 onPort = 0) {
    QStringList args{"robot", "--world", kWorld, "--port", QString::number(onPort)};
    args += extra;
    process.setProcessChannelMode(QProcess::SeparateChannels);
    process.start(kCli, args);
    QElapsedTimer t;
    t.start();
    static const QRegularExpression listening("listening on [0-9.]+:([0-9]+)");
    while (t.elapsed() < 20000) {
      if (!process.waitForReadyRead(200) && process.state() == QProcess::NotRunning) break;
      out += process.readAllStandardOutput();
      const auto m = listening.match(QString::fromUtf8(out));
      if (m.hasMatch()) {
        port = static_cast<quint16>(m.captured(1).toUInt());
        return true;
      }
    }
    error = "robot did not start: " + out + process.readAllStandardError();
    return false;
  }

  // SIGTERM, then the rest of its output; its exit code (-1 if it had to be killed).
  int stop() {
    if (process.state() != QProcess::NotRunning) {
      process.terminate();
      if (!process.waitForFinished(10000)) {
        process.kill();
        process.waitForFinished(5000);
        return -1;
      }
    }
    out += process.readAllStandardOutput();
    return process.exitStatus() == QProcess::NormalExit ? process.exitCode() : -1;
  }

  void kill9() {
    process.kill();
    process.waitForFinished(5000);
  }

  QString address() const { return QStringLiteral("tcp://127.0.0.1:%1").arg(port); }

  QProcess process;
  quint16 port = 0;
  QByteArray out;
  QByteArray error;
};

struct Finished {
  int code = -1;
  QByteArray out;
  QByteArray err;
  QJsonObject json;
};

Finished finish(QProcess& p, int timeoutMs) {
  Finished f;
  if (!p.waitForFinished(timeoutMs) || p.exitStatus() != QProcess::NormalExit) {
    p.kill();
    p.waitForFinished(5000);
    f.err = "did not finish normally";
    return f;
  }
  f.code = p.exitCode();
  f.out = p.readAllStandardOutput();
  f.err = p.readAllStandardError();
  f.json = QJsonDocument::fromJson(f.out).object();
  return f;
}

Finished run(const QStringList& args, int timeoutMs = 60000) {
  QProcess p;
  p.start(kCli, args);
  return finish(p, timeoutMs);
}

using live_test::scanLines;
using live_test::waitForScans;

sg::Dataset load(const QString& path) {
  return sg::readSglog(path.toStdString());
}

// Scans [from, to) of a log as a log of their own.
sg::Dataset slice(const sg::Dataset& d, std::size_t from, std::size_t to) {
  sg::Dataset out;
  out.ring = d.ring;
  out.scans.assign(d.scans.begin() + static_cast<std::ptrdiff_t>(from),
                   d.scans.begin() + static_cast<std::ptrdiff_t>(to));
  return out;
}

// Splits a log at its longest pause between scans (a reconnection).
std::size_t longestGap(const sg::Dataset& d) {
  std::size_t at = 0;
  double longest = 0.0;
  for (std::size_t i = 1; i < d.scans.size(); ++i) {
    const double gap = d.scans[i].time - d.scans[i - 1].time;
    if (gap > longest) {
      longest = gap;
      at = i;
    }
  }
  return at;
}

}  // namespace

class TstLiveSession : public QObject {
  Q_OBJECT

 private slots:
  // A whole session: the log `record` writes carries exactly the readings the virtual robot sent
  // (its own --log-out), poses equal to within the SIP's units, and maps to the same grid.
  void recordedLogMatchesTheRobotsOwn() {
    QTemporaryDir dir;
    const QString serverLog = dir.filePath("server.sglog");
    const QString recorded = dir.filePath("recorded.sglog");
    Robot robot;
    QVERIFY2(robot.start({"--seed", "5", "--duration", "60", "--log-out", serverLog}),
             robot.error.constData());
    const Finished rec = run(
        {"record", "--connect", robot.address(), "--duration", "7", "--out", recorded, "--json"});
    QCOMPARE(robot.stop(), 0);
    QVERIFY2(rec.code == 0, rec.err.constData());
    QVERIFY(rec.err.isEmpty());

    const sg::Dataset got = load(recorded);
    const sg::Dataset sent = load(serverLog);
    QCOMPARE(got.ring, sent.ring);
    QCOMPARE(static_cast<qint64>(got.scans.size()), rec.json["scans"].toInteger());
    QCOMPARE(static_cast<qint64>(got.readingCount()), rec.json["readings"].toInteger());
    QCOMPARE(rec.json["link"].toObject()["bad_checksums"].toInteger(), 0);
    // About 7 s of SIPs at 10 Hz. The robot logs each SIP as it sends it, so its log also holds
    // those still on their way when the recorder closed the session: one or two on an idle
    // machine, one per 0.1 s that a loaded machine holds the recorder back from reading (over 10
    // once, in a clean clone's `ctest -j2`). The recorder must not stop reading earlier than
    // that: at most 3 s of SIPs it did not get.
    QVERIFY2(got.scans.size() >= 60, QByteArray::number(qulonglong(got.scans.size())));
    QVERIFY(sent.scans.size() >= got.scans.size());
    QVERIFY2(
        sent.scans.size() <= got.scans.size() + 30,
        qPrintable(
            QString("sent %1 scans, recorded %2").arg(sent.scans.size()).arg(got.scans.size())));
    const double quantum = 0.485e-3;  // a Pioneer 3-DX position unit, metres
    for (std::size_t i = 0; i < got.scans.size(); ++i) {
      const sg::Scan& a = got.scans[i];
      const sg::Scan& b = sent.scans[i];
      QCOMPARE(a.readings.size(), b.readings.size());
      for (std::size_t k = 0; k < a.readings.size(); ++k) {
        QCOMPARE(a.readings[k].sonar, b.readings[k].sonar);
        QCOMPARE(a.readings[k].range, b.readings[k].range);
      }
      QVERIFY(std::abs(a.odometry.x() - b.odometry.x()) <= quantum / 2 + 1e-9);
      QVERIFY(std::abs(a.odometry.y() - b.odometry.y()) <= quantum / 2 + 1e-9);
      QVERIFY(std::abs(sg::wrapAngle(a.odometry.heading - b.odometry.heading)) <=
              std::numbers::pi / 4096 + 1e-9);
      // The true pose comes from SIMSTAT, in whole millimetres and degrees.
      QVERIFY(a.truth);
      QVERIFY(std::abs(a.truth->x() - b.truth->x()) <= 0.0005 + 1e-9);
      QVERIFY(std::abs(sg::wrapAngle(a.truth->heading - b.truth->heading)) <=
              sg::degToRad(0.5) + 1e-9);
    }

    // The same scans mapped on one grid (HIMM model and rule, 5 cm cells): the poses differ by
    // less than half a position unit and a heading unit (0.09 degrees, 8 mm at 5 m), so a cell
    // may only differ where a beam edge passes within millimetres of its centre.
    const sg::Dataset sentSame = slice(sent, 0, got.scans.size());
    sg::MapperSettings settings;
    settings.model = "himm";
    settings.rule = "himm";
    settings.parameters = sg::defaultParameters("himm", "himm");
    const sg::GridSpec grid = sentSame.fittingGrid(sg::PoseSource::Odometry, 0.05);
    sg::Mapper a(got.ring, grid, settings);
    sg::Mapper b(sent.ring, grid, settings);
    QVERIFY(a.mapDataset(got));
    QVERIFY(b.mapDataset(sentSame));
    const sg::OccupancyMap ma = a.snapshot();
    const sg::OccupancyMap mb = b.snapshot();
    std::size_t observed = 0;
    std::size_t differ = 0;
    for (std::size_t c = 0; c < ma.level.size(); ++c) {
      if (!ma.observed[c] && !mb.observed[c]) continue;
      ++observed;
      if (ma.level[c] != mb.level[c]) ++differ;
    }
    qInfo("%zu scans, %zu readings; mapped: %zu observed cells, %zu differ", got.scans.size(),
          got.readingCount(), observed, differ);
    QVERIFY(observed > 1000);
    QVERIFY2(differ * 100 <= observed, "more than 1 % of the observed cells differ");

    // The CLI reads the streamed log as any other.
    const Finished map =
        run({"map", "--log", recorded, "--model", "himm", "--rule", "himm", "--json"});
    QVERIFY2(map.code == 0, map.err.constData());
    QCOMPARE(map.json["readings"].toInteger(), static_cast<qint64>(got.readingCount()));
  }

  // The route is driven out and back over and over, without a jump where one lap ends and the
  // next begins; --time-scale 50 runs 300 s of it in 6.
  void routeRepeatsWithoutJumps() {
    QTemporaryDir dir;
    const QString serverLog = dir.filePath("server.sglog");
    Robot robot;
    QVERIFY2(robot.start({"--time-scale", "50", "--log-out", serverLog}), robot.error.constData());
    const Finished rec = run({"record", "--connect", robot.address(), "--duration", "6", "--out",
                              dir.filePath("recorded.sglog"), "--json"});
    QCOMPARE(robot.stop(), 0);
    QVERIFY2(rec.code == 0, rec.err.constData());
    const sg::Dataset sent = load(serverLog);
    QVERIFY(sent.scans.size() > 1000);
    QVERIFY(sent.scans.back().time - sent.scans.front().time > 200.0);
    // Never faster than the route's 0.3 m/s and 45 deg/s (simulator.md), between any two SIPs.
    const sg::Pose2D start = *sent.scans.front().truth;
    int returns = 0;
    bool away = false;
    for (std::size_t i = 1; i < sent.scans.size(); ++i) {
      const sg::Pose2D& a = *sent.scans[i - 1].truth;
      const sg::Pose2D& b = *sent.scans[i].truth;
      const double dt = sent.scans[i].time - sent.scans[i - 1].time;
      QVERIFY((b.position - a.position).norm() <= 0.3 * dt + 1e-9);
      QVERIFY(std::abs(sg::wrapAngle(b.heading - a.heading)) <= sg::degToRad(45.0) * dt + 1e-9);
      const double fromStart = (b.position - start.position).norm();
      if (fromStart > 1.0) away = true;
      if (away && fromStart < 0.05) {
        ++returns;
        away = false;
      }
    }
    QVERIFY2(returns >= 2, QByteArray::number(returns));
  }

  // The robot is killed mid-session and started again on the same port: the recorder reports
  // it, reconnects, and its log keeps every reading from before the kill.
  void reconnectsAfterTheRobotIsKilled() {
    QTemporaryDir dir;
    const QString first = dir.filePath("first.sglog");
    const QString second = dir.filePath("second.sglog");
    const QString recorded = dir.filePath("recorded.sglog");
    Robot robot1;
    QVERIFY2(robot1.start({"--log-out", first}), robot1.error.constData());
    QProcess record;
    record.start(kCli, {"record", "--connect", robot1.address(), "--out", recorded, "--json"});
    QVERIFY(waitForScans(recorded, 25, 10000));
    robot1.kill9();
    QTest::qWait(1000);
    // What the recorder had when the robot died: the recording must keep all of it.
    const sg::Dataset atKill = load(recorded);
    Robot robot2;
    bool started = false;
    for (int attempt = 0; attempt < 10 && !started; ++attempt) {
      started = robot2.start({"--log-out", second}, robot1.port);
      if (!started) QTest::qWait(200);
    }
    QVERIFY2(started, robot2.error.constData());
    // The recorder retries after 0.5, 1, 2, 4, 8 s: wait for two seconds of the second session.
    QVERIFY(waitForScans(recorded, static_cast<int>(atKill.scans.size()) + 20, 30000));
    ::kill(static_cast<pid_t>(record.processId()), SIGINT);
    const Finished rec = finish(record, 30000);
    QCOMPARE(robot2.stop(), 0);
    QVERIFY2(rec.code == 0, rec.err.constData());

    const QJsonObject link = rec.json["link"].toObject();
    QCOMPARE(link["connections"].toInteger(), 2);
    QCOMPARE(link["reconnects"].toInteger(), 1);
    QCOMPARE(link["lost_connections"].toInteger(), 1);
    const sg::Dataset got = load(recorded);  // strict: it ends with 'end'
    const sg::Dataset before = load(first);  // streamed, cut by SIGKILL: it still loads
    const sg::Dataset after = load(second);
    QCOMPARE(static_cast<qint64>(got.readingCount()), rec.json["readings"].toInteger());
    const std::size_t cut = longestGap(got);
    const sg::Dataset gotBefore = slice(got, 0, cut);
    const sg::Dataset gotAfter = slice(got, cut, got.scans.size());
    qInfo(
        "before the kill: robot sent %zu readings, recorder kept %zu; after: %zu and %zu; "
        "pause %.2f s",
        before.readingCount(), gotBefore.readingCount(), after.readingCount(),
        gotAfter.readingCount(), got.scans[cut].time - got.scans[cut - 1].time);
    // Nothing recorded before the kill is lost: the final log starts with exactly those scans.
    QCOMPARE(gotBefore.scans.size(), atKill.scans.size());
    for (std::size_t i = 0; i < atKill.scans.size(); ++i) QCOMPARE(got.scans[i], atKill.scans[i]);
    // And they are what the robot sent, reading for reading, but for a SIP or two that died with
    // it unsent (it logs a SIP as it queues it). After the restart, likewise, but for the SIPs on
    // their way when the recorder closed the session.
    QVERIFY(gotBefore.readingCount() <= before.readingCount());
    QVERIFY(gotBefore.readingCount() + 18 >= before.readingCount());
    for (std::size_t i = 0; i < gotBefore.scans.size(); ++i) {
      QCOMPARE(gotBefore.scans[i].readings.size(), before.scans[i].readings.size());
    }
    QVERIFY(gotAfter.readingCount() <= after.readingCount());
    QVERIFY(gotAfter.readingCount() + 60 >= after.readingCount());
  }

  // SIGINT or SIGTERM: the recorder closes the session and finishes the log.
  void stopsCleanlyOnSignal_data() {
    QTest::addColumn<int>("signal");
    QTest::newRow("SIGINT") << SIGINT;
    QTest::newRow("SIGTERM") << SIGTERM;
  }
  void stopsCleanlyOnSignal() {
    QFETCH(int, signal);
    QTemporaryDir dir;
    const QString recorded = dir.filePath("recorded.sglog");
    Robot robot;
    QVERIFY2(robot.start({}), robot.error.constData());
    QProcess record;
    record.start(kCli, {"record", "--connect", robot.address(), "--out", recorded, "--json"});
    QVERIFY(waitForScans(recorded, 15, 10000));
    ::kill(static_cast<pid_t>(record.processId()), signal);
    const Finished rec = finish(record, 10000);
    QCOMPARE(robot.stop(), 0);
    QVERIFY2(rec.code == 0, rec.err.constData());
    QCOMPARE(rec.json["stopped_by"].toString(), QString(signal == SIGINT ? "SIGINT" : "SIGTERM"));
    const sg::Dataset got = load(recorded);  // strict: the log is finished
    QCOMPARE(static_cast<qint64>(got.readingCount()), rec.json["readings"].toInteger());
    QVERIFY(got.scans.size() >= 15);
    // The robot saw the session closed, not dropped.
    QVERIFY2(robot.out.contains("the client sent CLOSE"), robot.out.constData());
  }

  // SIGKILL: the log ends after its last complete scan and loads with every reading the robot
  // sent up to a second before.
  void survivesSigkill() {
    QTemporaryDir dir;
    const QString serverLog = dir.filePath("server.sglog");
    const QString recorded = dir.filePath("recorded.sglog");
    Robot robot;
    QVERIFY2(robot.start({"--log-out", serverLog}), robot.error.constData());
    QProcess record;
    record.start(kCli, {"record", "--connect", robot.address(), "--out", recorded});
    QVERIFY(waitForScans(recorded, 30, 10000));
    record.kill();
    QVERIFY(record.waitForFinished(5000));
    // What the robot had sent when the recorder died (it logs each SIP as it sends it).
    const std::size_t sentReadings = load(serverLog).readingCount();
    QCOMPARE(robot.stop(), 0);
    const sg::Dataset got = load(recorded);
    qInfo("killed: the robot had sent %zu readings, the log holds %zu", sentReadings,
          got.readingCount());
    QVERIFY(got.readingCount() <= sentReadings);
    QVERIFY(got.readingCount() + kReadingsPerSecond >= sentReadings);
    // A valid log of what the robot sent, SIP for SIP and reading for reading, up to the cut.
    const sg::Dataset sent = load(serverLog);
    QVERIFY(got.scans.size() <= sent.scans.size());
    for (std::size_t i = 0; i < got.scans.size(); ++i) {
      QCOMPARE(got.scans[i].readings.size(), sent.scans[i].readings.size());
      for (std::size_t k = 0; k < got.scans[i].readings.size(); ++k) {
        QCOMPARE(got.scans[i].readings[k].sonar, sent.scans[i].readings[k].sonar);
        QCOMPARE(got.scans[i].readings[k].range, sent.scans[i].readings[k].range);
      }
    }
    QFile f(recorded);
    QVERIFY(f.open(QIODevice::ReadOnly));
    QVERIFY(!f.readAll().endsWith("end\n"));
  }

  // One client at a time: a second recorder is refused and says it never connected.
  void secondClientIsRefused() {
    QTemporaryDir dir;
    Robot robot;
    QVERIFY2(robot.start({}), robot.error.constData());
    QProcess first;
    const QString firstLog = dir.filePath("first.sglog");
    first.start(kCli, {"record", "--connect", robot.address(), "--out", firstLog, "--duration", "6",
                       "--json"});
    QVERIFY(waitForScans(firstLog, 5, 10000));
    const Finished second = run({"record", "--connect", robot.address(), "--out",
                                 dir.filePath("second.sglog"), "--duration", "2", "--json"});
    const Finished firstDone = finish(first, 20000);
    QCOMPARE(robot.stop(), 0);
    QCOMPARE(second.code, 1);
    QVERIFY2(second.err.contains("never connected"), second.err.constData());
    QCOMPARE(second.json["written"].toBool(), false);
    QVERIFY(!QFile::exists(dir.filePath("second.sglog")));
    QVERIFY2(robot.out.contains("refused client"), robot.out.constData());
    QCOMPARE(firstDone.code, 0);
    QCOMPARE(firstDone.json["link"].toObject()["reconnects"].toInteger(), 0);
  }

  // The serial path for real (issue 50, item 2): socat bridges a pseudo-terminal to the virtual
  // robot's TCP port, so `record` opens a tty device as it would a USB serial adapter. socat is
  // then killed (the pty closes: the cable is unplugged) and started again on the same device name
  // a second later (plugged back in): the recording goes on by itself, and keeps every scan from
  // before the unplug.
  void recordsOverAPseudoTerminalThroughSocat() {
    const QString socat = QStandardPaths::findExecutable(QStringLiteral("socat"));
    QVERIFY2(!socat.isEmpty(), "socat is not installed (.ci/deps.sh installs it)");
    QTemporaryDir dir;
    const QString tty = dir.filePath("robot-tty");
    const QString recorded = dir.filePath("serial.sglog");
    Robot robot;
    QVERIFY2(robot.start({}), robot.error.constData());
    // rawer: no line discipline on the pty; wait-slave: connect to the robot once the device is
    // opened, as a serial adapter's robot is there only while the cable is in.
    const QStringList bridge{QStringLiteral("PTY,link=%1,rawer,wait-slave").arg(tty),
                             QStringLiteral("TCP:127.0.0.1:%1").arg(robot.port)};
    auto plugIn = [&](QProcess& cable) {
      cable.start(socat, bridge);
      QElapsedTimer t;
      t.start();
      while (!QFile::exists(tty) && t.elapsed() < 10000) QTest::qWait(20);
      return QFile::exists(tty);
    };
    QProcess cable1;
    QVERIFY(plugIn(cable1));
    QProcess record;
    record.start(kCli, {"record", "--connect", "serial://" + tty + "?baud=115200", "--out",
                        recorded, "--json"});
    QVERIFY(waitForScans(recorded, 20, 20000));
    cable1.terminate();  // unplugged: socat closes the pty and removes the device name
    QVERIFY(cable1.waitForFinished(10000));
    QTest::qWait(1000);
    const sg::Dataset atUnplug = load(recorded);
    QProcess cable2;
    QVERIFY(plugIn(cable2));
    // The recorder tries again after 0.5, 1, 2, 4 s: wait for twenty scans of the new connection.
    QVERIFY(waitForScans(recorded, static_cast<int>(atUnplug.scans.size()) + 20, 30000));
    ::kill(static_cast<pid_t>(record.processId()), SIGINT);
    const Finished rec = finish(record, 30000);
    cable2.terminate();
    cable2.waitForFinished(10000);
    QCOMPARE(robot.stop(), 0);
    QVERIFY2(rec.code == 0, rec.err.constData());
    const QJsonObject link = rec.json["link"].toObject();
    QCOMPARE(link["connections"].toInteger(), 2);
    QCOMPARE(link["lost_connections"].toInteger(), 1);
    QCOMPARE(link["bad_checksums"].toInteger(), 0);
    const sg::Dataset got = load(recorded);  // strict: it ends with 'end'
    QVERIFY(got.scans.size() >= atUnplug.scans.size() + 20);
    for (std::size_t i = 0; i < atUnplug.scans.size(); ++i)
      QCOMPARE(got.scans[i], atUnplug.scans[i]);
    QCOMPARE(static_cast<qint64>(got.readingCount()), rec.json["readings"].toInteger());
  }

  // A log that cannot be created ends the recording at the first connection: exit 1, naming it.
  void unwritableLog() {
    Robot robot;
    QVERIFY2(robot.start({}), robot.error.constData());
    const Finished rec = run({"record", "--connect", robot.address(), "--out",
                              "/nonexistent-dir/x.sglog", "--duration", "5"});
    QCOMPARE(robot.stop(), 0);
    QCOMPARE(rec.code, 1);
    QVERIFY2(rec.err.contains("cannot write '/nonexistent-dir/x.sglog'"), rec.err.constData());
  }

  void badArguments_data() {
    QTest::addColumn<QStringList>("args");
    QTest::addColumn<QString>("message");
    QTest::newRow("record without --connect")
        << QStringList{"record", "--out", "x.sglog"} << "--connect";
    QTest::newRow("record: bad address")
        << QStringList{"record", "--connect", "tcp://h:99999", "--out", "x.sglog"}
        << "the port must be a number from 1 to 65535";
    QTest::newRow("record: unknown robot")
        << QStringList{"record", "--connect", "tcp://h", "--out", "x.sglog", "--robot", "k2a"}
        << "--robot expects p3dx, amigobot";
    QTest::newRow("robot: unknown robot")
        << QStringList{"robot", "--world", kWorld, "--robot", "k2a"} << "--robot expects";
    QTest::newRow("robot: --teleop with --route")
        << QStringList{"robot", "--world", kWorld, "--teleop", "--route", "u-turn"} << "--teleop";
    QTest::newRow("robot: bad bind address")
        << QStringList{"robot", "--world", kWorld, "--bind", "localhost:1"} << "--bind";
    QTest::newRow("robot: missing world")
        << QStringList{"robot", "--world", "/no/such.json"} << "/no/such.json";
  }
  void badArguments() {
    QFETCH(QStringList, args);
    QFETCH(QString, message);
    const Finished f = run(args, 20000);
    QCOMPARE(f.code, 2);
    QVERIFY2(f.err.contains(message.toUtf8()), f.err.constData());
  }
};

QTEST_GUILESS_MAIN(TstLiveSession)
#include "tst_live_session.moc"
