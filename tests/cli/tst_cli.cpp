// SPDX-License-Identifier: GPL-3.0-or-later
// sonargrid-cli as a script sees it: the `models` and `map` contract of docs/cli.md, checked by
// running the binary through QProcess on the bundled room log and on logs derived from it at run
// time (a copy without true poses, one with shifted odometry, one with a malformed line), so that
// the fixtures follow the .sglog format whenever the room log is regenerated.

#include <QByteArray>
#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QJsonValue>
#include <QList>
#include <QMap>
#include <QProcess>
#include <QSet>
#include <QStringList>
#include <QTemporaryDir>
#include <QVariantMap>
#include <QtEndian>
#include <QtTest>
#include <algorithm>
#include <cmath>
#include <csignal>
#include <vector>

#include <sys/types.h>

#include "cli_run.h"

namespace {

using cli_test::kCli;
const QString kRoomLog = QStringLiteral(SONARGRID_DATASETS "/room/room.sglog");

// The keys `map --json` prints, no more and no fewer (docs/cli.md).
const QStringList kMapKeys = {"model",        "rule",      "precision",           "params",
                              "grid",         "readings",  "scans_without_truth", "cells_filled",
                              "cv_histogram", "elapsed_ms"};
const QStringList kGridKeys = {"width", "height", "cell_m", "origin"};
const QStringList kParameterKeys = {"name", "symbol", "unit", "min", "max", "default", "source"};

using cli_test::describe;
using cli_test::Run;
using cli_test::runCli;

bool isWholeNumber(const QJsonValue& v) {
  return v.isDouble() && v.toDouble() >= 0 && v.toDouble() == std::floor(v.toDouble());
}

qint64 count(const QJsonValue& v) {
  return static_cast<qint64>(v.toDouble());
}

QStringList sorted(QStringList l) {
  l.sort();
  return l;
}

QStringList namesOf(const QJsonArray& items) {
  QStringList out;
  for (const QJsonValue& v : items) out << v.toObject().value("name").toString();
  return out;
}

// The fields of one .sglog line, without a trailing comment.
QList<QByteArray> fieldsOf(const QByteArray& line) {
  QList<QByteArray> out;
  for (const QByteArray& f : line.simplified().split(' ')) {
    if (f.isEmpty()) continue;
    if (f.startsWith('#')) break;
    out << f;
  }
  return out;
}

bool writeFile(const QString& path, const QByteArray& content) {
  QFile f(path);
  return f.open(QIODevice::WriteOnly | QIODevice::Truncate) && f.write(content) == content.size();
}

QByteArray readFile(const QString& path) {
  QFile f(path);
  return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}

QJsonObject withoutElapsed(QJsonObject o) {
  o.remove("elapsed_ms");
  return o;
}

}  // namespace

class TstCli : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase();

  void help();
  void noArguments();
  void modelsText();
  void modelsJson();
  void modelsParameters_data();
  void modelsParameters();
  void modelsCompatible();

  void mapPairs_data();
  void mapPairs();
  void mapRefusedPairs_data();
  void mapRefusedPairs();
  void mapUntil_data();
  void mapUntil();
  void mapSet_data();
  void mapSet();
  void mapPoseTruth();
  void mapLeavesOutScansWithoutTruth();
  void mapPng_data();
  void mapPng();
  void mapRosMap();
  void mapTextSummary();
  void mapForwardModel();
  void mapStopsOnSigint();

  void errors_data();
  void errors();

  void scoreJson();
  void scoreMetricsSubset();
  void scoreBuiltMapFile();
  void scoreErrors_data();
  void scoreErrors();
  void goodnessJson();
  void goodnessTwoRuns();

 private:
  // Runs `map ... --json`, expects exit 0, nothing on stderr and one JSON object on one line.
  void mapJson(const QStringList& args, QJsonObject& out);
  // Checks one `map --json` object against the contract.
  void checkMapObject(const QJsonObject& o, const QString& model, const QString& rule, double cell);
  QMap<QString, double> defaultsOf(const QString& model, const QString& rule) const;
  qint64 readingsUpTo(double until) const;

  QTemporaryDir tmp_;
  QJsonObject models_;           // `models --json`
  QList<QByteArray> roomLines_;  // room.sglog, one entry per line
  std::vector<double> times_;    // every reading's time, in file order
  QList<QByteArray> timeTexts_;  // the same, as written
  QString noTruthLog_;           // the room log with every true pose replaced by `none`
  QString shiftedLog_;           // the room log with odometry = truth + (2 m, 0)
  QString malformedLog_;         // the room log with one reading's range replaced by `abc`
  int malformedLine_ = 0;
  QString emptyLog_;
};

void TstCli::initTestCase() {
  QVERIFY2(QFile::exists(kCli), qPrintable(kCli));
  QVERIFY(tmp_.isValid());

  const QByteArray room = readFile(kRoomLog);
  QVERIFY2(!room.isEmpty(), qPrintable(kRoomLog));
  roomLines_ = room.split('\n');
  for (QByteArray& l : roomLines_) {
    if (l.endsWith('\r')) l.chop(1);
  }

  // Derived logs: the same lines with one kind of change each.
  QList<QByteArray> noTruth = roomLines_;
  QList<QByteArray> shifted = roomLines_;
  QList<QByteArray> malformed = roomLines_;
  int truthScans = 0;
  for (qsizetype i = 0; i < roomLines_.size(); ++i) {
    const QList<QByteArray> f = fieldsOf(roomLines_[i]);
    if (f.isEmpty()) continue;
    if (f[0] == "r") {
      QCOMPARE(f.size(), 4);
      bool ok = false;
      times_.push_back(f[3].toDouble(&ok));
      QVERIFY2(ok, roomLines_[i].constData());
      timeTexts_ << f[3];
      if (times_.size() == 5) {
        malformed[i] = "r " + f[1] + " abc " + f[3];
        malformedLine_ = static_cast<int>(i) + 1;
      }
    } else if (f[0] == "scan" && f.size() == 8) {
      ++truthScans;
      noTruth[i] = QList<QByteArray>(f.begin(), f.begin() + 5).join(' ') + " none";
      bool ok = false;
      const double x = f[5].toDouble(&ok);
      QVERIFY(ok);
      QList<QByteArray> g = f;
      g[2] = QByteArray::number(x + 2.0, 'g', 17);
      g[3] = f[6];
      g[4] = f[7];
      shifted[i] = g.join(' ');
    }
  }
  QVERIFY2(!times_.empty(), "the room log has no readings");
  QVERIFY2(truthScans > 0, "the room log has no true poses");
  QVERIFY(malformedLine_ > 0);

  noTruthLog_ = tmp_.filePath("no_truth.sglog");
  shiftedLog_ = tmp_.filePath("shifted_odometry.sglog");
  malformedLog_ = tmp_.filePath("malformed.sglog");
  emptyLog_ = tmp_.filePath("empty.sglog");
  QVERIFY(writeFile(noTruthLog_, noTruth.join('\n')));
  QVERIFY(writeFile(shiftedLog_, shifted.join('\n')));
  QVERIFY(writeFile(malformedLog_, malformed.join('\n')));
  QVERIFY(writeFile(emptyLog_, {}));

  const QStringList args = {"models", "--json"};
  const Run r = runCli(args);
  QVERIFY2(r.finished && r.status == QProcess::NormalExit && r.code == 0, describe(args, r));
  QJsonParseError error;
  const QJsonDocument doc = QJsonDocument::fromJson(r.out, &error);
  QVERIFY2(error.error == QJsonParseError::NoError, qPrintable(error.errorString()));
  QVERIFY(doc.isObject());
  models_ = doc.object();
}

QMap<QString, double> TstCli::defaultsOf(const QString& model, const QString& rule) const {
  QMap<QString, double> out;
  const auto collect = [&](const QJsonArray& items, const QString& name) {
    for (const QJsonValue& item : items) {
      const QJsonObject o = item.toObject();
      if (o.value("name").toString() != name) continue;
      for (const QJsonValue& p : o.value("parameters").toArray()) {
        out.insert(p.toObject().value("name").toString(), p.toObject().value("default").toDouble());
      }
    }
  };
  collect(models_.value("models").toArray(), model);
  collect(models_.value("rules").toArray(), rule);
  return out;
}

qint64 TstCli::readingsUpTo(double until) const {
  return static_cast<qint64>(
      std::count_if(times_.begin(), times_.end(), [until](double t) { return t <= until; }));
}

void TstCli::mapJson(const QStringList& args, QJsonObject& out) {
  const Run r = runCli(args, tmp_.path());
  QVERIFY2(r.finished && r.status == QProcess::NormalExit && r.code == 0, describe(args, r));
  QVERIFY2(r.err.isEmpty(), describe(args, r));
  QVERIFY2(r.out.endsWith('\n') && r.out.count('\n') == 1, describe(args, r));
  QJsonParseError error;
  const QJsonDocument doc = QJsonDocument::fromJson(r.out, &error);
  QVERIFY2(error.error == QJsonParseError::NoError, qPrintable(error.errorString()));
  QVERIFY(doc.isObject());
  out = doc.object();
}

void TstCli::checkMapObject(const QJsonObject& o, const QString& model, const QString& rule,
                            double cell) {
  QCOMPARE(sorted(o.keys()), sorted(kMapKeys));
  QCOMPARE(o.value("model").toString(), model);
  QCOMPARE(o.value("rule").toString(), rule);

  QVERIFY(o.value("params").isObject());
  const QJsonObject params = o.value("params").toObject();
  for (const QString& k : params.keys()) QVERIFY2(params.value(k).isDouble(), qPrintable(k));

  QVERIFY(o.value("grid").isObject());
  const QJsonObject grid = o.value("grid").toObject();
  QCOMPARE(sorted(grid.keys()), sorted(kGridKeys));
  QVERIFY(isWholeNumber(grid.value("width")) && count(grid.value("width")) > 0);
  QVERIFY(isWholeNumber(grid.value("height")) && count(grid.value("height")) > 0);
  QCOMPARE(grid.value("cell_m").toDouble(), cell);
  const QJsonArray origin = grid.value("origin").toArray();
  QCOMPARE(origin.size(), 2);
  QVERIFY(origin[0].isDouble() && origin[1].isDouble());
  const qint64 cells = count(grid.value("width")) * count(grid.value("height"));

  QVERIFY(isWholeNumber(o.value("readings")));
  QVERIFY(isWholeNumber(o.value("cells_filled")));
  QVERIFY(count(o.value("cells_filled")) <= cells);

  const QJsonArray histogram = o.value("cv_histogram").toArray();
  QCOMPARE(histogram.size(), 16);
  qint64 sum = 0;
  for (const QJsonValue& v : histogram) {
    QVERIFY(isWholeNumber(v));
    sum += count(v);
  }
  QCOMPARE(sum, cells);

  QVERIFY(o.value("elapsed_ms").isDouble());
  QVERIFY(o.value("elapsed_ms").toDouble() >= 0.0);
}

// ---- help and `models` --------------------------------------------------------------------------

void TstCli::help() {
  for (const QString& word : QStringList{"help", "--help", "-h"}) {
    const Run r = runCli({word});
    QVERIFY2(r.finished && r.status == QProcess::NormalExit && r.code == 0, describe({word}, r));
    QVERIFY(r.out.startsWith("usage: sonargrid-cli"));
    QVERIFY(r.err.isEmpty());
  }
}

void TstCli::noArguments() {
  const Run r = runCli({});
  QVERIFY2(r.finished && r.status == QProcess::NormalExit, describe({}, r));
  QCOMPARE(r.code, 2);
  QVERIFY(r.out.isEmpty());
  // The contract: a one-line reason on stderr.
  QCOMPARE(r.err, QByteArray("sonargrid-cli: no command given (try sonargrid-cli help)\n"));
}

void TstCli::modelsText() {
  const Run r = runCli({"models"});
  QVERIFY2(r.finished && r.status == QProcess::NormalExit && r.code == 0, describe({"models"}, r));
  QVERIFY(!r.out.isEmpty());
  QVERIFY(r.err.isEmpty());
}

void TstCli::modelsJson() {
  QCOMPARE(sorted(models_.keys()), sorted({"models", "rules", "compatible", "forward"}));
  // The forward model learned by EM, with its own rule (docs/forward-model.md).
  const QJsonArray forward = models_.value("forward").toArray();
  QCOMPARE(forward.size(), 1);
  QCOMPARE(forward[0].toObject().value("name").toString(), QString("forward-em"));
  QCOMPARE(forward[0].toObject().value("rule").toString(), QString("em"));
  QCOMPARE(sorted(namesOf(forward[0].toObject().value("parameters").toArray())),
           sorted({"omega", "sigma", "p_rand", "p_max", "p_init", "iterations"}));
  const QJsonArray models = models_.value("models").toArray();
  const QJsonArray rules = models_.value("rules").toArray();
  QCOMPARE(models.size(), 5);
  QCOMPARE(rules.size(), 7);
  QCOMPARE(sorted(namesOf(models)), sorted({"hpf", "konolige", "murphy", "parameterized", "himm"}));
  QCOMPARE(sorted(namesOf(rules)), sorted({"addition", "bayes", "bayes-recursive", "log", "logodds",
                                           "himm", "dempster-shafer"}));
  for (const QJsonValue& v : models) {
    const QJsonObject m = v.toObject();
    QVERIFY(m.value("name").isString());
    QVERIFY(m.value("title").isString() && !m.value("title").toString().isEmpty());
    QVERIFY(m.value("parameters").isArray());
  }
  for (const QJsonValue& v : rules) {
    const QJsonObject r = v.toObject();
    QVERIFY(r.value("name").isString());
    QVERIFY(r.value("title").isString() && !r.value("title").toString().isEmpty());
  }
}

void TstCli::modelsParameters_data() {
  QTest::addColumn<QJsonArray>("parameters");
  for (const QString& list : QStringList{"models", "rules", "forward"}) {
    for (const QJsonValue& v : models_.value(list).toArray()) {
      const QJsonObject o = v.toObject();
      if (!o.contains("parameters")) continue;  // the contract declares them for models only
      QTest::addRow("%s %s", qPrintable(list), qPrintable(o.value("name").toString()))
          << o.value("parameters").toArray();
    }
  }
}

void TstCli::modelsParameters() {
  QFETCH(QJsonArray, parameters);
  QSet<QString> names;
  for (const QJsonValue& v : parameters) {
    const QJsonObject p = v.toObject();
    const QString name = p.value("name").toString();
    for (const QString& key : kParameterKeys) {
      QVERIFY2(p.contains(key), qPrintable(name + " lacks " + key));
    }
    for (const QString& key : QStringList{"name", "symbol", "unit", "source"}) {
      QVERIFY2(p.value(key).isString(), qPrintable(name + "." + key));
    }
    for (const QString& key : QStringList{"min", "max", "default"}) {
      QVERIFY2(p.value(key).isDouble(), qPrintable(name + "." + key));
    }
    QVERIFY(!name.isEmpty());
    QVERIFY2(!names.contains(name), qPrintable(name));
    names.insert(name);
    const double min = p.value("min").toDouble();
    const double max = p.value("max").toDouble();
    const double def = p.value("default").toDouble();
    QVERIFY2(min <= def && def <= max,
             qPrintable(QStringLiteral("%1: %2 <= %3 <= %4").arg(name).arg(min).arg(def).arg(max)));
  }
}

void TstCli::modelsCompatible() {
  const QStringList models = namesOf(models_.value("models").toArray());
  const QStringList rules = namesOf(models_.value("rules").toArray());
  QSet<QString> seen;
  bool himmHimm = false;
  for (const QJsonValue& v : models_.value("compatible").toArray()) {
    QVERIFY(v.isArray());
    const QJsonArray pair = v.toArray();
    QCOMPARE(pair.size(), 2);
    const QString model = pair[0].toString();
    const QString rule = pair[1].toString();
    QVERIFY2(models.contains(model), qPrintable(model));
    QVERIFY2(rules.contains(rule), qPrintable(rule));
    QVERIFY2(!(rule == "himm" && model != "himm"), qPrintable(model + " × " + rule));
    QVERIFY2(!seen.contains(model + " " + rule), qPrintable(model + " × " + rule));
    seen.insert(model + " " + rule);
    himmHimm = himmHimm || (model == "himm" && rule == "himm");
  }
  QVERIFY(himmHimm);
  QVERIFY(seen.size() >= 25);  // every cone model with the six probability rules, at least
}

// ---- `map` --------------------------------------------------------------------------------------

void TstCli::mapPairs_data() {
  QTest::addColumn<QString>("model");
  QTest::addColumn<QString>("rule");
  QTest::addColumn<QString>("cell");  // empty: the default
  const QStringList cells = {"", "0.1", "0.08"};
  int i = 0;
  for (const QJsonValue& v : models_.value("compatible").toArray()) {
    const QString model = v.toArray()[0].toString();
    const QString rule = v.toArray()[1].toString();
    const QString cell = cells[i++ % cells.size()];
    QTest::addRow("%s × %s, cell %s", qPrintable(model), qPrintable(rule),
                  cell.isEmpty() ? "default" : qPrintable(cell))
        << model << rule << cell;
  }
}

void TstCli::mapPairs() {
  QFETCH(QString, model);
  QFETCH(QString, rule);
  QFETCH(QString, cell);
  QStringList args = {"map", "--log", kRoomLog, "--model", model, "--rule", rule, "--json"};
  if (!cell.isEmpty()) args << "--cell" << cell;
  QJsonObject o;
  mapJson(args, o);
  // --precision exact is the default: the same JSON (elapsed_ms aside); fast maps the same
  // grid and readings (its levels: tst_precision, docs/models.md, "Exact and fast engines").
  for (const char* precision : {"exact", "fast"}) {
    QJsonObject with;
    mapJson(args + QStringList{"--precision", precision}, with);
    if (QTest::currentTestFailed()) return;
    QCOMPARE(with.value("grid"), o.value("grid"));
    QCOMPARE(with.value("readings"), o.value("readings"));
    QCOMPARE(with.value("precision").toString(), QString(precision));  // the engine it used
    if (QString(precision) == "exact") {
      with.remove("elapsed_ms");
      QJsonObject without = o;
      without.remove("elapsed_ms");
      QCOMPARE(with, without);
    }
  }
  if (QTest::currentTestFailed()) return;
  checkMapObject(o, model, rule, cell.isEmpty() ? 0.05 : cell.toDouble());
  if (QTest::currentTestFailed()) return;
  QCOMPARE(count(o.value("readings")), static_cast<qint64>(times_.size()));

  // params: every parameter of the model and of the rule, at its declared default.
  const QMap<QString, double> defaults = defaultsOf(model, rule);
  const QJsonObject params = o.value("params").toObject();
  QCOMPARE(sorted(params.keys()), sorted(defaults.keys()));
  for (auto it = defaults.begin(); it != defaults.end(); ++it) {
    QCOMPARE(params.value(it.key()).toDouble(), it.value());
  }
}

void TstCli::mapRefusedPairs_data() {
  QTest::addColumn<QString>("model");
  QTest::addColumn<QString>("rule");
  QSet<QString> allowed;
  for (const QJsonValue& v : models_.value("compatible").toArray()) {
    allowed.insert(v.toArray()[0].toString() + " " + v.toArray()[1].toString());
  }
  for (const QString& model : namesOf(models_.value("models").toArray())) {
    for (const QString& rule : namesOf(models_.value("rules").toArray())) {
      if (allowed.contains(model + " " + rule)) continue;
      QTest::addRow("%s × %s", qPrintable(model), qPrintable(rule)) << model << rule;
    }
  }
}

// Every pair that `models --json` does not list is refused by `map`, with the reason.
void TstCli::mapRefusedPairs() {
  QFETCH(QString, model);
  QFETCH(QString, rule);
  const QStringList args = {"map", "--log", kRoomLog, "--model", model, "--rule", rule, "--json"};
  const Run r = runCli(args, tmp_.path());
  QVERIFY2(r.finished && r.status == QProcess::NormalExit && r.code == 2, describe(args, r));
  QVERIFY(r.out.isEmpty());
  QCOMPARE(r.err.count('\n'), 1);
  const QByteArray prefix = "sonargrid-cli: model '" + model.toUtf8() +
                            "' cannot be used with rule '" + rule.toUtf8() + "': ";
  QVERIFY2(r.err.startsWith(prefix), r.err.constData());
  QVERIFY2(r.err.size() > prefix.size() + 10, "the message gives no reason");
}

void TstCli::mapUntil_data() {
  QTest::addColumn<QString>("until");
  QTest::addColumn<qint64>("expected");
  std::vector<double> sortedTimes = times_;
  std::sort(sortedTimes.begin(), sortedTimes.end());
  const double first = sortedTimes.front();
  const double last = sortedTimes.back();
  const auto text = [](double t) { return QString::number(t, 'g', 17); };

  QTest::newRow("before the first reading") << text(first - 1.0) << qint64{0};
  // A reading's own time counts (readings at most `until` are mapped).
  const qsizetype middle = timeTexts_.size() / 2;
  QTest::newRow("a reading's time, as written")
      << QString::fromUtf8(timeTexts_[middle]) << readingsUpTo(times_[middle]);
  const std::size_t quarter = sortedTimes.size() / 4;
  auto next = std::upper_bound(sortedTimes.begin(), sortedTimes.end(), sortedTimes[quarter]);
  if (next != sortedTimes.end()) {
    const double between = (sortedTimes[quarter] + *next) / 2.0;
    QTest::newRow("between two readings") << text(between) << readingsUpTo(between);
  }
  QTest::newRow("the last reading") << text(last) << static_cast<qint64>(times_.size());
  QTest::newRow("after the last reading") << text(last + 1.0) << static_cast<qint64>(times_.size());
}

void TstCli::mapUntil() {
  QFETCH(QString, until);
  QFETCH(qint64, expected);
  QJsonObject full;
  QJsonObject part;
  mapJson({"map", "--log", kRoomLog, "--model", "hpf", "--rule", "bayes", "--json"}, full);
  mapJson(
      {"map", "--log", kRoomLog, "--model", "hpf", "--rule", "bayes", "--until", until, "--json"},
      part);
  if (QTest::currentTestFailed()) return;
  checkMapObject(part, "hpf", "bayes", 0.05);
  QCOMPARE(count(part.value("readings")), expected);
  // The grid fits the whole log whatever --until says.
  QCOMPARE(part.value("grid"), full.value("grid"));
  if (expected < static_cast<qint64>(times_.size())) {
    QVERIFY(part.value("cv_histogram") != full.value("cv_histogram"));
  } else {
    QCOMPARE(withoutElapsed(part), withoutElapsed(full));
  }
  if (expected == 0) QCOMPARE(count(part.value("cells_filled")), qint64{0});
}

void TstCli::mapSet_data() {
  QTest::addColumn<QString>("model");
  QTest::addColumn<QString>("rule");
  QTest::addColumn<QStringList>("extra");
  QTest::addColumn<QVariantMap>("changed");
  QTest::newRow("hpf epsilon") << "hpf"
                               << "bayes" << QStringList{"--set", "epsilon=0.3"}
                               << QVariantMap{{"epsilon", 0.3}};
  QTest::newRow("model and rule parameter")
      << "konolige"
      << "logodds" << QStringList{"--set", "false_rate=0.2", "--set", "clamp_max=0.9"}
      << QVariantMap{{"false_rate", 0.2}, {"clamp_max", 0.9}};
  QTest::newRow("--set=NAME=VALUE")
      << "himm"
      << "himm" << QStringList{"--set=increment=6"} << QVariantMap{{"increment", 6.0}};
  QTest::newRow("switch") << "hpf"
                          << "addition" << QStringList{"--set", "no_echo=1"}
                          << QVariantMap{{"no_echo", 1.0}};
}

void TstCli::mapSet() {
  QFETCH(QString, model);
  QFETCH(QString, rule);
  QFETCH(QStringList, extra);
  QFETCH(QVariantMap, changed);
  const QStringList base = {"map", "--log", kRoomLog, "--model", model, "--rule", rule, "--json"};
  QJsonObject byDefault;
  QJsonObject set;
  mapJson(base, byDefault);
  mapJson(base + extra, set);
  if (QTest::currentTestFailed()) return;
  checkMapObject(set, model, rule, 0.05);

  const QMap<QString, double> defaults = defaultsOf(model, rule);
  const QJsonObject params = set.value("params").toObject();
  QCOMPARE(sorted(params.keys()), sorted(defaults.keys()));
  for (auto it = defaults.begin(); it != defaults.end(); ++it) {
    const double expected = changed.value(it.key(), it.value()).toDouble();
    QCOMPARE(params.value(it.key()).toDouble(), expected);
  }
  QCOMPARE(set.value("grid"), byDefault.value("grid"));
  QCOMPARE(set.value("readings"), byDefault.value("readings"));
  QVERIFY2(set.value("cv_histogram") != byDefault.value("cv_histogram"),
           "--set did not change the map");
}

// The room log with its first scan's true pose replaced by `none` (as a simulator's first SIP
// before its first SIMSTAT is recorded): --pose truth maps the other 742 scans, says so on stderr
// and in the JSON, and gives the map of the log without that scan.
void TstCli::mapLeavesOutScansWithoutTruth() {
  QList<QByteArray> partial = roomLines_;
  QList<QByteArray> without;
  int scans = 0;
  qint64 firstScanReadings = 0;
  for (QByteArray& line : partial) {
    const QList<QByteArray> f = fieldsOf(line);
    const bool scan = !f.isEmpty() && f[0] == "scan";
    if (scan) ++scans;
    if (scan && scans == 1) line = QList<QByteArray>(f.begin(), f.begin() + 5).join(' ') + " none";
    if (scans == 1 && !f.isEmpty() && f[0] == "r") ++firstScanReadings;
    if (scans != 1) without << line;
  }
  QCOMPARE(firstScanReadings, qint64{16});  // room.sglog: 16 sonars a scan
  const QString partialLog = tmp_.filePath(QStringLiteral("first_scan_without_truth.sglog"));
  const QString withoutLog = tmp_.filePath(QStringLiteral("without_first_scan.sglog"));
  QVERIFY(writeFile(partialLog, partial.join('\n')));
  QVERIFY(writeFile(withoutLog, without.join('\n')));
  const QStringList args = {"map",     "--log", partialLog, "--pose", "truth",
                            "--model", "himm",  "--rule",   "himm",   "--json"};
  const Run r = runCli(args);
  QVERIFY2(r.finished && r.code == 0, describe(args, r));
  QCOMPARE(QString::fromUtf8(r.err.trimmed()),
           QStringLiteral("sonargrid-cli: note: %1: 1 of 743 scans have no true pose and are left "
                          "out of the map")
               .arg(partialLog));
  const QJsonObject o = QJsonDocument::fromJson(r.out).object();
  QCOMPARE(count(o.value("scans_without_truth")), qint64{1});
  QCOMPARE(count(o.value("readings")), static_cast<qint64>(times_.size()) - firstScanReadings);
  QJsonObject reference;
  mapJson(QStringList{"map", "--log", withoutLog, "--pose", "truth", "--model", "himm", "--rule",
                      "himm", "--json"},
          reference);
  QCOMPARE(count(reference.value("scans_without_truth")), qint64{0});
  QCOMPARE(o.value("grid"), reference.value("grid"));
  QCOMPARE(o.value("cv_histogram"), reference.value("cv_histogram"));
  QCOMPARE(o.value("cells_filled"), reference.value("cells_filled"));
}

void TstCli::mapPoseTruth() {
  const QStringList model = {"--model", "hpf", "--rule", "bayes", "--json"};
  QJsonObject roomTruth;
  QJsonObject shiftedTruth;
  QJsonObject roomOdom;
  QJsonObject shiftedOdom;
  mapJson(QStringList{"map", "--log", kRoomLog, "--pose", "truth"} + model, roomTruth);
  mapJson(QStringList{"map", "--log", shiftedLog_, "--pose", "truth"} + model, shiftedTruth);
  mapJson(QStringList{"map", "--log", kRoomLog, "--pose", "odom"} + model, roomOdom);
  mapJson(QStringList{"map", "--log", shiftedLog_} + model, shiftedOdom);
  if (QTest::currentTestFailed()) return;
  checkMapObject(roomTruth, "hpf", "bayes", 0.05);
  checkMapObject(shiftedTruth, "hpf", "bayes", 0.05);
  QCOMPARE(count(roomTruth.value("readings")), static_cast<qint64>(times_.size()));

  // The shifted log has the room's true poses: mapped with them it is the room's map exactly.
  QCOMPARE(withoutElapsed(shiftedTruth), withoutElapsed(roomTruth));
  // Its odometry is the true pose 2 m further along x: mapped with it (the default), so is the
  // grid.
  const QJsonObject a = roomTruth.value("grid").toObject();
  const QJsonObject b = shiftedOdom.value("grid").toObject();
  const double dx =
      b.value("origin").toArray()[0].toDouble() - a.value("origin").toArray()[0].toDouble();
  const double dy =
      b.value("origin").toArray()[1].toDouble() - a.value("origin").toArray()[1].toDouble();
  QVERIFY2(std::abs(dx - 2.0) <= 0.05 + 1e-9, qPrintable(QString::number(dx)));
  QVERIFY2(std::abs(dy) <= 0.05 + 1e-9, qPrintable(QString::number(dy)));
  QCOMPARE(shiftedOdom.value("readings"), roomTruth.value("readings"));
  // Snapping the origin to the cell size may add or drop one column or row.
  QVERIFY(std::abs(count(b.value("width")) - count(a.value("width"))) <= 1);
  QVERIFY(std::abs(count(b.value("height")) - count(a.value("height"))) <= 1);

  // Odometry is all a log without true poses needs.
  QJsonObject noTruth;
  mapJson(QStringList{"map", "--log", noTruthLog_, "--pose", "odom"} + model, noTruth);
  if (QTest::currentTestFailed()) return;
  QCOMPARE(withoutElapsed(noTruth), withoutElapsed(roomOdom));
}

void TstCli::mapPng_data() {
  QTest::addColumn<QStringList>("extra");
  QTest::addColumn<int>("scale");
  QTest::addColumn<bool>("legend");
  QTest::newRow("default scale") << QStringList{} << 1 << false;
  QTest::newRow("scale 3") << QStringList{"--scale", "3"} << 3 << false;
  QTest::newRow("legend") << QStringList{"--legend"} << 1 << true;
  QTest::newRow("legend, scale 2") << QStringList{"--legend", "--scale", "2"} << 2 << true;
}

void TstCli::mapPng() {
  QFETCH(QStringList, extra);
  QFETCH(int, scale);
  QFETCH(bool, legend);
  const QString png = tmp_.filePath(QStringLiteral("map-%1-%2.png").arg(scale).arg(legend));
  QFile::remove(png);
  QJsonObject o;
  mapJson(QStringList{"map", "--log", kRoomLog, "--model", "murphy", "--rule", "logodds", "--cell",
                      "0.1", "--png", png, "--json"} +
              extra,
          o);
  if (QTest::currentTestFailed()) return;
  checkMapObject(o, "murphy", "logodds", 0.1);

  const QByteArray bytes = readFile(png);
  QVERIFY2(bytes.size() > 33, qPrintable(png));
  QCOMPARE(bytes.left(8), QByteArray("\x89PNG\r\n\x1a\n", 8));
  QCOMPARE(bytes.mid(12, 4), QByteArray("IHDR"));
  const auto width = static_cast<qint64>(qFromBigEndian<quint32>(bytes.constData() + 16));
  const auto height = static_cast<qint64>(qFromBigEndian<quint32>(bytes.constData() + 20));
  const qint64 gridWidth = count(o.value("grid").toObject().value("width"));
  const qint64 gridHeight = count(o.value("grid").toObject().value("height"));
  if (legend) {
    QVERIFY(width >= gridWidth * scale);
    QVERIFY(height > gridHeight * scale);  // the legend strip is below the map
  } else {
    QCOMPARE(width, gridWidth * scale);
    QCOMPARE(height, gridHeight * scale);
  }
}

void TstCli::mapRosMap() {
  const QString base = tmp_.filePath("ros/room");
  QVERIFY(QDir().mkpath(tmp_.filePath("ros")));
  QJsonObject o;
  mapJson({"map", "--log", kRoomLog, "--model", "konolige", "--rule", "bayes", "--cell", "0.1",
           "--ros-map", base, "--json"},
          o);
  if (QTest::currentTestFailed()) return;
  const QJsonObject grid = o.value("grid").toObject();
  const qint64 width = count(grid.value("width"));
  const qint64 height = count(grid.value("height"));

  const QByteArray pgm = readFile(base + ".pgm");
  const QByteArray header =
      "P5\n" + QByteArray::number(width) + ' ' + QByteArray::number(height) + "\n255\n";
  QVERIFY2(pgm.startsWith(header), pgm.left(30).constData());
  QCOMPARE(static_cast<qint64>(pgm.size()), header.size() + width * height);

  const QList<QByteArray> yaml = readFile(base + ".yaml").split('\n');
  QVERIFY2(yaml.size() >= 7, "short YAML");
  QCOMPARE(yaml[0], QByteArray("image: room.pgm"));
  QVERIFY(yaml[1].startsWith("resolution: "));
  QCOMPARE(yaml[1].mid(12).toDouble(), grid.value("cell_m").toDouble());
  QVERIFY(yaml[2].startsWith("origin: [") && yaml[2].endsWith(", 0.0]"));
  const QList<QByteArray> origin = yaml[2].mid(9).chopped(1).split(',');
  QCOMPARE(origin.size(), 3);
  QCOMPARE(origin[0].trimmed().toDouble(), grid.value("origin").toArray()[0].toDouble());
  QCOMPARE(origin[1].trimmed().toDouble(), grid.value("origin").toArray()[1].toDouble());
  QCOMPARE(yaml[3], QByteArray("negate: 0"));
  QCOMPARE(yaml[4], QByteArray("occupied_thresh: 0.65"));
  QCOMPARE(yaml[5], QByteArray("free_thresh: 0.196"));
  QCOMPARE(yaml[6], QByteArray("mode: trinary"));
}

// Without --json the summary is for people; it is not part of the contract beyond "some text".
void TstCli::mapTextSummary() {
  const QString png = tmp_.filePath("summary.png");
  const QString ros = tmp_.filePath("summary");
  const QStringList args = {"map",  "--log", kRoomLog, "--model",   "himm", "--rule",
                            "himm", "--png", png,      "--ros-map", ros};
  const Run r = runCli(args, tmp_.path());
  QVERIFY2(r.finished && r.status == QProcess::NormalExit && r.code == 0, describe(args, r));
  QVERIFY(r.err.isEmpty());
  QVERIFY(!r.out.isEmpty());
  QVERIFY(!r.out.startsWith('{'));
  QVERIFY(QFile::exists(png));
  QVERIFY(QFile::exists(ros + ".yaml"));
  QVERIFY(QFile::exists(ros + ".pgm"));
}

// `--model forward-em` (docs/forward-model.md): EM's log-likelihood trace in --json, one line of
// progress per iteration on stderr, every reading of the log mapped; `score` takes it too.
void TstCli::mapForwardModel() {
  const QStringList args = {"map",        "--log",        kRoomLog, "--model",
                            "forward-em", "--iterations", "3",      "--json"};
  const Run r = runCli(args, tmp_.path());
  QVERIFY2(r.finished && r.status == QProcess::NormalExit && r.code == 0, describe(args, r));
  const QJsonObject o = QJsonDocument::fromJson(r.out).object();
  QCOMPARE(o.value("model").toString(), QString("forward-em"));
  QCOMPARE(o.value("rule").toString(), QString("em"));
  QCOMPARE(o.value("readings").toInteger(), qint64(times_.size()));
  QCOMPARE(o.value("params").toObject().value("iterations").toDouble(), 3.0);
  const QJsonObject em = o.value("em").toObject();
  const QJsonArray trace = em.value("log_likelihood").toArray();
  // The start and one value per iteration; three iterations do not converge on this log.
  QCOMPARE(em.value("iterations").toInt(), 3);
  QCOMPARE(em.value("converged").toBool(), false);
  QCOMPARE(trace.size(), 4);
  for (qsizetype i = 1; i < trace.size(); ++i)
    QVERIFY(trace[i].toDouble() >= trace[i - 1].toDouble());
  QVERIFY(em.value("cone_cells").toInteger() > o.value("readings").toInteger());
  QVERIFY(o.value("cells_filled").toInteger() > 0);
  QCOMPARE(r.err.count("EM iteration "), 4);

  const QString reference = QStringLiteral(SONARGRID_DATASETS "/room/room.json");
  const QStringList score = {"score",   "--reference", reference,      "--log", kRoomLog,
                             "--model", "forward-em",  "--iterations", "2",     "--json"};
  const Run s = runCli(score, tmp_.path());
  QVERIFY2(s.finished && s.status == QProcess::NormalExit && s.code == 0, describe(score, s));
  const double iop = QJsonDocument::fromJson(s.out).object().value("iop_mm").toDouble();
  QVERIFY(iop > 0.0);

  // `sweep` maps each set by EM: the set at the defaults scores as `score` scored it above.
  const QString csv = tmp_.filePath("forward-sweep.csv");
  const QStringList sweep = {
      "sweep",           "--log",      kRoomLog,       "--reference", reference,
      "--model",         "forward-em", "--iterations", "2",           "--grid",
      "sigma=0.03,0.05", "--metric",   "iop",          "--csv",       csv};
  const Run w = runCli(sweep, tmp_.path());
  QVERIFY2(w.finished && w.status == QProcess::NormalExit && w.code == 0, describe(sweep, w));
  QFile file(csv);
  QVERIFY(file.open(QIODevice::ReadOnly));
  QStringList rows;
  for (const QByteArray& line : file.readAll().split('\n'))
    if (!line.isEmpty() && !line.startsWith('#')) rows << QString::fromUtf8(line);
  QCOMPARE(rows.size(), 3);  // the header and two sets
  const QStringList header = rows[0].split(',');
  const QStringList second = rows[2].split(',');
  QCOMPARE(second[header.indexOf("sigma")].toDouble(), 0.05);
  QCOMPARE(second[header.indexOf("iop_mm")].toDouble(), iop);
}

// Ctrl-C during the forward model's EM (the room log, up to 500 iterations of some 40 ms): the map
// stops between iterations, nothing is written, exit status 128 + SIGINT.
void TstCli::mapStopsOnSigint() {
  const QString png = tmp_.filePath("stopped.png");
  QProcess p;
  p.setProgram(kCli);
  p.setArguments(
      {"map", "--log", kRoomLog, "--model", "forward-em", "--iterations", "500", "--png", png});
  p.start();
  QVERIFY(p.waitForStarted(10000));
  QByteArray err;
  QElapsedTimer clock;
  clock.start();
  while (!err.contains("EM iteration 1 ") && clock.elapsed() < 120000 &&
         p.state() == QProcess::Running) {
    p.waitForReadyRead(200);
    err += p.readAllStandardError();
  }
  QVERIFY2(err.contains("EM iteration 1 "), err.constData());
  QCOMPARE(::kill(static_cast<pid_t>(p.processId()), SIGINT), 0);
  QVERIFY(p.waitForFinished(60000));
  err += p.readAllStandardError();
  QCOMPARE(p.exitStatus(), QProcess::NormalExit);
  QCOMPARE(p.exitCode(), 128 + SIGINT);
  QVERIFY2(err.contains("sonargrid-cli: map stopped by SIGINT; nothing written"), err.constData());
  QVERIFY(!err.contains("EM iteration 500 "));
  QVERIFY(!QFile::exists(png));
}

// ---- errors -------------------------------------------------------------------------------------

void TstCli::errors_data() {
  QTest::addColumn<QStringList>("args");
  QTest::addColumn<int>("code");
  QTest::addColumn<QString>("message");  // the whole stderr line without "sonargrid-cli: " and LF
  QTest::addColumn<bool>("exact");       // false: `message` is the start of the line

  const QString log = kRoomLog;
  const QStringList map = {"map", "--log", log, "--model", "hpf", "--rule", "bayes"};
  const QString missingDir = tmp_.filePath("missing");

  QTest::newRow("unknown command")
      << QStringList{"frobnicate"} << 2 << "unknown command 'frobnicate' (try sonargrid-cli help)"
      << true;
  QTest::newRow("map: the forward model with a rule")
      << QStringList{"map", "--log", log, "--model", "forward-em", "--rule", "bayes"} << 2
      << "--model forward-em learns its map by EM and takes no update rule: leave out --rule "
         "'bayes'"
      << true;
  QTest::newRow("map: an unknown --precision")
      << (map + QStringList{"--precision", "double"}) << 2
      << "--precision takes fast or exact, got 'double'" << true;
  QTest::newRow("sweep: --precision fast")
      << QStringList{"sweep", "--log",    log,     "--model",     "hpf", "--rule",
                     "bayes", "--metric", "vsdns", "--precision", "fast"}
      << 2
      << "sweeps, the optimiser and the goodness study map with the exact engine: leave out "
         "--precision"
      << true;
  QTest::newRow("map: --iterations with an inverse model")
      << (map + QStringList{"--iterations", "5"}) << 2
      << "--iterations caps EM's iterations: it goes with --model forward-em" << true;
  QTest::newRow("map: --iterations out of range")
      << QStringList{"map", "--log", log, "--model", "forward-em", "--iterations", "0"} << 2
      << "--iterations: " << false;
  QTest::newRow("models: extra argument")
      << QStringList{"models", "--json", "extra"} << 2 << "unexpected argument 'extra'" << true;
  QTest::newRow("models: --json twice")
      << QStringList{"models", "--json", "--json"} << 2 << "--json is given 2 times" << true;

  QTest::newRow("map without arguments") << QStringList{"map"} << 2 << "missing --log" << true;
  QTest::newRow("missing --log") << QStringList{"map", "--model", "hpf", "--rule", "bayes"} << 2
                                 << "missing --log" << true;
  QTest::newRow("--log without a value")
      << QStringList{"map", "--log"} << 2 << "--log needs a value" << true;
  QTest::newRow("missing --model")
      << QStringList{"map", "--log", log, "--rule", "bayes"} << 2 << "missing --model" << true;
  QTest::newRow("missing --rule") << QStringList{"map", "--log", log, "--model", "hpf"} << 2
                                  << "missing --rule" << true;
  QTest::newRow("unknown model") << QStringList{"map",    "--log",  log,    "--model",
                                                "sonar9", "--rule", "bayes"}
                                 << 2
                                 << "unknown --model 'sonar9'; choose one of hpf, konolige, "
                                    "murphy, parameterized, himm, forward-em"
                                 << true;
  QTest::newRow("unknown rule")
      << QStringList{"map", "--log", log, "--model", "hpf", "--rule", "fuzzy"} << 2
      << "unknown --rule 'fuzzy'; choose one of addition, bayes, bayes-recursive, log, logodds, "
         "himm, dempster-shafer"
      << true;
  // The reason after the colon is compatibility()'s (docs/models.md); it mentions HIMM's one cell.
  QTest::newRow("incompatible pair hpf × himm")
      << QStringList{"map", "--log", log, "--model", "hpf", "--rule", "himm"} << 2
      << "model 'hpf' cannot be used with rule 'himm': the HIMM histogram adds I+ to one cell per "
         "reading"
      << false;
  QTest::newRow("unknown --pose") << map + QStringList{"--pose", "gps"} << 2
                                  << "--pose takes odom or truth, got 'gps'" << true;

  QTest::newRow("unknown --set name")
      << map + QStringList{"--set", "gain=2"} << 2
      << "--set: unknown parameter 'gain'; this model and rule take: epsilon omega r_min no_echo "
         "prior"
      << true;
  QTest::newRow("--set above the range")
      << map + QStringList{"--set", "epsilon=5"} << 2
      << "--set: parameter 'epsilon' = 5 is outside [0.005, 1] m" << true;
  QTest::newRow("--set below the range")
      << map + QStringList{"--set", "prior=0"} << 2
      << "--set: parameter 'prior' = 0 is outside [0.01, 0.99]" << true;
  QTest::newRow("--set fraction for a switch")
      << map + QStringList{"--set", "no_echo=0.5"} << 2
      << "--set: parameter 'no_echo' takes a whole number" << true;
  QTest::newRow("--set without =") << map + QStringList{"--set", "epsilon"} << 2
                                   << "--set expects NAME=VALUE, got 'epsilon'" << true;
  QTest::newRow("--set without a name")
      << map + QStringList{"--set", "=0.2"} << 2 << "--set expects NAME=VALUE, got '=0.2'" << true;
  QTest::newRow("--set with a non-number") << map + QStringList{"--set", "epsilon=0.2m"} << 2
                                           << "--set epsilon expects a number, got '0.2m'" << true;
  QTest::newRow("--set without a value")
      << map + QStringList{"--set"} << 2 << "--set needs a value" << true;

  QTest::newRow("--cell 0") << map + QStringList{"--cell", "0"} << 2
                            << "--cell must be between 0.001 and 10, got 0" << true;
  QTest::newRow("--cell=0") << map + QStringList{"--cell=0"} << 2
                            << "--cell must be between 0.001 and 10, got 0" << true;
  QTest::newRow("--cell too large") << map + QStringList{"--cell", "11"} << 2
                                    << "--cell must be between 0.001 and 10, got 11" << true;
  QTest::newRow("--cell non-numeric")
      << map + QStringList{"--cell", "fine"} << 2 << "--cell expects a number, got 'fine'" << true;
  QTest::newRow("--until non-numeric") << map + QStringList{"--until", "soon"} << 2
                                       << "--until expects a number, got 'soon'" << true;
  QTest::newRow("--until nan") << map + QStringList{"--until", "nan"} << 2
                               << "--until expects a number, got 'nan'" << true;
  QTest::newRow("--scale 0") << map + QStringList{"--scale", "0"} << 2
                             << "--scale must be between 1 and 64, got 0" << true;

  const QString absent = tmp_.filePath("absent.sglog");
  QTest::newRow("missing log file")
      << QStringList{"map", "--log", absent, "--model", "hpf", "--rule", "bayes"} << 2
      << absent + ": cannot open: No such file or directory" << true;
  QTest::newRow("log is a directory")
      << QStringList{"map", "--log", tmp_.path(), "--model", "hpf", "--rule", "bayes"} << 2
      << tmp_.path() + ": cannot read: Is a directory" << true;
  QTest::newRow("empty log") << QStringList{"map", "--log",  emptyLog_, "--model",
                                            "hpf", "--rule", "bayes"}
                             << 2
                             << emptyLog_ + ": empty file (expected 'sglog 1' on the first line)"
                             << true;
  QTest::newRow("malformed log")
      << QStringList{"map", "--log", malformedLog_, "--model", "hpf", "--rule", "bayes"} << 2
      << QStringLiteral("%1:%2: range: expected a number of metres >= 0 or 'none', found 'abc'")
             .arg(malformedLog_)
             .arg(malformedLine_)
      << true;
  QTest::newRow("--pose truth without true poses")
      << QStringList{"map",    "--log", noTruthLog_, "--model", "hpf",
                     "--rule", "bayes", "--pose",    "truth"}
      << 2 << noTruthLog_ + ": the log has no true pose in any scan; map with --pose odom" << true;

  // A log no grid can hold is input to fix (exit 2), not a 1 x 38 grid (an int overflow) and exit
  // 0. tests/data/sglog/far_pose.sglog: scans at x = 0 and 0.25 with 1 m echoes on a 25° cone
  // (edges at y = ±sin 12.5° = ±0.21644), and scan 2 at x = 1e12. At 5 cm with the 0.5 m margin: x
  // from -0.5, (1e12 + 1) / 0.05 = 20000000000020 cells; y from floor(-0.71644 / 0.05) = -15 cells,
  // (0.71644 + 0.75) / 0.05 = 29.3 -> 30 cells. Scan 2 is the one far from the middle of the path.
  const QString far = QStringLiteral(SONARGRID_TEST_DATA "/sglog/far_pose.sglog");
  const QString farMessage =
      far +
      ": scan 2 (t = 1 s) reaches (1e+12, 0) m: x 0 to 1e+12 m, y -0.21644 to 0.21644 m grown by "
      "0.5 m make a grid of 20000000000020 x 30 cells of 0.05 m, more than the grid limit of "
      "200000000 cells";
  QTest::newRow("a pose at x = 1e12 m")
      << QStringList{"map", "--log", far, "--model", "hpf", "--rule", "bayes"} << 2 << farMessage
      << true;
  QTest::newRow("a pose at x = 1e12 m, --png")
      << QStringList{"map",     "--log", far,
                     "--model", "hpf",   "--rule",
                     "bayes",   "--png", tmp_.filePath("missing/far.png")}
      << 2 << farMessage << true;
  QTest::newRow("goodness, a pose at x = 1e12 m")
      << QStringList{"goodness", "--log", far, "--model", "hpf", "--rule", "bayes"} << 2
      << farMessage << true;
  // The office (about 35 m x 27 m) at 1 mm: a real log, but 35791 x 27261 cells is more than the
  // limit. The message names the log and a scan at the edge of the extent.
  const QString office = QStringLiteral(SONARGRID_DATASETS "/office/office.sglog");
  QTest::newRow("a cell too small for the log")
      << QStringList{"map", "--log", office, "--model", "hpf", "--rule", "bayes", "--cell", "0.001"}
      << 2 << office + ": scan " << false;

  QTest::newRow("extra argument") << map + QStringList{"extra"} << 2
                                  << "unexpected argument 'extra'" << true;
  QTest::newRow("unknown option") << map + QStringList{"--colour"} << 2
                                  << "unexpected argument '--colour'" << true;
  QTest::newRow("--model twice") << map + QStringList{"--model", "hpf"} << 2
                                 << "--model is given 2 times" << true;
  QTest::newRow("--log twice") << map + QStringList{"--log=" + log} << 2 << "--log is given 2 times"
                               << true;
  QTest::newRow("--cell twice") << map + QStringList{"--cell", "0.1", "--cell=0.2"} << 2
                                << "--cell is given 2 times" << true;
  QTest::newRow("--scale not whole") << map + QStringList{"--png", "x.png", "--scale", "2.5"} << 2
                                     << "--scale expects a whole number, got '2.5'" << true;
  QTest::newRow("--legend without --png")
      << map + QStringList{"--legend"} << 2 << "--legend and --scale shape the PNG; give --png FILE"
      << true;
  QTest::newRow("--set twice") << map + QStringList{"--set", "epsilon=0.3", "--set", "epsilon=0.2"}
                               << 2 << "--set epsilon is given twice" << true;
  QTest::newRow("--json twice") << map + QStringList{"--json", "--json"} << 2
                                << "--json is given 2 times" << true;

  // An output that cannot be written is not the user's argument error: exit status 1.
  QTest::newRow("PNG into a missing directory")
      << map + QStringList{"--png", missingDir + "/map.png"} << 1
      << QStringLiteral("cannot write PNG '%1/map.png': directory '%1' does not exist")
             .arg(missingDir)
      << true;
  QTest::newRow("PNG into a missing directory, --json")
      << map + QStringList{"--png", missingDir + "/map.png", "--json"} << 1
      << QStringLiteral("cannot write PNG '%1/map.png': directory '%1' does not exist")
             .arg(missingDir)
      << true;
  QTest::newRow("ROS map into a missing directory")
      << map + QStringList{"--ros-map", missingDir + "/room"} << 1
      << QStringLiteral("cannot write '%1/room.pgm': directory '%1' does not exist").arg(missingDir)
      << true;
}

void TstCli::errors() {
  QFETCH(QStringList, args);
  QFETCH(int, code);
  QFETCH(QString, message);
  QFETCH(bool, exact);
  const Run r = runCli(args, tmp_.path());
  QVERIFY2(r.finished && r.status == QProcess::NormalExit, describe(args, r));
  QVERIFY2(r.code == code, describe(args, r));
  QVERIFY2(r.out.isEmpty(), describe(args, r));
  QVERIFY2(r.err.endsWith('\n') && r.err.count('\n') == 1, describe(args, r));
  const QString line = QString::fromUtf8(r.err.chopped(1));
  const QString expected = "sonargrid-cli: " + message;
  if (exact) {
    QCOMPARE(line, expected);
  } else {
    QVERIFY2(line.startsWith(expected), qPrintable(line));
  }
  QVERIFY(!QFileInfo::exists(tmp_.filePath("missing")));
}

// ---- score and goodness (issue 3's contract, docs/cli.md) ----

namespace {
const QString kRoomReference = SONARGRID_DATASETS "/room/room.json";
const QStringList kScoreKeys = {"iop_mm",
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
                                "iou",
                                "cells_evaluated"};
const QStringList kGoodnessKeys = {"vsdns",
                                   "derivative_noise",
                                   "derivative_noise_mean",
                                   "entropy_bits",
                                   "entropy_bits_mean",
                                   "entropy_bits_grid",
                                   "two_run_positive",
                                   "two_run_negative"};

QJsonObject jsonOf(const QByteArray& out) {
  return QJsonDocument::fromJson(out).object();
}
}  // namespace

void TstCli::scoreJson() {
  const QStringList args = {"score",  "--reference", kRoomReference, "--log", kRoomLog,
                            "--pose", "truth",       "--model",      "himm",  "--rule",
                            "himm",   "--cell",      "0.1",          "--json"};
  const Run r = runCli(args);
  QVERIFY2(r.finished && r.code == 0 && r.err.isEmpty(), describe(args, r));
  const QJsonObject o = jsonOf(r.out);
  QCOMPARE(sorted(o.keys()), sorted(kScoreKeys));
  // Paper 000 puts HIMM's IOP at about one 10 cm cell; any sane map of the room is within a few.
  const double iop = o["iop_mm"].toDouble();
  QVERIFY2(iop > 0 && iop < 300, qPrintable(QString::number(iop)));
  QVERIFY(count(o["cells_evaluated"]) > 0);
  for (const char* k : {"precision", "recall", "f1", "iou", "auc", "brier"}) {
    const double v = o[k].toDouble(-1);
    QVERIFY2(v >= 0 && v <= 1, k);
  }
  for (const char* k :
       {"correlation_pct", "map_score_pct", "path_false_positive_pct", "path_false_negative_pct"}) {
    QVERIFY2(o[k].isDouble() && o[k].toDouble() >= -100 && o[k].toDouble() <= 100, k);
  }
  // The same seed and pairs give the same answer.
  const Run again = runCli(args);
  QCOMPARE(again.out, r.out);
}

void TstCli::scoreMetricsSubset() {
  const QStringList args = {"score",  "--reference", kRoomReference, "--log",
                            kRoomLog, "--model",     "himm",         "--rule",
                            "himm",   "--metrics",   "iop",          "--json"};
  const Run r = runCli(args);
  QVERIFY2(r.finished && r.code == 0, describe(args, r));
  // Metrics not asked for are left out; cells_evaluated is always there (docs/cli.md).
  QCOMPARE(sorted(jsonOf(r.out).keys()), sorted(QStringList{"iop_mm", "cells_evaluated"}));
}

void TstCli::scoreBuiltMapFile() {
  // A map exported with --ros-map scores as a map file: HIMM's levels survive the round trip, so
  // the IOP from the file equals the IOP from the log (docs/metrics.md).
  const QString base = tmp_.filePath("himm-room");
  const QStringList common = {"--log",   kRoomLog, "--pose", "truth",
                              "--model", "himm",   "--rule", "himm"};
  const Run exported = runCli(QStringList{"map"} + common + QStringList{"--ros-map", base});
  QVERIFY2(exported.finished && exported.code == 0, describe({"map"}, exported));
  const Run fromLog = runCli(
      QStringList{"score", "--reference", kRoomReference, "--metrics", "iop", "--json"} + common);
  const QStringList fileArgs = {"score",        "--reference", kRoomReference, "--map",
                                base + ".yaml", "--metrics",   "iop",          "--json"};
  const Run fromFile = runCli(fileArgs);
  QVERIFY2(fromLog.code == 0 && fromFile.code == 0, describe(fileArgs, fromFile));
  QVERIFY(std::abs(jsonOf(fromLog.out)["iop_mm"].toDouble() -
                   jsonOf(fromFile.out)["iop_mm"].toDouble()) < 1e-6);
}

void TstCli::scoreErrors_data() {
  QTest::addColumn<QStringList>("args");
  QTest::addColumn<QString>("stderrStart");
  const QString bad = tmp_.filePath("bad-reference.json");
  QVERIFY(writeFile(bad,
                    "{\"format\": \"sonargrid-reference\", \"version\": 1, \"units\": \"m\",\n "
                    "\"objects\": [}\n"));
  QTest::newRow("no reference") << QStringList{"score", "--log",  kRoomLog, "--model",
                                               "himm",  "--rule", "himm"}
                                << "sonargrid-cli: missing --reference";
  QTest::newRow("neither log nor map")
      << QStringList{"score", "--reference", kRoomReference} << "sonargrid-cli: ";
  QTest::newRow("both log and map")
      << QStringList{"score",  "--reference", kRoomReference, "--log",  kRoomLog, "--map",
                     "x.yaml", "--model",     "himm",         "--rule", "himm"}
      << "sonargrid-cli: ";
  QTest::newRow("unknown metric") << QStringList{"score",  "--reference", kRoomReference, "--log",
                                                 kRoomLog, "--model",     "himm",         "--rule",
                                                 "himm",   "--metrics",   "iop,bogus"}
                                  << "sonargrid-cli: ";
  QTest::newRow("malformed reference names its line")
      << QStringList{"score",   "--reference", bad,      "--log", kRoomLog,
                     "--model", "himm",        "--rule", "himm"}
      << "sonargrid-cli: " + bad + ":2";
  QTest::newRow("missing reference file")
      << QStringList{"score", "--reference", tmp_.filePath("nope.json"),
                     "--log", kRoomLog,      "--model",
                     "himm",  "--rule",      "himm"}
      << "sonargrid-cli: " + tmp_.filePath("nope.json");
  QTest::newRow("goodness without log")
      << QStringList{"goodness", "--model", "himm", "--rule", "himm"}
      << "sonargrid-cli: missing --log";
}

void TstCli::scoreErrors() {
  QFETCH(QStringList, args);
  QFETCH(QString, stderrStart);
  const Run r = runCli(args);
  QVERIFY2(r.finished && r.status == QProcess::NormalExit, describe(args, r));
  QCOMPARE(r.code, 2);
  QVERIFY(r.out.isEmpty());
  QVERIFY2(r.err.startsWith(stderrStart.toUtf8()) && r.err.count('\n') == 1, describe(args, r));
}

void TstCli::goodnessJson() {
  const QStringList args = {"goodness",      "--log",  kRoomLog,          "--model",
                            "parameterized", "--rule", "bayes-recursive", "--json"};
  const Run r = runCli(args);
  QVERIFY2(r.finished && r.code == 0 && r.err.isEmpty(), describe(args, r));
  const QJsonObject o = jsonOf(r.out);
  QCOMPARE(sorted(o.keys()), sorted(kGoodnessKeys));
  // The model's values vary over a run, so some cell has σ > 0; σ of values in [0, 1] is at most
  // 0.5.
  QVERIFY(o["vsdns"].toDouble() > 0 && o["vsdns"].toDouble() <= 0.5);
  QVERIFY(o["derivative_noise"].toDouble() > 0);
  QVERIFY(o["two_run_positive"].isNull() && o["two_run_negative"].isNull());
}

void TstCli::goodnessTwoRuns() {
  // The same log twice: the two maps are identical, so every cell compared agrees.
  const QStringList args = {"goodness", "--log",  kRoomLog, "--second-log",    kRoomLog,
                            "--model",  "murphy", "--rule", "bayes-recursive", "--json"};
  const Run r = runCli(args);
  QVERIFY2(r.finished && r.code == 0, describe(args, r));
  const QJsonObject o = jsonOf(r.out);
  QVERIFY(count(o["two_run_positive"]) > 0);
  QCOMPARE(count(o["two_run_negative"]), qint64{0});
}

QTEST_GUILESS_MAIN(TstCli)
#include "tst_cli.moc"
