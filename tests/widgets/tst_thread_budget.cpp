// SPDX-License-Identifier: GPL-3.0-or-later
// One thread budget for every background job (issue 44, item 3): a sweep, the metrics panel, the
// cell inspector, the comparison table and a re-map started at once, with the thread policy at 2,
// never have more than 2 threads doing mapping work at a time, and the re-map is not kept waiting
// for the others. Before the budget each job's
// parallel paths took threadCount() threads for itself: 2 + 2 + 2 + 2 + 2 here.
//
// What is counted: every sensor model the registry makes is wrapped (the core's test hook,
// registry_hooks.h) in one that counts the threads inside its rasterising calls (footprints, row
// windows, evidence runs, direct paths) at the same moment, and keeps each call there a little
// longer (kHoldMicros) so that threads that overlap in time overlap in the count too, whatever
// the machine's core count. Every mapping path of every job goes through one of those calls.

#include <QSignalSpy>
#include <QtTest>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <memory>
#include <thread>

#include "cell_inspector.h"
#include "comparison_table.h"
#include "metrics_panel.h"
#include "remap_controller.h"
#include "sonargrid/base/concurrency.h"
#include "sonargrid/engine/mapper.h"
#include "sonargrid/io/sglog.h"
#include "sonargrid/testing/registry_hooks.h"
#include "sweep_view_runner.h"

using namespace sg;

namespace {

constexpr int kWaitMs = 300000;  // a bound against hangs, never a measured time
constexpr int kHoldMicros = 50;

std::atomic<int> inside{0};
std::atomic<int> mostInside{0};
std::atomic<long> calls{0};

// Counts this thread in for its scope.
struct Inside {
  Inside() {
    const int now = inside.fetch_add(1) + 1;
    int most = mostInside.load();
    while (now > most && !mostInside.compare_exchange_weak(most, now)) {
    }
    calls.fetch_add(1);
    std::this_thread::sleep_for(std::chrono::microseconds(kHoldMicros));
  }
  ~Inside() { inside.fetch_sub(1); }
  Inside(const Inside&) = delete;
  Inside& operator=(const Inside&) = delete;
};

class CountingModel final : public SensorModel {
 public:
  explicit CountingModel(std::unique_ptr<SensorModel> real) : real_(std::move(real)) {}
  const ModelInfo& info() const override { return real_->info(); }
  void configure(const ParameterSet& params) override { real_->configure(params); }
  ModelValue evaluate(double delta, double theta, double range, double maxRange) const override {
    return real_->evaluate(delta, theta, range, maxRange);
  }
  double reach(double maxRange) const override { return real_->reach(maxRange); }
  void footprint(const Beam& beam, const GridSpec& grid, const BeamTables& tables,
                 Footprint& out) const override {
    const Inside in;
    real_->footprint(beam, grid, tables, out);
  }
  void footprintRows(const Beam& beam, const GridSpec& grid, const BeamTables& tables,
                     RowWindow window, Footprint& out) const override {
    const Inside in;
    real_->footprintRows(beam, grid, tables, window, out);
  }
  bool rasterisesRows() const override { return real_->rasterisesRows(); }
  bool evidenceRuns(const Beam& beam, const GridSpec& grid, const BeamTables& tables,
                    RowWindow window, EvidenceRuns& out) const override {
    const Inside in;
    return real_->evidenceRuns(beam, grid, tables, window, out);
  }
  bool listDirect(const Beam* beams, std::size_t count, const GridSpec& grid,
                  DirectCells& out) const override {
    const Inside in;
    return real_->listDirect(beams, count, grid, out);
  }
  bool applyDirect(const DirectCells& cells, const UpdateRule& rule, Grid& grid) const override {
    const Inside in;
    return real_->applyDirect(cells, rule, grid);
  }
  bool integrateDirect(const Beam* beams, std::size_t count, const UpdateRule& rule,
                       Grid& grid) const override {
    const Inside in;
    return real_->integrateDirect(beams, count, rule, grid);
  }

 private:
  std::unique_ptr<SensorModel> real_;
};

MapperSettings settingsFor(const std::string& model, const std::string& rule) {
  MapperSettings s;
  s.model = model;
  s.rule = rule;
  s.parameters = defaultParameters(model, rule);
  return s;
}

}  // namespace

class TestThreadBudget : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() {
    testing::wrapSensorModels([](std::unique_ptr<SensorModel> real) {
      return std::unique_ptr<SensorModel>(std::make_unique<CountingModel>(std::move(real)));
    });
  }
  void cleanupTestCase() { testing::wrapSensorModels({}); }

  void fiveJobsAtOnceShareTwoThreads() {
    const ScopedThreadCount policy(2);
    // The office log: long enough (22 000 readings) that the jobs overlap for seconds.
    const auto log =
        std::make_shared<const Dataset>(readSglog(SONARGRID_DATASETS "/office/office.sglog"));
    const MapperSettings settings = settingsFor("parameterized", "bayes-recursive");
    const double cell = 0.1;
    const GridSpec grid = log->fittingGrid(settings.pose, cell);
    // The map the metrics panel scores and the comparison table's rows are mapped up front, before
    // the count starts.
    Mapper mapper(log->ring, grid, settings);
    mapper.mapDataset(*log, std::numeric_limits<double>::infinity());
    const auto map = std::make_shared<const OccupancyMap>(mapper.snapshot());
    inside = 0;
    mostInside = 0;
    calls = 0;

    ui::RemapController remap;
    ui::MetricsPanel metrics;
    ui::CellInspector inspector;
    ui::ComparisonTable comparison;
    ui::SweepRunner sweep;
    QSignalSpy mapped(&remap, &ui::RemapController::mapped);
    QSignalSpy swept(&sweep, &ui::SweepRunner::finished);
    QSignalSpy traced(&inspector, &ui::CellInspector::traced);
    QSignalSpy compared(&comparison, &ui::ComparisonTable::updated);

    // The sweep: six sets of P2 (paper 002's derivative noise needs no reference).
    auto job = std::make_shared<ui::SweepJob>();
    job->run = log;
    job->settings.model = settings.model;
    job->settings.rule = settings.rule;
    job->settings.grid = grid;
    job->metrics = {"derivative"};
    for (double p2 : {0.05, 0.1, 0.15, 0.2, 0.25, 0.3}) {
      ParameterSet set = settings.parameters;
      set.set("p2", p2);
      job->sets.push_back(set);
    }
    QVERIFY(sweep.start(job));
    remap.start(log, cell, settingsFor("konolige", "bayes-recursive"),
                std::numeric_limits<double>::infinity());
    metrics.setRuns(log, nullptr, settings, cell);  // goodness: maps the log again
    metrics.setMap(map);
    inspector.setContext(log, grid, settings);
    QVERIFY(inspector.inspectAt(log->scans[log->scans.size() / 2].odometry.position));
    comparison.setRuns(log, nullptr);
    comparison.setRows({{QStringLiteral("hpf"), settingsFor("hpf", "addition"), cell}});

    QVERIFY(swept.wait(kWaitMs));
    QVERIFY(mapped.count() > 0 || mapped.wait(kWaitMs));
    QVERIFY(metrics.waitForResult(kWaitMs));
    QVERIFY(comparison.waitForResult(kWaitMs));
    QTRY_VERIFY_WITH_TIMEOUT(!inspector.busy(), kWaitMs);

    QCOMPARE(swept.at(0).at(0).toBool(), true);  // every set done
    QCOMPARE(traced.count(), 1);
    QVERIFY(compared.count() > 0);
    qInfo("%ld rasterising calls; at most %d threads inside them at once", calls.load(),
          mostInside.load());
    QVERIFY(calls.load() > 0);
    QVERIFY2(mostInside.load() <= 2, qPrintable(QString::number(mostInside.load())));
    QCOMPARE(ThreadLease::leased(), 0u);  // every job gave its threads back
  }

  void aLeaseNeverExceedsThePolicy() {
    // The budget itself, by hand, at 3 threads (concurrency.h, ThreadLease).
    const ScopedThreadCount policy(3);
    // A lease that never gets a thread: it waits until `cancel` turns, then holds nothing.
    auto starved = [](LeaseClass c) {
      std::atomic<bool> cancel{false};
      unsigned got = 99;
      std::thread other([&] {
        const ThreadLease l(0, &cancel, c);
        got = l.threads();
      });
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      cancel = true;
      other.join();
      return got;
    };
    {
      // The re-map's class takes every thread; nobody else gets one meanwhile.
      const ThreadLease all(0, nullptr, LeaseClass::Interactive);
      QCOMPARE(all.threads(), 3u);
      QCOMPARE(parallelThreads(), 3u);
      QCOMPARE(ThreadLease::leased(), 3u);
      QCOMPARE(starved(LeaseClass::Background), 0u);
      QCOMPARE(starved(LeaseClass::Interactive), 0u);
      // Inside a lease of this thread: a share of it, nothing new from the budget.
      const ThreadLease nested(2);
      QCOMPARE(nested.threads(), 2u);
      QCOMPARE(parallelThreads(), 2u);
      QCOMPARE(ThreadLease::leased(), 3u);
    }
    QCOMPARE(ThreadLease::leased(), 0u);
    QCOMPARE(parallelThreads(), 3u);
    {
      // Background leases together keep one of the 3 for the re-map.
      const ThreadLease sweep;
      QCOMPARE(sweep.threads(), 2u);
      QCOMPARE(starved(LeaseClass::Background), 0u);
      unsigned remap = 0;
      std::thread other([&] {
        const ThreadLease l(0, nullptr, LeaseClass::Interactive);
        remap = l.threads();
      });
      other.join();
      QCOMPARE(remap, 1u);
    }
    {
      // At 1 thread there is nothing to keep: a background lease takes it.
      const ScopedThreadCount one(1);
      const ThreadLease l;
      QCOMPARE(l.threads(), 1u);
      QCOMPARE(starved(LeaseClass::Interactive), 0u);
    }
    QCOMPARE(ThreadLease::leased(), 0u);
  }
};

QTEST_MAIN(TestThreadBudget)
#include "tst_thread_budget.moc"
