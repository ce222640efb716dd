// SPDX-License-Identifier: BSD-3-Clause
// The batched sweep (core/sonargrid/sweep/batch_evaluation.h) against its oracle, one map per set
// (evaluateSet()): every field of every evaluation must be the same double, bit for bit, whatever
// the thread count and whichever batch a set falls in.

#include <QtTest>
#include <cstring>
#include <map>

#include "sonargrid/base/concurrency.h"
#include "sonargrid/engine/mapper.h"
#include "sonargrid/sim/ray_sonar.h"
#include "sonargrid/sweep/batch_evaluation.h"

using namespace sg;

namespace {

// A 4 m x 3 m room with a pillar, driven along a bend: a few hundred readings in every direction,
// echoes and no-echoes (the ring reaches 10 m, so beams that leave through the open side get none).
Dataset room(std::uint64_t seed, double shift) {
  const std::vector<Position> walls{{0, 0}, {4, 0}, {4, 3}, {0, 3}};
  const std::vector<Position> corners{{2, 1.2}, {2.3, 1.2}, {2.3, 1.5}};
  std::vector<Segment> world = polygonSegments(walls, false);
  const std::vector<Segment> pillar = polygonSegments(corners, true);
  world.insert(world.end(), pillar.begin(), pillar.end());
  std::vector<TimedPose> route;
  for (int k = 0; k < 16; ++k)
    route.push_back({k * 0.1, Pose2D(0.7 + 0.12 * k + shift, 0.8 + 0.05 * k, 0.1 * k)});
  SonarPhysics physics;
  physics.seed = seed;
  return simulateRoute(world, route, SonarRing::amigobot(), physics, "room");
}

// Thirteen sets: five of one cone (a uniform batch, padded), three of another and single sets of
// other P5, P3 and the no-echo switch (mixed batches), priors other than 0.5.
std::vector<ParameterSet> sets() {
  struct S {
    double p2, p3, p4, p5, noEcho, prior;
  };
  const S table[] = {
      {0.05, 0.25, 0.95, 15, 0, 0.5}, {0.10, 0.25, 0.96, 15, 0, 0.5},
      {0.15, 0.25, 0.97, 15, 0, 0.4}, {0.20, 0.25, 0.98, 15, 0, 0.5},
      {0.05, 0.25, 0.98, 15, 0, 0.6}, {0.05, 0.5, 0.95, 6, 0, 0.5},
      {0.20, 0.5, 0.97, 6, 0, 0.5},   {0.10, 0.5, 0.98, 6, 0, 0.5},
      {0.15, 1.5, 0.95, 40, 0, 0.5},  {0.05, 0.75, 0.96, 27, 1, 0.5},
      {0.20, 0.1, 0.98, 10, 1, 0.3},  {0.10, 1.0, 0.95, 35, 0, 0.5},
      {0.15, 0.25, 0.97, 7, 1, 0.5},
  };
  std::vector<ParameterSet> out;
  for (const S& s : table) {
    ParameterSet p = defaultParameters("parameterized", "bayes-recursive");
    p.set("p1", 1.0 - s.p4);
    p.set("p2", s.p2);
    p.set("p3", s.p3);
    p.set("p4", s.p4);
    p.set("p5", s.p5);
    p.set("no_echo", s.noEcho);
    p.set("prior", s.prior);
    out.push_back(p);
  }
  return out;
}

// The same bits (NaN included), or the same emptiness.
bool same(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}
bool same(const std::optional<double>& a, const std::optional<double>& b) {
  return a.has_value() == b.has_value() && (!a || same(*a, *b));
}

// Every field of two evaluations; the first that differs, or "".
std::string difference(const SetEvaluation& a, const SetEvaluation& b) {
  if (a.vsdns.has_value() != b.vsdns.has_value()) return "vsdns measured";
  if (a.vsdns && !same(a.vsdns->vsdns, b.vsdns->vsdns)) return "vsdns";
  if (a.vsdns && a.vsdns->cellsWithSpread != b.vsdns->cellsWithSpread) return "cellsWithSpread";
  if (a.derivative.has_value() != b.derivative.has_value()) return "derivative measured";
  if (a.derivative && !same(a.derivative->sum, b.derivative->sum)) return "derivative sum";
  if (a.derivative && !same(a.derivative->mean, b.derivative->mean)) return "derivative mean";
  if (a.derivative && a.derivative->cellsScored != b.derivative->cellsScored)
    return "derivative cells";
  if (a.entropy.has_value() != b.entropy.has_value()) return "entropy measured";
  if (a.entropy && !same(a.entropy->totalBits, b.entropy->totalBits)) return "entropy total";
  if (a.entropy && !same(a.entropy->observedBits, b.entropy->observedBits))
    return "entropy observed";
  if (a.entropy && a.entropy->cellsObserved != b.entropy->cellsObserved) return "entropy cells";
  if (a.entropy && !same(a.entropy->meanBits, b.entropy->meanBits)) return "entropy mean";
  if (a.twoRun.has_value() != b.twoRun.has_value()) return "two-run measured";
  if (a.twoRun && a.twoRun->positive != b.twoRun->positive) return "two-run positive";
  if (a.twoRun && a.twoRun->negative != b.twoRun->negative) return "two-run negative";
  return "";
}

}  // namespace

class TestBatchEvaluation : public QObject {
  Q_OBJECT

 private slots:
  // Which inputs the batched path serves (batch_evaluation.h): the parameterized model; with a
  // measure that reads the map, only with the recursive Bayes rule it implements.
  void servesTheParameterizedModel_data() {
    QTest::addColumn<QString>("model");
    QTest::addColumn<QString>("rule");
    QTest::addColumn<bool>("mapMeasure");
    QTest::addColumn<bool>("served");
    QTest::newRow("parameterized, bayes-recursive, map") << "parameterized"
                                                         << "bayes-recursive" << true << true;
    QTest::newRow("parameterized, bayes-recursive, vsdns") << "parameterized"
                                                           << "bayes-recursive" << false << true;
    // VSDNS reads the model's values only: any rule serves.
    QTest::newRow("parameterized, logodds, vsdns") << "parameterized"
                                                   << "logodds" << false << true;
    QTest::newRow("parameterized, logodds, map") << "parameterized"
                                                 << "logodds" << true << false;
    QTest::newRow("murphy, bayes-recursive, vsdns") << "murphy"
                                                    << "bayes-recursive" << false << false;
  }
  void servesTheParameterizedModel() {
    QFETCH(QString, model);
    QFETCH(QString, rule);
    QFETCH(bool, mapMeasure);
    QFETCH(bool, served);
    SetEvaluationInput in;
    in.settings.model = model.toStdString();
    in.settings.rule = rule.toStdString();
    in.measures.vsdns = true;
    in.measures.entropy = mapMeasure;
    QCOMPARE(batchEvaluable(in), served);
  }

  // Every set's evaluation from the batches equals its own map's, field for field and bit for bit,
  // at 1 and 3 threads.
  void batchesEqualOneMapPerSet_data() {
    QTest::addColumn<QString>("rule");
    QTest::addColumn<bool>("maps");  // derivative, entropy and two runs besides VSDNS
    QTest::addColumn<int>("threads");
    QTest::newRow("vsdns, 1 thread") << "bayes-recursive" << false << 1;
    QTest::newRow("vsdns, 3 threads") << "bayes-recursive" << false << 3;
    QTest::newRow("vsdns with logodds, 3 threads") << "logodds" << false << 3;
    QTest::newRow("all, 1 thread") << "bayes-recursive" << true << 1;
    QTest::newRow("all, 3 threads") << "bayes-recursive" << true << 3;
  }
  void batchesEqualOneMapPerSet() {
    QFETCH(QString, rule);
    QFETCH(bool, maps);
    QFETCH(int, threads);
    const Dataset first = room(1, 0.0);
    const Dataset second = room(2, 0.03);
    SetEvaluationInput in;
    in.run = &first;
    in.secondRun = maps ? &second : nullptr;
    in.settings.model = "parameterized";
    in.settings.rule = rule.toStdString();
    GridSpec grid = first.fittingGrid(PoseSource::Odometry, 0.05);
    in.settings.grid = grid;
    in.measures.vsdns = true;
    in.measures.derivative = maps;
    in.measures.entropy = maps;
    in.measures.twoRun = maps;
    QVERIFY(batchEvaluable(in));

    std::vector<ParameterSet> all = sets();
    if (rule != "bayes-recursive") {
      for (ParameterSet& s : all) {
        ParameterSet p = defaultParameters("parameterized", rule.toStdString());
        for (const auto& [name, value] : s.values()) {
          if (p.has(name)) p.set(name, value);
        }
        s = p;
      }
    }
    // Every set but the seventh, so that the positions passed differ from the set numbers.
    std::vector<std::size_t> indices;
    for (std::size_t i = 0; i < all.size(); ++i) {
      if (i != 6) indices.push_back(i);
    }
    std::map<std::size_t, SetEvaluation> batched;
    {
      const ScopedThreadCount count(static_cast<unsigned>(threads));
      const bool done = evaluateSets(in, all, indices, [&](std::size_t k, const SetEvaluation& e) {
        QVERIFY(batched.emplace(k, e).second);  // each position once
      });
      QVERIFY(done);
    }
    QCOMPARE(batched.size(), indices.size());
    std::size_t spread = 0;
    for (const auto& [k, e] : batched) {
      const std::optional<SetEvaluation> oracle = evaluateSet(in, all[indices[k]]);
      QVERIFY(oracle);
      const std::string diff = difference(e, *oracle);
      QVERIFY2(diff.empty(), ("set " + std::to_string(indices[k]) + ": " + diff).c_str());
      // Not a vacuous comparison: the maps have cells whose values varied.
      QVERIFY(e.vsdns && e.vsdns->vsdns);
      spread += e.vsdns->cellsWithSpread;
      if (maps) QVERIFY(e.twoRun->positive > 0);
    }
    QVERIFY(spread > 1000);
  }

  // A cancel flag set before the start stops the batches before any set is finished.
  void cancelStopsTheBatches() {
    const Dataset run = room(1, 0.0);
    SetEvaluationInput in;
    in.run = &run;
    in.settings.model = "parameterized";
    in.settings.rule = "bayes-recursive";
    in.settings.grid = run.fittingGrid(PoseSource::Odometry, 0.05);
    in.measures.vsdns = true;
    const std::vector<ParameterSet> all = sets();
    std::vector<std::size_t> indices(all.size());
    for (std::size_t i = 0; i < indices.size(); ++i) indices[i] = i;
    std::atomic<bool> cancel{true};
    std::size_t finished = 0;
    QVERIFY(!evaluateSetsBatched(
        in, all, indices, [&](std::size_t, const SetEvaluation&) { ++finished; }, &cancel));
    QCOMPARE(finished, std::size_t(0));
  }
};

QTEST_APPLESS_MAIN(TestBatchEvaluation)
#include "tst_batch_evaluation.moc"
