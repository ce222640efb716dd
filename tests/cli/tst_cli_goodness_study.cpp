// SPDX-License-Identifier: GPL-3.0-or-later
// `goodness-study` (issue 14 item 4; docs/goodness-study.md). A 12-set grid on the bundled room
// log: every ρ of the table equals Spearman's ρ computed here, independently of the core, from the
// rows `sweep --csv` writes for the same sets; the study's own --csv is that sweep CSV byte for
// byte; the output is the same at 1 and 2 threads; bad flags exit 2 naming the flag. A 4-set grid
// on arafat-room's two runs checks the two-run agreement against its CSV columns.

#include <QByteArray>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QTemporaryDir>
#include <QtTest>
#include <cmath>
#include <optional>
#include <vector>

#include "cli_run.h"

namespace {

const QString kRoom = QStringLiteral(SONARGRID_DATASETS "/room/room.sglog");
const QString kRoomWorld = QStringLiteral(SONARGRID_DATASETS "/room/room.json");
const QString kRun1 = QStringLiteral(SONARGRID_DATASETS "/arafat-room/run-1.sglog");
const QString kRun2 = QStringLiteral(SONARGRID_DATASETS "/arafat-room/run-2.sglog");
const QString kArafatWorld = QStringLiteral(SONARGRID_DATASETS "/arafat-room/world.json");

using cli_test::describe;
using cli_test::kCli;
using cli_test::Run;

// A 12-set study on a loaded machine: up to 240 s (twice cli_run.h's default).
Run runCli(const QStringList& args) {
  return cli_test::runProgram(kCli, args, {}, {}, 240000);
}

QByteArray readFile(const QString& path) {
  QFile f(path);
  return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}

// The grid: p5 ∈ {6, 15, 25} outer, p2 ∈ {0.05, 0.1, 0.15, 0.2} inner, 12 sets of the room's
// parameterized × bayes-recursive map.
QStringList roomMapFlags() {
  return {"--log",   kRoom,           "--reference", kRoomWorld,
          "--model", "parameterized", "--rule",      "bayes-recursive",
          "--grid",  "p5=6,15,25",    "--grid",      "p2=0.05:0.05:0.2"};
}

QStringList roomStudy() {
  return QStringList{"goodness-study"} << roomMapFlags() << "--bootstrap"
                                       << "200"
                                       << "--seed"
                                       << "5";
}

// A sweep CSV's data rows by column name; an empty field is an undefined value.
struct Csv {
  QList<QByteArray> columns;
  QList<QList<QByteArray>> rows;
  std::optional<double> value(int row, const QString& column) const {
    const int c = static_cast<int>(columns.indexOf(column.toUtf8()));
    if (c < 0 || rows[row][c].isEmpty()) return std::nullopt;
    return rows[row][c].toDouble();
  }
};

Csv parseCsv(const QByteArray& bytes) {
  Csv csv;
  bool header = true;
  for (const QByteArray& line : bytes.split('\n')) {
    if (line.isEmpty() || line.startsWith('#')) continue;
    if (header) {
      header = false;
      csv.columns = line.split(',');
      continue;
    }
    csv.rows.append(line.split(','));
  }
  return csv;
}

// Spearman's ρ written out here apart from the core: the average rank of a value is the number of
// smaller values plus (1 + the number of equal ones) / 2 (ranks 1-based), then Pearson's r of the
// ranks. Empty when either side is constant.
std::optional<double> spearmanByCounting(const std::vector<double>& x,
                                         const std::vector<double>& y) {
  auto ranks = [](const std::vector<double>& v) {
    std::vector<double> r;
    for (double a : v) {
      int less = 0, equal = 0;
      for (double b : v) {
        less += b < a;
        equal += b == a;
      }
      r.push_back(less + (1.0 + equal) / 2.0);
    }
    return r;
  };
  const std::vector<double> rx = ranks(x), ry = ranks(y);
  const double n = static_cast<double>(x.size());
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    mx += rx[i] / n;
    my += ry[i] / n;
  }
  double sxy = 0, sxx = 0, syy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += (rx[i] - mx) * (ry[i] - my);
    sxx += (rx[i] - mx) * (rx[i] - mx);
    syy += (ry[i] - my) * (ry[i] - my);
  }
  if (sxx == 0 || syy == 0) return std::nullopt;
  return sxy / std::sqrt(sxx * syy);
}

// The free measure's value of a CSV row, as docs/goodness-study.md defines it.
std::optional<double> freeValue(const Csv& csv, int row, const QString& free) {
  if (free == "entropy") return csv.value(row, "map_entropy");
  if (free == "two_run_agreement") {
    const auto p = csv.value(row, "two_run_positive");
    const auto n = csv.value(row, "two_run_negative");
    if (!p || !n || *p + *n <= 0) return std::nullopt;
    return *p / (*p + *n);
  }
  return csv.value(row, free);
}

// Every row of the study's table against ρ computed from the CSV.
void compareTable(const QJsonObject& study, const Csv& csv, int expectedRows) {
  const QJsonArray table = study.value("table").toArray();
  QCOMPARE(table.size(), expectedRows);
  for (const QJsonValue& v : table) {
    const QJsonObject row = v.toObject();
    const QString free = row.value("free").toString();
    const QString reference = row.value("reference").toString();
    std::vector<double> x, y;
    for (int i = 0; i < csv.rows.size(); ++i) {
      const auto a = freeValue(csv, i, free);
      const auto b = csv.value(i, reference);
      if (a && b) {
        x.push_back(*a);
        y.push_back(*b);
      }
    }
    const QByteArray what = (free + " × " + reference).toUtf8();
    QCOMPARE(row.value("n").toInt(), static_cast<int>(x.size()));
    const std::optional<double> rho = spearmanByCounting(x, y);
    QVERIFY2(rho.has_value() == !row.value("spearman").isNull(), what);
    if (!rho) continue;
    // The CSV holds the shortest text that reads back to each double, so the ranks, and ρ, are
    // those of the study's own values; the sums run in another order, hence the tolerance.
    QVERIFY2(std::abs(row.value("spearman").toDouble() - *rho) < 1e-12,
             what + ": " + QByteArray::number(row.value("spearman").toDouble(), 'g', 17) + " vs " +
                 QByteArray::number(*rho, 'g', 17));
    const QJsonArray ci = row.value("ci95").toArray();
    QCOMPARE(ci.size(), 2);
    QVERIFY2(
        -1.0 <= ci[0].toDouble() && ci[0].toDouble() <= ci[1].toDouble() && ci[1].toDouble() <= 1.0,
        what);
    // The oriented ρ: signed by the measures' better directions (docs/goodness-study.md: lower
    // VSDNS, derivative noise, map entropy and IOP are better; higher agreement, correlation and
    // AUC). A free measure the doc does not name fails.
    const QStringList lowerFree{"vsdns", "derivative_noise", "derivative_noise_mean", "entropy"};
    QVERIFY2(lowerFree.contains(free) || free == "two_run_agreement", what);
    const bool freeLower = lowerFree.contains(free);
    const bool referenceLower = reference == "iop_mm";
    QCOMPARE(row.value("oriented").toDouble(),
             (freeLower == referenceLower ? 1 : -1) * row.value("spearman").toDouble());
  }
}

}  // namespace

class TstCliGoodnessStudy : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase();
  void rhoEqualsSpearmanOfSweepRows();
  void csvIsTheSweepCsv();
  void sameOutputAnyThreadCount();
  void textTable();
  void twoRunAgreement();
  void badFlagsExit2_data();
  void badFlagsExit2();

 private:
  QString path(const QString& name) const { return tmp_.filePath(name); }
  QTemporaryDir tmp_;
  QByteArray studyJson_;  // the room study at 1 thread
  QByteArray sweepCsv_;   // `sweep --csv` of the same sets
};

void TstCliGoodnessStudy::initTestCase() {
  QVERIFY2(QFile::exists(kCli), qPrintable(kCli));
  QVERIFY(tmp_.isValid());
  const QStringList study = roomStudy() << "--threads"
                                        << "1"
                                        << "--csv" << path("study.csv") << "--json";
  const Run r = runCli(study);
  QVERIFY2(r.finished && r.code == 0, describe(study, r));
  studyJson_ = r.out;
  const QStringList sweep = QStringList{"sweep"} << roomMapFlags() << "--metric"
                                                 << "vsdns,derivative,entropy,iop,correlation,auc"
                                                 << "--csv" << path("sweep.csv");
  const Run s = runCli(sweep);
  QVERIFY2(s.finished && s.code == 0, describe(sweep, s));
  sweepCsv_ = readFile(path("sweep.csv"));
  QCOMPARE(parseCsv(sweepCsv_).rows.size(), 12);
}

void TstCliGoodnessStudy::rhoEqualsSpearmanOfSweepRows() {
  const QJsonObject study = QJsonDocument::fromJson(studyJson_).object();
  QCOMPARE(study.value("sets").toInt(), 12);
  QCOMPARE(study.value("bootstrap").toInt(), 200);
  QCOMPARE(study.value("seed").toInt(), 5);
  // No second log: VSDNS, derivative noise and its mean, map entropy, each against IOP,
  // correlation and AUC.
  compareTable(study, parseCsv(sweepCsv_), 12);
  QStringList pairs;
  for (const QJsonValue& v : study.value("table").toArray())
    pairs << v.toObject().value("free").toString() + "/" +
                 v.toObject().value("reference").toString();
  QCOMPARE(pairs, (QStringList{"vsdns/iop_mm", "vsdns/correlation_pct", "vsdns/auc",
                               "derivative_noise/iop_mm", "derivative_noise/correlation_pct",
                               "derivative_noise/auc", "derivative_noise_mean/iop_mm",
                               "derivative_noise_mean/correlation_pct", "derivative_noise_mean/auc",
                               "entropy/iop_mm", "entropy/correlation_pct", "entropy/auc"}));
}

void TstCliGoodnessStudy::csvIsTheSweepCsv() {
  QVERIFY2(readFile(path("study.csv")) == sweepCsv_,
           "goodness-study --csv differs from sweep --csv of the same sets");
}

void TstCliGoodnessStudy::sameOutputAnyThreadCount() {
  const QStringList args = roomStudy() << "--threads"
                                       << "2"
                                       << "--json";
  const Run r = runCli(args);
  QVERIFY2(r.finished && r.code == 0, describe(args, r));
  QCOMPARE(r.out, studyJson_);
}

void TstCliGoodnessStudy::textTable() {
  const QStringList args = QStringList{"goodness-study"} << roomMapFlags() << "--bootstrap"
                                                         << "0"
                                                         << "--seed"
                                                         << "5";
  const Run r = runCli(args);
  QVERIFY2(r.finished && r.code == 0, describe(args, r));
  QVERIFY2(r.out.startsWith("goodness-study: 12 sets, 0 bootstrap replicates, seed 5"), r.out);
  QVERIFY2(r.out.contains("free measure") && r.out.contains("oriented"), r.out);
  // Without replicates there is no interval: each row's CI reads "-".
  const QJsonArray table = QJsonDocument::fromJson(studyJson_).object().value("table").toArray();
  const QByteArray rho =
      QByteArray::number(table[0].toObject().value("spearman").toDouble(), 'f', 3);
  bool found = false;
  for (const QByteArray& line : r.out.split('\n')) {
    if (!line.startsWith("vsdns ") || !line.contains("iop_mm")) continue;
    found = true;
    QVERIFY2(line.contains(" " + rho + " "), line);
    QVERIFY2(line.contains(" - "), line);
  }
  QVERIFY2(found, r.out);
}

void TstCliGoodnessStudy::twoRunAgreement() {
  const QStringList flags{
      "--log",      kRun1,     "--second-log",  kRun2,         "--reference",
      kArafatWorld, "--model", "parameterized", "--rule",      "bayes-recursive",
      "--grid",     "p5=6,15", "--grid",        "p2=0.05,0.2", "--tie",
      "p1=1-p4"};
  const QStringList study = QStringList{"goodness-study"} << flags << "--bootstrap"
                                                          << "50"
                                                          << "--json";
  const Run r = runCli(study);
  QVERIFY2(r.finished && r.code == 0, describe(study, r));
  const QStringList sweep = QStringList{"sweep"}
                            << flags << "--metric"
                            << "vsdns,derivative,entropy,two-run,iop,correlation,auc"
                            << "--csv" << path("arafat.csv");
  const Run s = runCli(sweep);
  QVERIFY2(s.finished && s.code == 0, describe(sweep, s));
  const QJsonObject json = QJsonDocument::fromJson(r.out).object();
  QCOMPARE(json.value("sets").toInt(), 4);
  // Five free measures with the second log (two_run_agreement, then entropy), three reference
  // metrics.
  compareTable(json, parseCsv(readFile(path("arafat.csv"))), 15);
  QCOMPARE(json.value("table").toArray()[9].toObject().value("free").toString(),
           QString("two_run_agreement"));
  QCOMPARE(json.value("table").toArray()[12].toObject().value("free").toString(),
           QString("entropy"));
}

void TstCliGoodnessStudy::badFlagsExit2_data() {
  QTest::addColumn<QStringList>("args");
  QTest::addColumn<QString>("message");  // stderr names this
  const QStringList map{"--log", kRoom, "--model", "parameterized", "--rule", "bayes-recursive"};
  const QStringList ref{"--reference", kRoomWorld};
  const QStringList grid{"--grid", "p2=0.05:0.05:0.2"};
  auto study = [&](const QStringList& extra) {
    return QStringList{"goodness-study"} << map << extra;
  };
  QTest::newRow("no reference") << study(grid) << "--reference";
  QTest::newRow("metric given") << study(QStringList(ref) << grid << "--metric"
                                                          << "vsdns")
                                << "--metric";
  QTest::newRow("bootstrap negative") << study(QStringList(ref) << grid << "--bootstrap"
                                                                << "-1")
                                      << "--bootstrap";
  QTest::newRow("bootstrap text") << study(QStringList(ref) << grid << "--bootstrap"
                                                            << "many")
                                  << "--bootstrap";
  QTest::newRow("seed text") << study(QStringList(ref) << grid << "--seed"
                                                       << "lucky")
                             << "--seed";
  QTest::newRow("grid unknown parameter") << study(QStringList(ref) << "--grid"
                                                                    << "nope=1,2")
                                          << "--grid 'nope=1,2'";
  QTest::newRow("grid out of range") << study(QStringList(ref) << "--grid"
                                                               << "p2=0.05,5")
                                     << "--grid 'p2=0.05,5'";
  QTest::newRow("too few sets") << study(QStringList(ref) << "--grid"
                                                          << "p2=0.05,0.1")
                                << "--grid gives 2 sets";
  QTest::newRow("no grid") << study(ref) << "--grid gives 1 set";
  QTest::newRow("bad tie") << study(QStringList(ref) << grid << "--tie"
                                                     << "p1=log(p4)")
                           << "--tie";
  QTest::newRow("threads") << study(QStringList(ref) << grid << "--threads"
                                                     << "-2")
                           << "--threads";
  QTest::newRow("unknown flag") << study(QStringList(ref) << grid << "--frobnicate")
                                << "--frobnicate";
  QTest::newRow("unknown model") << (QStringList{"goodness-study", "--log", kRoom, "--model",
                                                 "nope", "--rule", "bayes-recursive"}
                                     << ref << grid)
                                 << "nope";
}

void TstCliGoodnessStudy::badFlagsExit2() {
  QFETCH(QStringList, args);
  QFETCH(QString, message);
  const Run r = runCli(args);
  QVERIFY2(r.finished && r.status == QProcess::NormalExit && r.code == 2, describe(args, r));
  QVERIFY2(r.err.contains(message.toUtf8()), describe(args, r));
}

QTEST_GUILESS_MAIN(TstCliGoodnessStudy)
#include "tst_cli_goodness_study.moc"
