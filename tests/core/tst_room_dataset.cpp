// SPDX-License-Identifier: BSD-3-Clause
// The bundled room dataset: the generator reproduces it byte for byte, and its content is what
// datasets/README.md says it is.

#include <QtTest>
#include <cmath>

#include "sonargrid/io/sglog.h"

using namespace sg;

namespace {

const QString kRoomDir = QStringLiteral(SONARGRID_DATASETS "/room");

// 743 scans: two laps of the 8 + pi metre loop at 3 cm per scan, plus the starting pose.
constexpr std::size_t kScans = 743;

QByteArray contents(const QString& path) {
  QFile f(path);
  if (!f.open(QIODevice::ReadOnly)) return {};
  return f.readAll();
}

}  // namespace

class TstRoomDataset : public QObject {
  Q_OBJECT

 private slots:
  void generatorReproducesTheBundledFiles() {
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    const QString log = dir.filePath("room.sglog");
    const QString reference = dir.filePath("room.json");
    QProcess gen;
    gen.start(QStringLiteral(MAKE_ROOM_DATASET), {log, reference});
    QVERIFY2(gen.waitForFinished(120000), qPrintable(gen.errorString()));
    QVERIFY2(gen.exitStatus() == QProcess::NormalExit && gen.exitCode() == 0,
             gen.readAllStandardError().constData());

    const QByteArray bundled = contents(kRoomDir + "/room.sglog");
    QVERIFY2(!bundled.isEmpty(), "datasets/room/room.sglog is missing");
    const QByteArray fresh = contents(log);
    if (fresh != bundled) {
      // Name the first differing line: that says which effect or setting changed.
      const QList<QByteArray> a = fresh.split('\n');
      const QList<QByteArray> b = bundled.split('\n');
      qsizetype i = 0;
      while (i < a.size() && i < b.size() && a[i] == b[i]) ++i;
      QFAIL(
          qPrintable(QString("regenerated log differs from the bundled one at line %1:\n  %2\n  %3")
                         .arg(i + 1)
                         .arg(QString::fromUtf8(a.value(i)), QString::fromUtf8(b.value(i)))));
    }
    QCOMPARE(contents(reference), contents(kRoomDir + "/room.json"));
  }

  void bundledLogContents() {
    const Dataset d = readSglog((kRoomDir + "/room.sglog").toStdString());
    QVERIFY(d.name.starts_with("room: "));
    QCOMPARE(d.ring, SonarRing::pioneer3dx());
    QCOMPARE(d.ring.size(), std::size_t(16));
    QCOMPARE(d.scans.size(), kScans);
    QCOMPARE(d.readingCount(), kScans * 16);
    QVERIFY(d.hasTruth());

    std::size_t echoes = 0;
    for (const Scan& s : d.scans) {
      QVERIFY(s.truth.has_value());
      QCOMPARE(*s.truth, s.odometry);  // no drift yet
      // The loop keeps 1 m inside the 6 x 4 m walls.
      QVERIFY(s.truth->x() >= 1.0 - 1e-9 && s.truth->x() <= 5.0 + 1e-9);
      QVERIFY(s.truth->y() >= 1.0 - 1e-9 && s.truth->y() <= 3.0 + 1e-9);
      QCOMPARE(s.readings.size(), std::size_t(16));
      for (const Reading& r : s.readings) {
        if (!r.echo()) continue;
        ++echoes;
        QVERIFY(r.range >= d.ring.minRange && r.range < d.ring.maxRange);
      }
    }
    // Specular walls drop some readings, but most echo: 10697 of 11888 when generated.
    QVERIFY(echoes > 0);
    QVERIFY(echoes < d.readingCount());
    QVERIFY2(echoes > d.readingCount() * 8 / 10, qPrintable(QString::number(echoes)));
  }
};

QTEST_GUILESS_MAIN(TstRoomDataset)
#include "tst_room_dataset.moc"
