// `sonargrid-cli reproduce` on tiny datasets laid out like the bundled ones (docs/cli.md,
// docs/reproduction.md): every file is written and every summary key is there. The datasets are
// generated here with the ray-cast simulator, so the test needs nothing from datasets/.

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QTemporaryDir>
#include <QtTest>
#include <fstream>

#include "sonargrid/io/sglog.h"
#include "sonargrid/sim/ray_sonar.h"

using namespace sg;

namespace {

struct Box {
  const char* name;
  std::vector<Position> corners;
};

void writeWorld(const QString& path, const std::vector<Box>& boxes) {
  std::ofstream out(path.toStdString());
  out << R"({"format": "sonargrid-reference", "version": 1, "units": "m", "objects": [)";
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    out << (i ? "," : "") << R"({"name": ")" << boxes[i].name
        << R"(", "closed": true, "corners": [)";
    for (std::size_t k = 0; k < boxes[i].corners.size(); ++k)
      out << (k ? "," : "") << '[' << boxes[i].corners[k].x() << ',' << boxes[i].corners[k].y()
          << ']';
    out << "]}";
  }
  out << "]}\n";
}

std::vector<Segment> segmentsOf(const std::vector<Box>& boxes) {
  std::vector<Segment> world;
  for (const Box& b : boxes) {
    const std::vector<Segment> s = polygonSegments(b.corners, true);
    world.insert(world.end(), s.begin(), s.end());
  }
  return world;
}

// `count` poses along y = 0.8 from x = 0.6, 0.25 m apart, facing +x.
std::vector<TimedPose> route(int count, double step) {
  std::vector<TimedPose> out;
  for (int k = 0; k < count; ++k) out.push_back({0.2 * k, Pose2D(0.6 + step * k, 0.8, 0.0)});
  return out;
}

void writeLog(const QString& path, const std::vector<Box>& boxes,
              const std::vector<TimedPose>& poses, const SonarRing& ring, std::uint64_t seed) {
  SonarPhysics physics;
  physics.seed = seed;
  writeSglog(simulateRoute(segmentsOf(boxes), poses, ring, physics, "tiny"), path.toStdString());
}

QString two(int run) {
  return QString("%1").arg(run, 2, 10, QChar('0'));
}

}  // namespace

class TestReproduce : public QObject {
  Q_OBJECT

  QTemporaryDir data_;
  QTemporaryDir out_;

  struct Result {
    int status = -1;
    QByteArray out, err;
  };
  Result run(const QStringList& args) {
    QProcess p;
    p.start(SONARGRID_CLI, args);
    p.waitForFinished(240000);
    return {p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1, p.readAllStandardOutput(),
            p.readAllStandardError()};
  }
  QString file(const QString& rel) const { return out_.filePath(rel); }

 private slots:
  void initTestCase() {
    QVERIFY(data_.isValid() && out_.isValid());
    const std::vector<Box> room{{"walls", {{0, 0}, {3, 0}, {3, 1.6}, {0, 1.6}}}};
    std::vector<Box> multi = room;
    multi.push_back({"box", {{2.2, 0.3}, {2.5, 0.3}, {2.5, 0.5}, {2.2, 0.5}}});
    multi.push_back({"pole", {{1.5, 1.3}, {1.55, 1.3}, {1.55, 1.35}, {1.5, 1.35}}});
    std::vector<Box> single = room;
    single.push_back({"box", {{2.2, 0.3}, {2.5, 0.3}, {2.5, 0.5}, {2.2, 0.5}}});
    const QDir d(data_.path());
    for (const auto& [folder, world] :
         {std::pair{"raschke-multi", multi}, std::pair{"raschke-single", single}}) {
      QVERIFY(d.mkpath(folder));
      writeWorld(d.filePath(QString(folder) + "/world.json"), world);
      for (int r = 1; r <= 10; ++r) {
        writeLog(d.filePath(QString(folder) + "/in-motion-" + two(r) + ".sglog"), world,
                 route(6, 0.2), SonarRing::k2a(), static_cast<std::uint64_t>(r));
        writeLog(d.filePath(QString(folder) + "/stop-and-scan-" + two(r) + ".sglog"), world,
                 route(4, 0.4), SonarRing::k2a(), static_cast<std::uint64_t>(100 + r));
      }
    }
    QVERIFY(d.mkpath("arafat-room"));
    writeWorld(d.filePath("arafat-room/world.json"), multi);
    writeLog(d.filePath("arafat-room/run-1.sglog"), multi, route(8, 0.2), SonarRing::amigobot(), 1);
    writeLog(d.filePath("arafat-room/run-2.sglog"), multi, route(8, 0.2), SonarRing::amigobot(), 2);
  }

  // The summary keys of issue 4 item 6; the files each paper writes (docs/cli.md).
  void raschke1990() {
    const Result r = run(
        {"reproduce", "raschke1990", "--out", out_.path(), "--datasets", data_.path(), "--json"});
    QVERIFY2(r.status == 0, r.err.constData());
    QVERIFY(r.err.isEmpty());
    const QJsonObject j = QJsonDocument::fromJson(r.out).object();
    QCOMPARE(j.keys(), QStringList{"raschke1990"});
    for (const QString env : {"multi", "single"}) {
      for (const QString m : {"himm", "hpf"}) {
        const QJsonObject o = j["raschke1990"][env][m].toObject();
        QVERIFY2(o["iop_mean_mm"].isDouble(), qPrintable(env + "/" + m));
        QVERIFY(o["iop_sd_mm"].isDouble());
        QVERIFY(o["iop_mean_mm"].toDouble() >= 0.0);
      }
    }
    for (const QString f : {"table1.md", "table1.csv", "table1-runs.csv", "fig4-multi-hpf.png",
                            "fig4-multi-himm.png", "fig4-single-hpf.png", "fig4-single-himm.png"})
      QVERIFY2(QFileInfo(file("raschke1990/" + f)).size() > 0, qPrintable(f));
    // One header and 2 environments x 2 methods x 10 runs.
    QFile runs(file("raschke1990/table1-runs.csv"));
    QVERIFY(runs.open(QIODevice::ReadOnly));
    QCOMPARE(runs.readAll().count('\n'), 41);
  }

  void osullivan() {
    const Result r =
        run({"reproduce", "osullivan", "--out", out_.path(), "--datasets", data_.path(), "--json"});
    QVERIFY2(r.status == 0, r.err.constData());
    const QJsonObject j = QJsonDocument::fromJson(r.out).object()["osullivan"].toObject();
    const QStringList keys{"correlation_pct", "map_score_pct", "map_score_occupied_pct",
                           "path_false_positive_pct"};
    for (const QString v : {"2dg", "mtm"}) {
      for (const QString& k : keys) QVERIFY2(j["models"][v][k].isDouble(), qPrintable(v + k));
    }
    for (const QString v : {"simple", "bayes", "log"}) {
      for (const QString& k : keys) QVERIFY2(j["rules"][v][k].isDouble(), qPrintable(v + k));
    }
    // The log row of the rule table is the multiple-target row of the model table: one map.
    QCOMPARE(j["rules"]["log"]["correlation_pct"], j["models"]["mtm"]["correlation_pct"]);
    for (const QString f :
         {"models.md", "models.csv", "rules.md", "rules.csv", "runs.csv", "hpf-log.png",
          "konolige-log.png", "konolige-addition.png", "konolige-bayes.png"})
      QVERIFY2(QFileInfo(file("osullivan/" + f)).size() > 0, qPrintable(f));
  }

  void arafat() {
    const Result r = run({"reproduce", "arafat", "--out", out_.path(), "--datasets", data_.path(),
                          "--json", "--sets", "20", "--threads", "2"});
    QVERIFY2(r.status == 0, r.err.constData());
    QVERIFY(r.err.isEmpty());
    const QJsonObject j = QJsonDocument::fromJson(r.out).object()["arafat"].toObject();
    QCOMPARE(j["sweep_sets"].toInt(), 20);
    const QJsonArray counts = j["histogram"]["counts"].toArray();
    QCOMPARE(counts.size(), 14);
    int total = 0;
    for (const auto& c : counts) total += c.toInt();
    QCOMPARE(total, 20);  // every set of the tiny room has a VSDNS
    for (const QString k : {"optimal_histogram", "optimal_min", "optimal_mean",
                            "optimal_derivative_noise", "optimal_two_run"}) {
      for (const QString p : {"p1", "p2", "p3", "two_p3", "p4", "p5"})
        QVERIFY2(j[k][p].isDouble(), qPrintable(k + "." + p));
    }
    // The minimum's P1 is tied to its P4 (Table 1, footnote *).
    QCOMPARE(j["optimal_min"]["p1"].toDouble(), 1.0 - j["optimal_min"]["p4"].toDouble());
    for (const QString f :
         {"fig6.md", "fig6.csv", "fig6-standard.png", "fig6-parameterized.png", "sweep.csv",
          "histogram.md", "histogram.csv", "lowest-bin.md", "optima.md", "optima.csv",
          "optimal-histogram.png", "optimal-min.png", "optimal-mean.png",
          "optimal-derivative-noise.png", "optimal-two-run.png"})
      QVERIFY2(QFileInfo(file("arafat/" + f)).size() > 0, qPrintable(f));
    QFile sweep(file("arafat/sweep.csv"));
    QVERIFY(sweep.open(QIODevice::ReadOnly));
    QCOMPARE(sweep.readAll().count('\n'), 21);
  }

  void errors_data() {
    QTest::addColumn<QStringList>("args");
    QTest::addColumn<QString>("named");
    QTest::newRow("no paper") << QStringList{"--out", "x"} << "raschke1990";
    QTest::newRow("unknown paper") << QStringList{"elfes", "--out", "x"} << "elfes";
    QTest::newRow("two papers") << QStringList{"arafat", "osullivan", "--out", "x"} << "osullivan";
    QTest::newRow("no --out") << QStringList{"arafat"} << "--out";
    QTest::newRow("--sets elsewhere")
        << QStringList{"osullivan", "--out", "x", "--sets", "3"} << "--sets";
    QTest::newRow("--sets too big")
        << QStringList{"arafat", "--out", "x", "--sets", "1441"} << "--sets";
  }
  // Bad arguments: exit status 2, one line naming the problem.
  void errors() {
    QFETCH(QStringList, args);
    QFETCH(QString, named);
    const Result r = run(QStringList{"reproduce"} + args + QStringList{"--datasets", data_.path()});
    QCOMPARE(r.status, 2);
    QVERIFY(r.out.isEmpty());
    QVERIFY2(r.err.contains(named.toUtf8()), r.err.constData());
  }

  // A missing dataset file is input the user must fix: status 2, the file named.
  void missingDataset() {
    QTemporaryDir empty;
    const Result r =
        run({"reproduce", "arafat", "--out", out_.path(), "--datasets", empty.path(), "--json"});
    QCOMPARE(r.status, 2);
    QVERIFY2(r.err.contains("arafat-room/world.json"), r.err.constData());
  }
};

QTEST_GUILESS_MAIN(TestReproduce)
#include "tst_reproduce.moc"
