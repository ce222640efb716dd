// SPDX-License-Identifier: BSD-3-Clause
// One grid per reading set (issue 50, item 3): the same readings read from a .sglog, from a CARMEN
// log and from a Player log, each written with its logger's own format strings
// (writer_fixtures.h), load as the same readings and so give the same grid, cell for cell and bit
// for bit. The grid is decided in one place from the readings and the ring
// (Dataset::fittingGrid); a reader that loaded a reading differently would show here.

#include <QtTest>
#include <cmath>
#include <cstring>
#include <string>

#include "sonargrid/engine/mapper.h"
#include "sonargrid/io/log_reader.h"
#include "sonargrid/io/sglog.h"
#include "writer_fixtures.h"

namespace {

double rounded(double v, int decimals) {
  const double scale = std::pow(10.0, decimals);
  return std::round(v * scale) / scale;  // an integer over a power of ten: the decimal's double
}

// The room log with every number cut to the decimals the coarsest format prints: 2 for ranges
// (CARMEN's "%.2lf"), 3 for poses, headings and mount positions (Player's "%+07.3f", "%+04.3f"),
// 4 for mount headings (Player's "%+07.4f"), 6 for the cone (CARMEN's "%f"), 3 for times
// (Player's "%014.3f"). Readings take their scan's time, as in a CARMEN or Player scan.
sg::Dataset roomAtFormatPrecision() {
  sg::Dataset d = sg::readSglog(SONARGRID_DATASETS "/room/room.sglog");
  d.ring.apertureRad = rounded(d.ring.apertureRad, 6);
  for (sg::SonarMount& m : d.ring.sonars)
    m.pose = sg::Pose2D(rounded(m.pose.x(), 3), rounded(m.pose.y(), 3), rounded(m.pose.heading, 4));
  for (sg::Scan& s : d.scans) {
    s.time = rounded(s.time, 3);
    s.odometry = sg::Pose2D(rounded(s.odometry.x(), 3), rounded(s.odometry.y(), 3),
                            rounded(s.odometry.heading, 3));
    if (s.truth)
      s.truth = sg::Pose2D(rounded(s.truth->x(), 3), rounded(s.truth->y(), 3),
                           rounded(s.truth->heading, 3));
    for (sg::Reading& r : s.readings) {
      r.time = s.time;
      if (r.echo()) r.range = rounded(r.range, 2);
      if (r.range >= d.ring.maxRange) r.range = sg::Reading::kNoEcho;
    }
  }
  return d;
}

sg::OccupancyMap mapOf(const sg::Dataset& d, const sg::GridSpec& grid) {
  sg::MapperSettings settings;  // HPF and addition, the defaults; odometry poses
  sg::Mapper m(d.ring, grid, settings);
  m.mapDataset(d);
  return m.snapshot();
}

template <typename T>
QByteArray bytesOf(const std::vector<T>& v) {
  return QByteArray(reinterpret_cast<const char*>(v.data()),
                    static_cast<qsizetype>(v.size() * sizeof(T)));
}

}  // namespace

class TstFormatGrids : public QObject {
  Q_OBJECT

 private slots:
  void theSameReadingsGiveTheSameGridInEveryFormat_data() {
    QTest::addColumn<QString>("format");
    QTest::newRow("carmen") << "carmen";
    QTest::newRow("player") << "player";
  }

  void theSameReadingsGiveTheSameGridInEveryFormat() {
    QFETCH(QString, format);
    const sg::Dataset want = roomAtFormatPrecision();
    std::ostringstream sglogText;
    sg::writeSglog(want, sglogText);
    const sg::Dataset sglog = sg::parseLog(sglogText.str(), "room.sglog", {});
    QVERIFY(sglog == want);

    sg::LogOptions options;
    std::string text;
    if (format == "carmen") {
      text = writer_fixtures::carmenLogOf(want);
    } else {
      text = writer_fixtures::playerSonarLogOf(want);
      options.ring = want.ring;  // Player logs no cone or range limits: --robot lends them
    }
    sg::LoadReport report;
    const sg::Dataset got = sg::parseLog(text, "room." + format.toStdString(), options, &report);
    QCOMPARE(got.scans.size(), want.scans.size());
    QCOMPARE(got.ring.apertureRad, want.ring.apertureRad);
    QCOMPARE(got.ring.maxRange, want.ring.maxRange);
    QCOMPARE(got.ring.sonars, want.ring.sonars);
    for (std::size_t i = 0; i < want.scans.size(); ++i) {
      QCOMPARE(got.scans[i].time, want.scans[i].time);
      QCOMPARE(got.scans[i].odometry, want.scans[i].odometry);
      QCOMPARE(got.scans[i].readings, want.scans[i].readings);
    }
    // One grid: the same size and origin, and the same bits in it.
    const sg::GridSpec grid = sglog.fittingGrid(sg::PoseSource::Odometry, 0.05);
    const sg::GridSpec own = got.fittingGrid(sg::PoseSource::Odometry, 0.05);
    QCOMPARE(own.width, grid.width);
    QCOMPARE(own.height, grid.height);
    QCOMPARE(own.origin, grid.origin);
    const sg::OccupancyMap a = mapOf(sglog, grid);
    const sg::OccupancyMap b = mapOf(got, own);
    QVERIFY(a.filledCount() > 0);
    QCOMPARE(bytesOf(b.probability.values()), bytesOf(a.probability.values()));
    QCOMPARE(bytesOf(b.level), bytesOf(a.level));
    QCOMPARE(bytesOf(b.observed), bytesOf(a.observed));
  }
};

QTEST_GUILESS_MAIN(TstFormatGrids)
#include "tst_format_grids.moc"
