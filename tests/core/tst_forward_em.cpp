// SPDX-License-Identifier: BSD-3-Clause
// The forward model learned by EM (forward/forward_em.h; Thrun 2003; docs/forward-model.md).
//
// The hand-sized world: one row of cells 0.5 m wide, the transducer in cell 0 looking along the
// row, so a reading's cone is the cells 1, 2, 3 at 0.5, 1.0 and 1.5 m. Two readings of 1.0 m and
// one of 1.5 m: a door frame (cell 2) seen two times in three, the far wall (cell 3) once through
// the opening. With σ = 5 cm the Gaussians of cells half a metre apart are e⁻⁵⁰ of their peak, so
// as p_rand → 0 the log-likelihood is, by hand,
//   2 log((1 − m1) m2) + log((1 − m1)(1 − m2) m3) + const,
// whose maximum is m1 = 0, m2 = 2/3, m3 = 1: the door is open one time in three, not closed.
// An inverse model that adds evidence cell by cell marks cell 2 occupied twice and free once.

#include <QtTest>
#include <atomic>
#include <cmath>
#include <limits>
#include <vector>

#include "sonargrid/base/concurrency.h"
#include "sonargrid/forward/forward_em.h"
#include "sonargrid/io/log_reader.h"

using namespace sg;
using namespace sg::forward;

namespace {

GridSpec rowGrid() {
  GridSpec g;
  g.origin = {0.0, 0.0};
  g.cellSize = 0.5;
  g.width = 4;
  g.height = 1;
  return g;
}

ForwardBeam along(double range) {
  ForwardBeam b;
  b.sensor = Pose2D(0.25, 0.25, 0.0);
  b.range = range;
  b.maxRange = 5.0;
  return b;
}

std::vector<ForwardBeam> doorReadings() {
  return {along(1.0), along(1.0), along(1.5)};
}

ForwardSettings handSettings(double pRandom) {
  ForwardSettings s;
  s.omegaDeg = 5.0;
  s.sigma = 0.05;
  s.pRandom = pRandom;
  s.pMax = 0.1;
  s.pInit = 0.5;
  s.iterations = 500;
  return s;
}

// log p(z | m) of the door readings written out from forward_em.h's formula, for the brute force.
double handLogLikelihood(double m1, double m2, double m3, const ForwardSettings& s) {
  const double delta = 0.5, zmax = 5.0, w = 1.0 - s.pRandom - s.pMax;
  const auto n = [&](double x) {  // cut at 4σ, as the model (forward_em.h)
    if (std::abs(x) > 4.0 * s.sigma) return 0.0;
    return std::exp(-0.5 * (x / s.sigma) * (x / s.sigma)) / (s.sigma * std::sqrt(2.0 * M_PI)) /
           std::erf(4.0 / std::sqrt(2.0));
  };
  const double r = s.pRandom / zmax;
  const double at1 = delta * (r + w * (m1 * n(0.5) + (1 - m1) * m2 * n(0.0)));
  const double at15 =
      delta * (r + w * (m1 * n(1.0) + (1 - m1) * m2 * n(0.5) + (1 - m1) * (1 - m2) * m3 * n(0.0)));
  return 2.0 * std::log(at1) + std::log(at15);
}

Dataset roomLog() {
  return readLog(std::string(SONARGRID_DATASETS) + "/room/room.sglog");
}

}  // namespace

class TstForwardEm : public QObject {
  Q_OBJECT

 private slots:
  void conesAreTheCellsInDetectionOrder() {
    // Cells 1 and 2 at 0.5 and 1.0 m for a reading of 1.0 m (the cone ends at 1.0 + 4σ = 1.2 m).
    const Cones c = conesOf({along(1.0), along(Reading::kNoEcho)}, rowGrid(), handSettings(0.05));
    QCOMPARE(c.readings(), std::size_t(2));
    QCOMPARE(c.first[1], std::uint64_t(2));
    QCOMPARE(c.cell[0], 1u);
    QCOMPARE(c.cell[1], 2u);
    QCOMPARE(c.distance[1], 1.0f);
    // No echo: the whole row to 5 m, which the grid cuts at cell 3.
    QCOMPARE(c.first[2] - c.first[1], std::uint64_t(3));
    QVERIFY(std::isinf(c.range[1]));
  }

  void conesMatchAnExhaustiveSearch() {
    // Every cell of a 6 m × 5 m grid tested against the cone's definition (forward_em.h: centre
    // within reach and within ω/2 of the axis, the transducer's own point left out), sorted by
    // distance then index, against conesOf's row-by-row search and bucket sort; headings on and
    // off the axes, echoes and no echoes, the apex on a cell centre and off it.
    GridSpec g;
    g.origin = {-3.0, -2.5};
    g.cellSize = 0.05;
    g.width = 120;
    g.height = 100;
    ForwardSettings s;
    std::vector<ForwardBeam> beams;
    for (int i = 0; i < 40; ++i) {
      ForwardBeam b;
      b.sensor = Pose2D(0.013 * i - 0.2, 0.025 - 0.011 * i, -3.2 + i * (6.4 / 39.0));
      if (i % 5 == 0) b.sensor.heading = (i / 5) * M_PI / 4.0 - M_PI;  // exactly on the axes
      b.maxRange = 2.5 + 0.01 * i;
      b.range = i % 3 == 0 ? Reading::kNoEcho : 0.4 + 0.05 * i;
      beams.push_back(b);
    }
    const Cones cones = conesOf(beams, g, s);
    const double half = s.omegaDeg * M_PI / 360.0;
    for (std::size_t r = 0; r < beams.size(); ++r) {
      const ForwardBeam& b = beams[r];
      const double reach = b.echo() ? std::min(b.range + 4.0 * s.sigma, b.maxRange) : b.maxRange;
      std::vector<std::pair<float, std::uint32_t>> want;
      for (int y = 0; y < g.height; ++y)
        for (int x = 0; x < g.width; ++x) {
          const double dx = g.origin.x() + (x + 0.5) * g.cellSize - b.sensor.x();
          const double dy = g.origin.y() + (y + 0.5) * g.cellSize - b.sensor.y();
          const double d = std::sqrt(dx * dx + dy * dy);
          if (d > reach || d == 0.0) continue;
          if (dx * std::cos(b.sensor.heading) + dy * std::sin(b.sensor.heading) <
              d * std::cos(half))
            continue;
          want.emplace_back(static_cast<float>(d), static_cast<std::uint32_t>(y * g.width + x));
        }
      std::sort(want.begin(), want.end());
      QVERIFY2(want.size() > 20, qPrintable(QString("beam %1").arg(r)));
      QCOMPARE(cones.first[r + 1] - cones.first[r], std::uint64_t(want.size()));
      for (std::size_t k = 0; k < want.size(); ++k) {
        QCOMPARE(cones.cell[cones.first[r] + k], want[k].second);
        QCOMPARE(cones.distance[cones.first[r] + k], want[k].first);
      }
    }
  }

  void emFindsTheDoorOpenOneTimeInThree() {
    // As p_rand → 0 the maximum is (0, 2/3, 1), by hand (the header).
    const EmResult r = runEm(doorReadings(), rowGrid(), handSettings(1e-9));
    QVERIFY(r.converged);
    QVERIFY2(std::abs(r.occupancy[2] - 2.0 / 3.0) < 1e-3,
             qPrintable(QString::number(r.occupancy[2])));
    QVERIFY(r.occupancy[1] < 1e-6);
    QVERIFY(r.occupancy[3] > 1.0 - 1e-6);
  }

  void emMatchesABruteForceSearch() {
    // p_rand = 0.05: the maximum moves off the hand values; a search over every m on a 0.005 grid
    // of [0, 1]³ finds it, and EM's map must be at least as likely and within a grid step of it.
    const ForwardSettings s = handSettings(0.05);
    const EmResult r = runEm(doorReadings(), rowGrid(), s);
    QVERIFY(r.converged);
    double best = -1e300, b1 = 0, b2 = 0, b3 = 0;
    for (int i = 0; i <= 200; ++i)
      for (int j = 0; j <= 200; ++j)
        for (int k = 0; k <= 200; ++k) {
          const double l = handLogLikelihood(i / 200.0, j / 200.0, k / 200.0, s);
          if (l > best) best = l, b1 = i / 200.0, b2 = j / 200.0, b3 = k / 200.0;
        }
    const double em = handLogLikelihood(r.occupancy[1], r.occupancy[2], r.occupancy[3], s);
    QVERIFY2(em >= best - 1e-12, qPrintable(QString("EM %1, search %2").arg(em).arg(best)));
    QVERIFY(std::abs(r.occupancy[1] - b1) <= 0.005);
    QVERIFY(std::abs(r.occupancy[2] - b2) <= 0.005);
    QVERIFY(std::abs(r.occupancy[3] - b3) <= 0.005);
    // The trace's last value is the formula's at EM's map (the same model, written twice).
    QVERIFY(std::abs(r.logLikelihood.back() - em) < 1e-9);
  }

  void thePosteriorKeepsTheFrameAndTheWall() {
    // The posterior with the other cells at m*: cell 2 explains two readings and blocks one, so
    // its likelihood ratio is log((r + wN)/r)·2 − log((r + wN/3)/r)·1 > 0 with r = p_rand/z_max
    // and N the Gaussian's peak, and its prior log((A + 1)/(B + 1)) = log(3/2) > 0 (two expected
    // hits, one pass); cell 1 is passed by all three readings (ratio < 0, prior log(1/4)); cell 3
    // explains the one reading it meets. Cell 0 holds the transducer and is met by no cone:
    // unobserved.
    const EmResult r = runEm(doorReadings(), rowGrid(), handSettings(0.05));
    const OccupancyMap& m = r.map;
    QCOMPARE(m.observed[0], std::uint8_t(0));
    QCOMPARE(m.probability[0], 0.5);
    QCOMPARE(m.filled[1], std::uint8_t(0));
    QCOMPARE(m.filled[2], std::uint8_t(1));
    QCOMPARE(m.filled[3], std::uint8_t(1));
    QCOMPARE(m.level[1], std::uint8_t(0));
    QCOMPARE(m.model, std::string(kModelName));
  }

  void aDoorSeenThroughStaysOpen() {
    // A corridor wall with a door (docs/forward-model.md, the doorway that inverse models close):
    // 10 cm cells, the wall on row 10 (y 1.0–1.1 m) but for the door at columns 12–17 (x 1.2–1.8
    // m), a far wall on row 19. Sonars 0.25 m from the bottom, every 10 cm along x, look up
    // with the default 25° cone. Each reading is the distance of the first occupied cell its cone
    // meets (the model's own detection order, exact data): 0.75 m or so under the wall and near
    // the door frame, 1.65 m or so through the door. EM must keep the door's cells free
    // and put the wall and the far wall seen through the door on their rows.
    GridSpec g;
    g.origin = {0.0, 0.0};
    g.cellSize = 0.1;
    g.width = 30;
    g.height = 20;
    std::vector<std::uint8_t> truth(g.cellCount(), 0);
    for (int x = 0; x < g.width; ++x) {
      if (x < 12 || x > 17) truth[10 * g.width + x] = 1;
      truth[19 * g.width + x] = 1;
    }
    const ForwardSettings s;  // the defaults: 50 iterations
    std::vector<ForwardBeam> probes;
    for (int i = 0; i < 28; ++i) {
      ForwardBeam b;
      b.sensor = Pose2D(0.15 + 0.1 * i, 0.25, M_PI / 2.0);
      b.maxRange = 5.0;
      b.range = Reading::kNoEcho;
      probes.push_back(b);
    }
    const Cones whole = conesOf(probes, g, s);
    std::vector<ForwardBeam> readings;
    for (std::size_t r = 0; r < probes.size(); ++r) {
      ForwardBeam b = probes[r];
      for (std::uint64_t e = whole.first[r]; e < whole.first[r + 1]; ++e) {
        if (!truth[whole.cell[e]]) continue;
        b.range = whole.distance[e];
        break;
      }
      for (int k = 0; k < 3; ++k) readings.push_back(b);  // each reading three times
    }
    const EmResult r = runEm(readings, g, s);
    for (int x = 12; x <= 17; ++x)  // the door: free
      QVERIFY2(r.map.probability[10 * g.width + x] < 0.5, qPrintable(QString::number(x)));
    for (const int x : {0, 5, 11, 18, 24, 29})  // the wall either side, the frame: occupied
      QVERIFY2(r.map.probability[10 * g.width + x] > 0.5, qPrintable(QString::number(x)));
    for (int x = 12; x <= 17; ++x)  // the far wall, seen only through the door: occupied
      QVERIFY2(r.map.probability[19 * g.width + x] > 0.5, qPrintable(QString::number(x)));
  }

  void theLogLikelihoodNeverDecreases() {
    const Dataset data = roomLog();
    ForwardSettings s;
    s.iterations = 30;
    const GridSpec grid = data.fittingGrid(PoseSource::Odometry, 0.1);
    std::vector<double> reported;
    const EmResult r = runEm(beamsOf(data, PoseSource::Odometry), grid, s, nullptr,
                             [&](const EmProgress& p) { reported.push_back(p.logLikelihood); });
    QVERIFY(r.logLikelihood.size() >= 3);
    QCOMPARE(reported, r.logLikelihood);
    for (std::size_t i = 1; i < r.logLikelihood.size(); ++i)
      QVERIFY2(r.logLikelihood[i] >= r.logLikelihood[i - 1],
               qPrintable(QString("iteration %1: %2 after %3")
                              .arg(i)
                              .arg(r.logLikelihood[i], 0, 'g', 17)
                              .arg(r.logLikelihood[i - 1], 0, 'g', 17)));
    QCOMPARE(static_cast<std::size_t>(r.iterations) + 1, r.logLikelihood.size());
  }

  void theMapIsTheSameAtAnyThreadCount() {
    const Dataset data = roomLog();
    ForwardSettings s;
    s.iterations = 5;
    const GridSpec grid = data.fittingGrid(PoseSource::Odometry, 0.1);
    const std::vector<ForwardBeam> beams = beamsOf(data, PoseSource::Odometry);
    EmResult one;
    {
      ScopedThreadCount t(1);
      one = runEm(beams, grid, s);
    }
    for (const unsigned n : {2u, 3u, 8u}) {
      ScopedThreadCount t(n);
      const EmResult other = runEm(beams, grid, s);
      QVERIFY(other.map.probability.identical(one.map.probability));
      QCOMPARE(other.map.level, one.map.level);
      QCOMPARE(other.logLikelihood, one.logLikelihood);
    }
  }

  void thePredictionIsADistribution() {
    // One occupied cell at 1.0 m and free cells before it: the density is w N(z; 1.0,
    // σ²) (cut at 4σ and scaled to a total of 1) + p_rand / z_max, no echo has probability p_max,
    // and the density integrates to 1 − p_max (w = 1 − p_rand − p_max = 0.85).
    const ForwardSettings s = handSettings(0.05);
    const std::vector<double> occupancy{0.0, 0.0, 1.0, 0.0};
    std::vector<double> z;
    for (int i = 0; i < 5000; ++i) z.push_back((i + 0.5) * 0.001);
    const RangePrediction p = predictRange(along(1.0), rowGrid(), occupancy, s, z);
    // p_max (a failure, whatever the cone meets) and a random reading in the last 0.5 m bin.
    QCOMPARE(p.noEcho, 0.1 + 0.05 * 0.5 / 5.0);
    double integral = 0.0;
    for (const double d : p.density) integral += d * 0.001;
    QVERIFY(std::abs(integral - 0.9) < 1e-6);
    const double peak =
        0.85 / (0.05 * std::sqrt(2.0 * M_PI)) / std::erf(4.0 / std::sqrt(2.0)) + 0.05 / 5.0;
    QVERIFY(std::abs(p.density[999] - peak) < 1e-3);  // z = 0.9995
    // Every cell free: every reading is random or no echo.
    const RangePrediction none =
        predictRange(along(1.0), rowGrid(), std::vector<double>(4, 0.0), s, z);
    QCOMPARE(none.noEcho, 0.85 + 0.1 + 0.05 * 0.5 / 5.0);
  }

  void badSettingsAndCancelSayWhat() {
    ForwardSettings s = handSettings(0.05);
    s.sigma = 0.0;
    QVERIFY_THROWS_EXCEPTION(ForwardError, runEm(doorReadings(), rowGrid(), s));
    s = handSettings(1.0);
    QVERIFY_THROWS_EXCEPTION(ForwardError, runEm(doorReadings(), rowGrid(), s));
    // Beams EM cannot use, named by their index.
    for (const double maxRange : {0.0, -1.0, std::numeric_limits<double>::infinity(),
                                  std::numeric_limits<double>::quiet_NaN()}) {
      std::vector<ForwardBeam> beams = doorReadings();
      beams[2].maxRange = maxRange;
      try {
        runEm(beams, rowGrid(), handSettings(0.05));
        QFAIL("a bad maximum range was taken");
      } catch (const ForwardError& e) {
        QVERIFY2(QString(e.what()).contains("reading 2: the maximum range"), e.what());
      }
    }
    for (const double range : {-0.5, std::numeric_limits<double>::quiet_NaN()}) {
      std::vector<ForwardBeam> beams = doorReadings();
      beams[1].range = range;
      QVERIFY_THROWS_EXCEPTION(ForwardError, runEm(beams, rowGrid(), handSettings(0.05)));
    }
    std::atomic<bool> cancel{true};
    const EmResult r = runEm(doorReadings(), rowGrid(), handSettings(0.05), &cancel);
    QVERIFY(r.cancelled);
    QVERIFY(r.map.level.empty());
  }

  void parametersAreDeclaredOnce() {
    const ParameterSet p = defaultForwardParameters();
    const ForwardSettings s = settingsOf(p);
    const ForwardSettings d;
    QCOMPARE(s.omegaDeg, d.omegaDeg);
    QCOMPARE(s.sigma, d.sigma);
    QCOMPARE(s.pRandom, d.pRandom);
    QCOMPARE(s.pMax, d.pMax);
    QCOMPARE(s.iterations, d.iterations);
  }
};

QTEST_GUILESS_MAIN(TstForwardEm)
#include "tst_forward_em.moc"
