// SPDX-License-Identifier: GPL-3.0-or-later
// `sonargrid-cli compare` (docs/cli.md, "compare"; issue 16 item 2) and the scoring flags it
// shares with `score`: --iop-weight, --filled-threshold (item 3), and the warning of a reference
// the map never saw (issue 17). Expected values come from `score --json` runs of the same maps,
// worked into means and standard deviations here, so they follow the bundled datasets when those
// are regenerated.

#include <QDir>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>
#include <QtTest>
#include <algorithm>
#include <cmath>

#include "cli_run.h"

using cli_test::describe;
using cli_test::Run;
using cli_test::runCli;

namespace {

const QString kDir = QStringLiteral(SONARGRID_DATASETS "/raschke-multi/");
const QString kLog1 = kDir + "stop-and-scan-01.sglog";
const QString kLog2 = kDir + "stop-and-scan-02.sglog";
const QString kWorld = kDir + "world.json";

// The metric keys of `score --json`, in its order (docs/cli.md, "score").
const QStringList kMetricKeys = {"iop_mm",
                                 "correlation_pct",
                                 "map_score_pct",
                                 "map_score_occupied_pct",
                                 "match_bits",
                                 "path_false_positive_pct",
                                 "path_false_negative_pct",
                                 "cross_entropy",
                                 "brier",
                                 "auc",
                                 "precision",
                                 "recall",
                                 "f1",
                                 "iou"};

QJsonObject jsonOf(const QByteArray& out) {
  return QJsonDocument::fromJson(out).object();
}

// `score --json` of one log and configuration ("model/rule").
QJsonObject scoreOf(const QString& log, const QString& model, const QString& rule,
                    const QStringList& extra = {}) {
  const QStringList args = QStringList{"score",   "--reference", kWorld,   "--log", log,
                                       "--model", model,         "--rule", rule,    "--json"} +
                           extra;
  const Run r = runCli(args);
  if (r.code != 0) qWarning("%s", describe(args, r).constData());
  return jsonOf(r.out);
}

QJsonObject compareOf(const QStringList& args) {
  const QStringList all = QStringList{"compare"} + args + QStringList{"--json"};
  const Run r = runCli(all);
  if (r.code != 0 || !r.err.isEmpty()) qWarning("%s", describe(all, r).constData());
  return jsonOf(r.out);
}

QJsonObject rowOf(const QJsonObject& compare, const QString& config) {
  for (const QJsonValue& v : compare["rows"].toArray()) {
    if (v.toObject()["config"].toString() == config) return v.toObject();
  }
  return {};
}

// Equal to rounding: mean and sd are worked here from the printed doubles.
bool near(double a, double b) {
  return std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(b));
}

}  // namespace

class TstCliCompare : public QObject {
  Q_OBJECT

 private slots:
  void meanAndSdOverTwoLogsAreThoseOfScore_data();
  void meanAndSdOverTwoLogsAreThoseOfScore();
  void commonCellsAreTheSameForEveryRow();
  void oneConfigurationOnCommonCellsIsScore();
  void sameBytesAtAnyThreadCount();
  void csvAndMarkdownFiles();
  void badFlags_data();
  void badFlags();
  void iopWeightOfScore_data();
  void iopWeightOfScore();
  void scoreWarnsOfAReferenceNeverObserved();
};

void TstCliCompare::meanAndSdOverTwoLogsAreThoseOfScore_data() {
  QTest::addColumn<QString>("model");
  QTest::addColumn<QString>("rule");
  QTest::newRow("hpf/addition") << "hpf"
                                << "addition";
  QTest::newRow("konolige/log") << "konolige"
                                << "log";
  QTest::newRow("himm/himm") << "himm"
                             << "himm";
  // The forward model learned by EM, with EM as its rule (docs/forward-model.md).
  QTest::newRow("forward-em/em") << "forward-em"
                                 << "em";
}

void TstCliCompare::meanAndSdOverTwoLogsAreThoseOfScore() {
  // --cells own scores each map on its own cells, as `score` does: every metric's mean is
  // (a + b) / 2 and its sample sd |a − b| / √2 (n − 1 = 1) of the two `score --json` values.
  QFETCH(QString, model);
  QFETCH(QString, rule);
  const QString config = model + "/" + rule;
  const QJsonObject c =
      compareOf({"--log", kLog1, "--log", kLog2, "--reference", kWorld, "--config", "hpf/addition",
                 "--config", "konolige/log", "--config", "himm/himm", "--config", "forward-em/em",
                 "--cells", "own"});
  QCOMPARE(c["cells"].toString(), QString("own"));
  QCOMPARE(c["rows"].toArray().size(), 4);
  const QJsonObject row = rowOf(c, config);
  QVERIFY2(!row.isEmpty(), qPrintable(config));
  const QJsonObject a = scoreOf(kLog1, model, rule), b = scoreOf(kLog2, model, rule);
  QVERIFY(!a.isEmpty() && !b.isEmpty());
  QCOMPARE(row["cells_scored"].toInteger(),
           a["cells_evaluated"].toInteger() + b["cells_evaluated"].toInteger());
  QCOMPARE(row["cells_scored_per_log"].toArray(),
           (QJsonArray{a["cells_evaluated"], b["cells_evaluated"]}));
  const QJsonObject metrics = row["metrics"].toObject();
  QCOMPARE(metrics.keys().size(), kMetricKeys.size());
  for (const QString& key : kMetricKeys) {
    const QJsonObject m = metrics[key].toObject();
    QVERIFY2(m.contains("mean") && m.contains("sd"), qPrintable(key));
    if (a[key].isNull() || b[key].isNull()) continue;  // a metric undefined in a run
    const double x = a[key].toDouble(), y = b[key].toDouble();
    QVERIFY2(near(m["mean"].toDouble(), (x + y) / 2),
             qPrintable(QString("%1 %2: mean %3, runs %4 and %5")
                            .arg(config, key)
                            .arg(m["mean"].toDouble(), 0, 'g', 17)
                            .arg(x, 0, 'g', 17)
                            .arg(y, 0, 'g', 17)));
    QVERIFY2(near(m["sd"].toDouble(), std::abs(x - y) / std::sqrt(2.0)),
             qPrintable(QString("%1 %2: sd").arg(config, key)));
    QCOMPARE(m["n"].toInt(), 2);
  }
  // The parameters are the defaults `score` used (the whole set of the model and the rule).
  QVERIFY(!row["params"].toObject().isEmpty());
  QCOMPARE(row["model"].toString(), model);
  QCOMPARE(row["rule"].toString(), rule);
}

void TstCliCompare::commonCellsAreTheSameForEveryRow() {
  // HPF reaches 10 m, Konolige 2.5 m: on their own cells they are scored on different counts, on
  // the common cells (the default) on one count, no larger than either own count.
  const QStringList args{"--log", kLog1,      "--log",        kLog2,      "--reference",
                         kWorld,  "--config", "hpf/addition", "--config", "konolige/log"};
  const QJsonObject common = compareOf(args);
  const QJsonObject own = compareOf(args + QStringList{"--cells", "own"});
  QCOMPARE(common["cells"].toString(), QString("common"));
  const QJsonArray rows = common["rows"].toArray();
  QCOMPARE(rows.size(), 2);
  const qint64 n = rows[0].toObject()["cells_scored"].toInteger();
  QVERIFY(n > 0);
  QCOMPARE(rows[1].toObject()["cells_scored"].toInteger(), n);
  QCOMPARE(rows[1].toObject()["cells_scored_per_log"], rows[0].toObject()["cells_scored_per_log"]);
  const qint64 hpf = rowOf(own, "hpf/addition")["cells_scored"].toInteger();
  const qint64 konolige = rowOf(own, "konolige/log")["cells_scored"].toInteger();
  QVERIFY2(hpf != konolige, "own cells should differ between the two reaches");
  QVERIFY(n <= std::min(hpf, konolige));
}

void TstCliCompare::oneConfigurationOnCommonCellsIsScore() {
  // With one configuration the common cells are its own: compare of one log equals score.
  const QJsonObject c = compareOf({"--log", kLog1, "--reference", kWorld, "--config",
                                   "konolige/bayes:attenuation_slope=0.5,false_rate=0.1"});
  const QJsonObject s = scoreOf(kLog1, "konolige", "bayes",
                                {"--set", "attenuation_slope=0.5", "--set", "false_rate=0.1"});
  const QJsonObject row = rowOf(c, "konolige/bayes:attenuation_slope=0.5,false_rate=0.1");
  QCOMPARE(row["cells_scored"].toInteger(), s["cells_evaluated"].toInteger());
  QCOMPARE(row["params"].toObject()["attenuation_slope"].toDouble(), 0.5);
  QCOMPARE(row["params"].toObject()["false_rate"].toDouble(), 0.1);
  for (const QString& key : kMetricKeys) {
    const QJsonObject m = row["metrics"].toObject()[key].toObject();
    QCOMPARE(m["mean"], s[key]);  // the very double
    QVERIFY(m["sd"].isNull());    // one log: no standard deviation
  }
}

void TstCliCompare::sameBytesAtAnyThreadCount() {
  const QStringList args{"compare",      "--log",    kLog1,       "--log",     kLog2,
                         "--reference",  kWorld,     "--config",  "hpf/bayes", "--config",
                         "konolige/log", "--config", "himm/himm", "--json"};
  const Run one = runCli(args + QStringList{"--threads", "1"});
  const Run two = runCli(args + QStringList{"--threads", "2"});
  const Run three = runCli(args + QStringList{"--threads", "3"});
  QVERIFY2(one.code == 0, describe(args, one));
  QCOMPARE(two.out, one.out);
  QCOMPARE(three.out, one.out);
}

void TstCliCompare::csvAndMarkdownFiles() {
  QTemporaryDir dir;
  QVERIFY(dir.isValid());
  const QString csv = dir.filePath("t.csv"), md = dir.filePath("t.md");
  const QStringList args{"compare",         "--log",        kLog1,      "--reference", kWorld,
                         "--config",        "hpf/addition", "--config", "himm/himm",   "--metrics",
                         "iop,correlation", "--csv",        csv,        "--markdown",  md};
  const Run r = runCli(args);
  QVERIFY2(r.code == 0, describe(args, r));
  QFile c(csv), m(md);
  QVERIFY(c.open(QIODevice::ReadOnly) && m.open(QIODevice::ReadOnly));
  const QList<QByteArray> lines = c.readAll().split('\n');
  // Header, two rows, the empty string after the last newline.
  QCOMPARE(lines.size(), 4);
  QCOMPARE(lines[0], QByteArray("config,params,cells_scored,iop_mm_mean,iop_mm_sd,"
                                "correlation_pct_mean,correlation_pct_sd"));
  QVERIFY(lines[1].startsWith("hpf/addition,"));
  QVERIFY(lines[2].startsWith("himm/himm,"));
  const QByteArray markdown = m.readAll();
  QVERIFY(markdown.contains("| config | cells scored | IOP (mm) | correlation (%) |"));
  QVERIFY(markdown.contains("| hpf/addition |"));
  QCOMPARE(r.out, markdown);  // without --json the table is printed as well
  // An output into a missing directory: exit 1, nothing written.
  const QStringList bad{"compare",     "--log", kLog1,
                        "--reference", kWorld,  "--config",
                        "himm/himm",   "--csv", dir.filePath("no/such/t.csv")};
  QCOMPARE(runCli(bad).code, 1);
}

void TstCliCompare::badFlags_data() {
  QTest::addColumn<QStringList>("args");
  QTest::addColumn<QString>("named");
  const QStringList base{"--log", kLog1, "--reference", kWorld};
  QTest::newRow("no config") << base << "--config";
  QTest::newRow("no log") << QStringList{"--reference", kWorld, "--config", "himm/himm"} << "--log";
  QTest::newRow("no reference") << QStringList{"--log", kLog1, "--config", "himm/himm"}
                                << "--reference";
  QTest::newRow("cells") << base + QStringList{"--config", "himm/himm", "--cells", "both"}
                         << "--cells";
  QTest::newRow("no rule") << base + QStringList{"--config", "hpf"} << "--config 'hpf'";
  QTest::newRow("unknown model") << base + QStringList{"--config", "sonar/bayes"}
                                 << "--config 'sonar/bayes'";
  QTest::newRow("unknown rule") << base + QStringList{"--config", "hpf/votes"}
                                << "--config 'hpf/votes'";
  QTest::newRow("incompatible") << base + QStringList{"--config", "hpf/himm"}
                                << "--config 'hpf/himm'";
  QTest::newRow("forward model with a rule")
      << base + QStringList{"--config", "forward-em/bayes"} << "--config 'forward-em/bayes'";
  QTest::newRow("EM with an inverse model")
      << base + QStringList{"--config", "hpf/em"} << "--config 'hpf/em'";
  QTest::newRow("unknown parameter")
      << base + QStringList{"--config", "hpf/bayes:bogus=1"} << "--config 'hpf/bayes:bogus=1'";
  QTest::newRow("out of range") << base + QStringList{"--config", "hpf/bayes:epsilon=2"}
                                << "--config 'hpf/bayes:epsilon=2'";
  QTest::newRow("no value") << base + QStringList{"--config", "hpf/bayes:epsilon"}
                            << "--config 'hpf/bayes:epsilon'";
  QTest::newRow("twice") << base + QStringList{"--config", "himm/himm", "--config", "himm/himm"}
                         << "--config 'himm/himm'";
  QTest::newRow("weight") << base + QStringList{"--config", "himm/himm", "--iop-weight", "cv"}
                          << "--iop-weight";
  QTest::newRow("threshold") << base +
                                    QStringList{"--config", "himm/himm", "--filled-threshold", "16"}
                             << "--filled-threshold";
  QTest::newRow("pose") << base + QStringList{"--config", "himm/himm", "--pose", "gps"} << "--pose";
  QTest::newRow("cell") << base + QStringList{"--config", "himm/himm", "--cell", "0"} << "--cell";
  QTest::newRow("unknown flag") << base + QStringList{"--config", "himm/himm", "--model", "hpf"}
                                << "--model";
  QTest::newRow("threads") << base + QStringList{"--config", "himm/himm", "--threads", "x"}
                           << "--threads";
}

void TstCliCompare::badFlags() {
  QFETCH(QStringList, args);
  QFETCH(QString, named);
  const QStringList all = QStringList{"compare"} + args;
  const Run r = runCli(all);
  QVERIFY2(r.code == 2, describe(all, r));
  QVERIFY(r.out.isEmpty());
  QVERIFY2(r.err.startsWith("sonargrid-cli: "), describe(all, r));
  QVERIFY2(r.err.contains(named.toUtf8()), describe(all, r));
}

void TstCliCompare::iopWeightOfScore_data() {
  QTest::addColumn<QString>("model");
  QTest::addColumn<QString>("rule");
  QTest::addColumn<bool>("same");
  // HIMM's evidence is its CV, which is its level: the weights agree. Addition's filled cells
  // have level round(7.5 (1 + Occ)) ≥ 8 but evidence 15·Occ, which is smaller for every Occ < 1.
  QTest::newRow("himm") << "himm"
                        << "himm" << true;
  QTest::newRow("hpf/addition") << "hpf"
                                << "addition" << false;
}

void TstCliCompare::iopWeightOfScore() {
  QFETCH(QString, model);
  QFETCH(QString, rule);
  QFETCH(bool, same);
  const QJsonObject byDefault = scoreOf(kLog1, model, rule, {"--metrics", "iop"});
  const QJsonObject evidence =
      scoreOf(kLog1, model, rule, {"--metrics", "iop", "--iop-weight", "evidence"});
  const QJsonObject level =
      scoreOf(kLog1, model, rule, {"--metrics", "iop", "--iop-weight", "level"});
  QVERIFY(evidence["iop_mm"].isDouble() && level["iop_mm"].isDouble());
  QCOMPARE(byDefault["iop_mm"], evidence["iop_mm"]);  // the default is evidence
  QCOMPARE(evidence["iop_mm"] == level["iop_mm"], same);
  // The highest threshold keeps only cells of full certainty; a cell of weight 15 always counts,
  // so the IOP is defined or not, never an error.
  const QJsonObject strict =
      scoreOf(kLog1, model, rule, {"--metrics", "iop", "--filled-threshold", "15"});
  QVERIFY(strict.contains("iop_mm"));
}

void TstCliCompare::scoreWarnsOfAReferenceNeverObserved() {
  // A 10 x 10 ROS map of 10 cm cells that observed only its bottom row (free, pixel 254), the
  // rest unknown (205); a wall at x = 0.55 m from y = 0.35 to 0.85 m crosses the grid but no
  // observed cell. The numbers come with a warning on stderr and in the JSON.
  QTemporaryDir dir;
  QVERIFY(dir.isValid());
  QByteArray pgm = "P5\n10 10\n255\n";
  for (int row = 0; row < 10; ++row) pgm += QByteArray(10, row == 9 ? char(254) : char(205));
  QFile image(dir.filePath("m.pgm"));
  QVERIFY(image.open(QIODevice::WriteOnly) && image.write(pgm) == pgm.size());
  image.close();
  QFile yaml(dir.filePath("m.yaml"));
  QVERIFY(yaml.open(QIODevice::WriteOnly));
  yaml.write(
      "image: m.pgm\nresolution: 0.1\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
      "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  yaml.close();
  QFile ref(dir.filePath("far.json"));
  QVERIFY(ref.open(QIODevice::WriteOnly));
  ref.write(R"({"format": "sonargrid-reference", "version": 1, "units": "m", "objects": [
      {"name": "wall", "closed": false, "corners": [[0.55, 0.35], [0.55, 0.85]]}]})");
  ref.close();
  const QStringList args{"score", "--reference",          dir.filePath("far.json"),
                         "--map", dir.filePath("m.yaml"), "--json"};
  const Run r = runCli(args);
  QVERIFY2(r.code == 0, describe(args, r));
  QVERIFY2(r.err.contains("warning") && r.err.contains("none of the 6 cells"), describe(args, r));
  const QJsonArray warnings = jsonOf(r.out)["warnings"].toArray();
  QCOMPARE(warnings.size(), 1);
  QVERIFY(warnings[0].toString().contains("none of the 6 cells"));
  // The room scored against its own reference has no warning, and no "warnings" key.
  const QStringList room{"score",
                         "--reference",
                         SONARGRID_DATASETS "/room/room.json",
                         "--log",
                         SONARGRID_DATASETS "/room/room.sglog",
                         "--model",
                         "himm",
                         "--rule",
                         "himm",
                         "--metrics",
                         "iop",
                         "--json"};
  const Run ok = runCli(room);
  QVERIFY2(ok.code == 0 && ok.err.isEmpty(), describe(room, ok));
  QVERIFY(!jsonOf(ok.out).contains("warnings"));
}

QTEST_GUILESS_MAIN(TstCliCompare)
#include "tst_cli_compare.moc"
