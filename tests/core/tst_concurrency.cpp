// SPDX-License-Identifier: BSD-3-Clause
// The thread policy (core/sonargrid/base/concurrency.h): which count wins, how SONARGRID_THREADS is
// read, that the default is the affinity mask's CPU count; and that every parallel path reports a
// failure on any of its threads to the caller, never hanging and never ending in std::terminate.
// Failures are injected by wrapping the real model or rule (sonargrid/testing/registry_hooks.h) in
// one that throws after some calls on a thread other than the test's, and by making a thread start
// fail (testing::failThreadStartAfter). Each run is watched: a hang aborts the suite (so CI fails)
// instead of blocking it.

#include <sched.h>

#include <QtTest>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <set>
#include <stdexcept>
#include <system_error>
#include <thread>

#include "sonargrid/base/concurrency.h"
#include "sonargrid/engine/beam_tables.h"
#include "sonargrid/engine/mapper.h"
#include "sonargrid/engine/row_bands.h"
#include "sonargrid/io/sglog.h"
#include "sonargrid/sweep/parameter_sweep.h"
#include "sonargrid/testing/registry_hooks.h"

using namespace sg;

namespace {

// Aborts the process when the scope it guards is still running after `limit`: a hung parallel
// path then fails the suite with a message instead of blocking CI until ctest's timeout. Generous,
// as the ThreadSanitizer build runs the suite ten or more times slower.
class Watchdog {
 public:
  explicit Watchdog(QByteArray what, std::chrono::seconds limit = std::chrono::seconds(120))
      : what_(std::move(what)), thread_([this, limit] {
          std::unique_lock lock(mutex_);
          if (!done_.wait_for(lock, limit, [this] { return finished_; })) {
            std::fprintf(stderr, "FAIL: '%s' still running after %lld s: a parallel path hung\n",
                         what_.constData(), static_cast<long long>(limit.count()));
            std::fflush(stderr);
            std::abort();
          }
        }) {}
  ~Watchdog() {
    {
      const std::lock_guard lock(mutex_);
      finished_ = true;
    }
    done_.notify_one();
    thread_.join();
  }
  Watchdog(const Watchdog&) = delete;
  Watchdog& operator=(const Watchdog&) = delete;

 private:
  QByteArray what_;
  std::mutex mutex_;
  std::condition_variable done_;
  bool finished_ = false;
  std::thread thread_;
};

// Where and when an injected failure happens. `after` calls on the chosen side succeed; the next
// throws. Calls on the other side never throw.
struct Fault {
  std::thread::id caller = std::this_thread::get_id();
  bool onCaller = false;  // the test's own thread rather than a worker
  bool runs = true;       // the model hands its rows over as runs (as every cone model does)
  int after = 200;
  std::atomic<bool> armed{true};
  std::atomic<int> calls{0};
  std::atomic<int> callerCalls{0};
  std::atomic<bool> thrown{false};

  void maybeThrow(const char* what) {
    if (!armed.load()) return;
    const bool onCallerThread = std::this_thread::get_id() == caller;
    // The caller's first calls are slowed down, so that workers certainly get some of the work
    // wherever the caller could take it from them (the pipeline computes ahead when it can).
    if (onCallerThread && callerCalls.fetch_add(1) < 4)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    if (onCallerThread != onCaller) return;
    if (calls.fetch_add(1) >= after) {
      // Slow to fail, as a real failure may be: by now the other threads wait on this one (the
      // pipeline's applying thread for this footprint's slot), and must be woken.
      std::this_thread::sleep_for(std::chrono::milliseconds(30));
      thrown.store(true);
      throw std::runtime_error(std::string("injected ") + what + " failure");
    }
  }
};

class FaultyModel final : public SensorModel {
 public:
  FaultyModel(std::unique_ptr<SensorModel> real, Fault& fault)
      : real_(std::move(real)), fault_(fault) {}
  const ModelInfo& info() const override { return real_->info(); }
  void configure(const ParameterSet& params) override { real_->configure(params); }
  ModelValue evaluate(double delta, double theta, double range, double maxRange) const override {
    return real_->evaluate(delta, theta, range, maxRange);
  }
  double reach(double maxRange) const override { return real_->reach(maxRange); }
  void footprint(const Beam& beam, const GridSpec& grid, const BeamTables& tables,
                 Footprint& out) const override {
    fault_.maybeThrow("model");
    real_->footprint(beam, grid, tables, out);
  }
  void footprintRows(const Beam& beam, const GridSpec& grid, const BeamTables& tables,
                     RowWindow window, Footprint& out) const override {
    fault_.maybeThrow("model");
    real_->footprintRows(beam, grid, tables, window, out);
  }
  bool rasterisesRows() const override { return real_->rasterisesRows(); }
  bool evidenceRuns(const Beam& beam, const GridSpec& grid, const BeamTables& tables,
                    RowWindow window, EvidenceRuns& out) const override {
    if (!fault_.runs) return false;
    fault_.maybeThrow("model");
    return real_->evidenceRuns(beam, grid, tables, window, out);
  }

 private:
  std::unique_ptr<SensorModel> real_;
  Fault& fault_;
};

class FaultyRule final : public UpdateRule {
 public:
  FaultyRule(std::unique_ptr<UpdateRule> real, Fault& fault)
      : real_(std::move(real)), fault_(fault) {}
  const RuleInfo& info() const override { return real_->info(); }
  void configure(const ParameterSet& params) override { real_->configure(params); }
  CellLayout layout() const override { return real_->layout(); }
  void apply(const Footprint& footprint, Grid& grid) const override {
    fault_.maybeThrow("rule");
    real_->apply(footprint, grid);
  }
  bool needsTotals() const override { return real_->needsTotals(); }
  void applyPart(const Footprint& part, const FootprintTotals& totals, Grid& grid) const override {
    fault_.maybeThrow("rule");
    real_->applyPart(part, totals, grid);
  }
  double occupancy(const Grid& grid, std::size_t cell) const override {
    return real_->occupancy(grid, cell);
  }
  double native(const Grid& grid, std::size_t cell) const override {
    return real_->native(grid, cell);
  }
  bool filled(const Grid& grid, std::size_t cell) const override {
    return real_->filled(grid, cell);
  }
  std::uint8_t level(const Grid& grid, std::size_t cell) const override {
    return real_->level(grid, cell);
  }
  double evidence(const Grid& grid, std::size_t cell) const override {
    return real_->evidence(grid, cell);
  }
  void writeLevels(const Grid& grid, std::uint8_t* level, std::size_t begin,
                   std::size_t end) const override {
    fault_.maybeThrow("rule");
    real_->writeLevels(grid, level, begin, end);
  }
  void writeLayer(const Grid& grid, DerivedLayer layer, std::size_t begin, std::size_t end,
                  void* out) const override {
    real_->writeLayer(grid, layer, begin, end, out);
  }

 private:
  std::unique_ptr<UpdateRule> real_;
  Fault& fault_;
};

// Wraps every model (or rule) the registry makes while it lives.
struct ModelsFail {
  explicit ModelsFail(Fault& fault) {
    testing::wrapSensorModels([&fault](std::unique_ptr<SensorModel> real) {
      return std::unique_ptr<SensorModel>(std::make_unique<FaultyModel>(std::move(real), fault));
    });
  }
  ~ModelsFail() { testing::wrapSensorModels({}); }
};
struct RulesFail {
  explicit RulesFail(Fault& fault) {
    testing::wrapUpdateRules([&fault](std::unique_ptr<UpdateRule> real) {
      return std::unique_ptr<UpdateRule>(std::make_unique<FaultyRule>(std::move(real), fault));
    });
  }
  ~RulesFail() { testing::wrapUpdateRules({}); }
};

// Makes the next thread start but `succeed` fail while it lives.
struct StartFails {
  explicit StartFails(int succeed) { testing::failThreadStartAfter(succeed); }
  ~StartFails() { testing::failThreadStartAfter(-1); }
};

// The bundled room log: 11 888 readings, above the mapper's threshold for threads (4096).
const Dataset& room() {
  static const Dataset d = readSglog(SONARGRID_DATASETS "/room/room.sglog");
  return d;
}

bool sameLayers(const OccupancyMap& a, const OccupancyMap& b) {
  return a.spec == b.spec && a.level == b.level && a.filled == b.filled &&
         a.observed == b.observed && a.probability.identical(b.probability) &&
         a.native.identical(b.native) && a.evidence.identical(b.evidence);
}

// Sees every footprint: makes the mapper use its ordered pipeline.
struct CountingObserver final : FootprintObserver {
  std::size_t seen = 0;
  void reset(std::size_t) override { seen = 0; }
  void observe(const Footprint&) override { ++seen; }
};

class EnvironmentVariable {
 public:
  EnvironmentVariable() : had_(qEnvironmentVariableIsSet(kThreadsVariable)) {
    if (had_) saved_ = qgetenv(kThreadsVariable);
  }
  ~EnvironmentVariable() {
    if (had_)
      qputenv(kThreadsVariable, saved_);
    else
      qunsetenv(kThreadsVariable);
  }
  EnvironmentVariable(const EnvironmentVariable&) = delete;
  EnvironmentVariable& operator=(const EnvironmentVariable&) = delete;

 private:
  bool had_;
  QByteArray saved_;
};

int cpuCountOfMask() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) != 0) return -1;
  return CPU_COUNT(&set);
}

}  // namespace

class TstConcurrency : public QObject {
  Q_OBJECT

 private slots:
  void init();
  void cleanup();

  void precedence_data();
  void precedence();
  void environmentValues_data();
  void environmentValues();
  void affinityIsTheDefault();

  void runParallelRunsEveryIndexOnce_data();
  void runParallelRunsEveryIndexOnce();
  void workerFailureStopsTheOthers();
  void startFailureStopsTheStarted_data();
  void startFailureStopsTheStarted();
  void nestedRunsUseOneThread();

  void balancedBandsSplitTheWork_data();
  void balancedBandsSplitTheWork();
  void estimatedRowWorkSpreadsEachBeam();

  void failureReachesTheCaller_data();
  void failureReachesTheCaller();
  void sameGridAfterAFailure_data();
  void sameGridAfterAFailure();

 private:
  EnvironmentVariable environment_;
};

void TstConcurrency::init() {
  qunsetenv(kThreadsVariable);
  setThreadCount(0);
}

void TstConcurrency::cleanup() {
  setThreadCount(0);
  testing::failThreadStartAfter(-1);
  testing::wrapSensorModels({});
  testing::wrapUpdateRules({});
}

void TstConcurrency::precedence_data() {
  QTest::addColumn<int>("explicitCount");       // 0: none
  QTest::addColumn<QByteArray>("environment");  // empty: unset
  QTest::addColumn<int>("expected");            // -1: the affinity mask's count
  QTest::newRow("nothing set: affinity") << 0 << QByteArray() << -1;
  QTest::newRow("environment beats affinity") << 0 << QByteArray("3") << 3;
  QTest::newRow("explicit beats environment") << 5 << QByteArray("3") << 5;
  QTest::newRow("explicit alone") << 2 << QByteArray() << 2;
  QTest::newRow("explicit beyond the CPUs") << 8 << QByteArray() << 8;
  // A bad value is the front end's to report (environmentValues); the core passes it over.
  QTest::newRow("bad environment: affinity") << 0 << QByteArray("lots") << -1;
  QTest::newRow("bad environment under explicit") << 4 << QByteArray("0") << 4;
}

void TstConcurrency::precedence() {
  QFETCH(int, explicitCount);
  QFETCH(QByteArray, environment);
  QFETCH(int, expected);
  if (!environment.isEmpty()) qputenv(kThreadsVariable, environment);
  setThreadCount(static_cast<unsigned>(explicitCount));
  const unsigned want = expected < 0 ? affinityThreadCount() : static_cast<unsigned>(expected);
  QCOMPARE(threadCount(), want);
  QCOMPARE(parallelThreads(), want);
  QCOMPARE(explicitThreadCount(), static_cast<unsigned>(explicitCount));
  {
    // A scoped count wins for its scope, then the one before is back.
    const ScopedThreadCount scoped(7);
    QCOMPARE(threadCount(), 7u);
  }
  QCOMPARE(threadCount(), want);
}

void TstConcurrency::environmentValues_data() {
  QTest::addColumn<QByteArray>("value");
  QTest::addColumn<int>("expected");  // 0: unset (nullopt), -1: refused with ThreadCountError
  QTest::newRow("1") << QByteArray("1") << 1;
  QTest::newRow("4") << QByteArray("4") << 4;
  QTest::newRow("the maximum, 1024") << QByteArray("1024") << 1024;
  QTest::newRow("empty: unset") << QByteArray("") << 0;
  QTest::newRow("zero") << QByteArray("0") << -1;
  QTest::newRow("negative") << QByteArray("-2") << -1;
  QTest::newRow("plus sign") << QByteArray("+3") << -1;
  QTest::newRow("leading space") << QByteArray(" 3") << -1;
  QTest::newRow("trailing space") << QByteArray("3 ") << -1;
  QTest::newRow("decimal") << QByteArray("3.0") << -1;
  QTest::newRow("word") << QByteArray("auto") << -1;
  QTest::newRow("above the maximum") << QByteArray("1025") << -1;
  QTest::newRow("beyond 32 bits") << QByteArray("99999999999") << -1;
}

void TstConcurrency::environmentValues() {
  QFETCH(QByteArray, value);
  QFETCH(int, expected);
  qputenv(kThreadsVariable, value);
  if (expected >= 0) {
    const std::optional<unsigned> got = environmentThreadCount();
    QCOMPARE(got.has_value(), expected > 0);
    if (got) QCOMPARE(*got, static_cast<unsigned>(expected));
    return;
  }
  try {
    environmentThreadCount();
    QFAIL("a bad SONARGRID_THREADS was accepted");
  } catch (const ThreadCountError& e) {
    // The message names the variable and quotes the value, so the user can find and fix it.
    const QString message = QString::fromUtf8(e.what());
    QVERIFY2(message.contains("SONARGRID_THREADS"), e.what());
    QVERIFY2(message.contains("'" + QString::fromUtf8(value) + "'"), e.what());
  }
}

void TstConcurrency::affinityIsTheDefault() {
  // The default is CPU_COUNT of this thread's affinity mask (what taskset or Slurm grant), and
  // follows it when the mask is narrowed to one CPU.
  const int cpus = cpuCountOfMask();
  QVERIFY(cpus > 0);
  QCOMPARE(affinityThreadCount(), static_cast<unsigned>(cpus));
  QCOMPARE(threadCount(), static_cast<unsigned>(cpus));

  cpu_set_t original;
  CPU_ZERO(&original);
  QCOMPARE(sched_getaffinity(0, sizeof original, &original), 0);
  int first = 0;
  while (!CPU_ISSET(first, &original)) ++first;
  cpu_set_t one;
  CPU_ZERO(&one);
  CPU_SET(first, &one);
  QCOMPARE(sched_setaffinity(0, sizeof one, &one), 0);
  const unsigned narrowed = affinityThreadCount();
  const unsigned policy = threadCount();
  QCOMPARE(sched_setaffinity(0, sizeof original, &original), 0);
  QCOMPARE(narrowed, 1u);
  QCOMPARE(policy, 1u);
  QCOMPARE(affinityThreadCount(), static_cast<unsigned>(cpus));
}

void TstConcurrency::runParallelRunsEveryIndexOnce_data() {
  QTest::addColumn<unsigned>("count");
  QTest::newRow("0 counts as 1") << 0u;
  QTest::newRow("1") << 1u;
  QTest::newRow("2") << 2u;
  QTest::newRow("8") << 8u;
}

void TstConcurrency::runParallelRunsEveryIndexOnce() {
  QFETCH(unsigned, count);
  const unsigned expected = std::max(count, 1u);
  std::mutex mutex;
  std::vector<int> runs(expected, 0);
  std::set<std::thread::id> threads;
  std::thread::id ranZero;
  const Watchdog watchdog(QTest::currentDataTag());
  runParallel(count, [&](unsigned k) {
    const std::lock_guard lock(mutex);
    ++runs[k];
    threads.insert(std::this_thread::get_id());
    if (k == 0) ranZero = std::this_thread::get_id();
  });
  QCOMPARE(runs, std::vector<int>(expected, 1));
  QCOMPARE(threads.size(), std::size_t{expected});  // each on its own thread
  QCOMPARE(ranZero, std::this_thread::get_id());    // work(0) on the caller's
}

void TstConcurrency::workerFailureStopsTheOthers() {
  // Worker 2 of 4 throws; the others wait until they are told to stop (as the mapper's threads
  // wait for each other) and must all be woken, joined, and the error rethrown here.
  std::atomic<bool> stop{false};
  std::atomic<int> stops{0};
  std::atomic<int> returned{0};
  const Watchdog watchdog("workerFailureStopsTheOthers");
  try {
    runParallel(
        4,
        [&](unsigned k) {
          if (k == 2) {
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
            throw std::runtime_error("worker 2 failed");
          }
          while (!stop.load()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
          ++returned;
        },
        [&] {
          ++stops;
          stop.store(true);
        });
    QFAIL("the worker's exception was not rethrown");
  } catch (const std::runtime_error& e) {
    QCOMPARE(QByteArray(e.what()), QByteArray("worker 2 failed"));
  }
  QCOMPARE(stops.load(), 1);
  QCOMPARE(returned.load(), 3);
}

void TstConcurrency::startFailureStopsTheStarted_data() {
  QTest::addColumn<int>("succeed");
  QTest::newRow("first start fails") << 0;
  QTest::newRow("second start fails") << 1;
  QTest::newRow("third start fails") << 2;
}

void TstConcurrency::startFailureStopsTheStarted() {
  // Four threads asked for, the (succeed + 1)-th start fails: the ones started wait for the stop
  // call, work(0) never runs on the caller, and std::system_error reaches the caller.
  QFETCH(int, succeed);
  std::atomic<bool> stop{false};
  std::atomic<int> ran{0};
  std::atomic<bool> ranZero{false};
  const StartFails fails(succeed);
  const Watchdog watchdog(QTest::currentDataTag());
  try {
    runParallel(
        4,
        [&](unsigned k) {
          if (k == 0) ranZero.store(true);
          ++ran;
          while (!stop.load()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
        },
        [&] { stop.store(true); });
    QFAIL("the failed start was not reported");
  } catch (const std::system_error& e) {
    QCOMPARE(e.code(), std::make_error_code(std::errc::resource_unavailable_try_again));
  }
  QCOMPARE(ran.load(), succeed);
  QVERIFY(!ranZero.load());
  // The hook fires once: the next run starts all its threads.
  std::atomic<int> again{0};
  runParallel(4, [&](unsigned) { ++again; });
  QCOMPARE(again.load(), 4);
}

void TstConcurrency::balancedBandsSplitTheWork_data() {
  // Band k ends at the first row where the work before it plus half its own reaches (k + 1) /
  // count of the total (row_bands.h); the ends below are worked out by hand from that rule.
  QTest::addColumn<QList<double>>("work");
  QTest::addColumn<int>("count");
  QTest::addColumn<QList<int>>("ends");
  // Total 8, target 4: rows 0-3 reach 0.5, 1.5, 2.5, 3.5 with their halves; row 4 reaches 4.5.
  QTest::newRow("even work, halves")
      << QList<double>{1, 1, 1, 1, 1, 1, 1, 1} << 2 << QList<int>{4, 8};
  // Target 4: row 0 reaches 2 with its half, then row 1 already 4 + 0.
  QTest::newRow("work at both ends")
      << QList<double>{4, 0, 0, 0, 0, 0, 0, 4} << 2 << QList<int>{1, 8};
  // Target 4: rows 0, 1 reach 0, row 2 reaches 3 with its half (< 4), row 3 then 6.
  QTest::newRow("one heavy row") << QList<double>{0, 0, 6, 0, 0, 2} << 2 << QList<int>{3, 6};
  // Targets 4 and 8 of 12: with their halves rows 0-2 reach 1, 3, 5 and rows 2-4 5, 7, 9.
  QTest::newRow("three bands") << QList<double>{2, 2, 2, 2, 2, 2} << 3 << QList<int>{2, 4, 6};
  // No work at all: the rows shared out evenly, 5 · 1/3 and 5 · 2/3 rounded down.
  QTest::newRow("no work") << QList<double>{0, 0, 0, 0, 0} << 3 << QList<int>{1, 3, 5};
  // More bands than rows: a band may be empty, and the rows are still all covered once.
  QTest::newRow("more bands than rows") << QList<double>{1, 1} << 3 << QList<int>{1, 1, 2};
  QTest::newRow("one band") << QList<double>{3, 0, 1} << 1 << QList<int>{3};
}

void TstConcurrency::balancedBandsSplitTheWork() {
  QFETCH(QList<double>, work);
  QFETCH(int, count);
  QFETCH(QList<int>, ends);
  const std::vector<double> rows(work.begin(), work.end());
  const std::vector<RowWindow> bands = balancedBands(rows, static_cast<unsigned>(count));
  QCOMPARE(static_cast<int>(bands.size()), count);
  int begin = 0;
  for (int k = 0; k < count; ++k) {
    // Consecutive and in order.
    QCOMPARE(bands[k].begin, begin);
    QCOMPARE(bands[k].end, ends[k]);
    begin = bands[k].end;
  }
  QCOMPARE(begin, static_cast<int>(rows.size()));
}

void TstConcurrency::estimatedRowWorkSpreadsEachBeam() {
  // Ten rows of 1 m from y = 0. A beam spreads r² (r in cells) over the grid's rows within r of
  // its sensor: from floor(y − r) to floor(y + r), clamped to the grid.
  GridSpec grid;
  grid.cellSize = 1.0;
  grid.width = 4;
  grid.height = 10;
  auto beam = [](double y, double range) {
    Beam b;
    b.sensor = Pose2D(1.0, y, 0.0);
    b.range = range;
    b.maxRange = 5.0;
    return b;
  };
  static_assert(kEstimateStride == 4, "the beams below are laid out for a stride of 4");
  std::vector<Beam> beams(13, beam(4.5, 1.0));  // only 0, 4, 8 and 12 are looked at
  beams[0] = beam(4.5, 2.0);                    // rows floor(2.5) = 2 to floor(6.5) = 6: 4 / 5 each
  beams[4] = beam(0.5, 2.0);                    // rows 0 (from −2, clamped) to 2: 4 / 3 each
  beams[8] = beam(4.5, Reading::kNoEcho);  // no echo: 5 m, capped at 3 m: rows 1 to 7, 9 / 7 each
  beams[12] = beam(-10.0, 2.0);            // rows −12 to −8: none in the grid, nothing
  const std::vector<double> without = estimatedRowWork(beams, grid, 3.0, false);
  const std::vector<double> with = estimatedRowWork(beams, grid, 3.0, true);
  const double expectedWithout[10] = {4.0 / 3, 4.0 / 3, 4.0 / 3 + 0.8, 0.8, 0.8, 0.8, 0.8, 0, 0, 0};
  QCOMPARE(static_cast<int>(without.size()), 10);
  QCOMPARE(static_cast<int>(with.size()), 10);
  for (int row = 0; row < 10; ++row) {
    QVERIFY2(std::abs(without[row] - expectedWithout[row]) < 1e-12,
             qPrintable(QString::number(row)));
    const double noEcho = row >= 1 && row <= 7 ? 9.0 / 7 : 0.0;
    QVERIFY2(std::abs(with[row] - expectedWithout[row] - noEcho) < 1e-12,
             qPrintable(QString::number(row)));
  }
}

void TstConcurrency::nestedRunsUseOneThread() {
  // Inside a run's work (a sweep's set), parallel paths use one thread: the outer run already
  // occupies the CPUs. Outside, the policy's count again.
  const ScopedThreadCount threads(3);
  std::atomic<int> nestedCounts{0};
  runParallel(3, [&](unsigned) { nestedCounts += static_cast<int>(parallelThreads()); });
  QCOMPARE(nestedCounts.load(), 3);
  QCOMPARE(parallelThreads(), 3u);
}

// Every parallel path, every kind of failure. Paths: the mapper's bands of rows (hpf × bayes), and
// with a model that gives no runs (footprints of the band's rows), its bands in two passes for
// footprint totals (hpf × addition, which normalises; with a model that gives no runs, on the
// caller's thread alone), its ordered pipeline (with an observer; and himm × himm, whose model
// does not rasterise rows), the snapshot's layers on a grid of 200 000 cells, the beam tables'
// fill, and the parameter sweep.
// Failures: the model or the rule throws on a worker after 200 calls there (the rule of the
// pipeline applies only on the caller's thread: there it throws on the caller, with workers
// waiting on it), or the first or second thread start fails.
void TstConcurrency::failureReachesTheCaller_data() {
  QTest::addColumn<QString>("path");
  QTest::addColumn<QString>("failure");
  QTest::addColumn<unsigned>("threads");
  struct Row {
    const char* path;
    std::vector<const char*> failures;
  };
  const std::vector<Row> rows{
      {"bands", {"model on worker", "rule on worker", "start 1", "start 2"}},
      {"bands without runs", {"model on worker", "rule on worker"}},
      {"totals", {"model on worker", "rule on worker", "start 1", "start 2"}},
      // Normalising addition with a model that gives no runs is mapped on the calling thread.
      {"totals without runs", {"model on caller", "rule on caller"}},
      {"pipeline observer", {"model on worker", "rule on caller", "start 1", "start 2"}},
      // HIMM's axis model does not rasterise by rows: the mapper maps it on the calling thread
      // (its beams are still placed on several).
      {"himm on one thread", {"model on caller", "rule on caller", "start 1", "start 2"}},
      {"snapshot", {"rule on worker", "start 1", "start 2"}},
      {"beam tables", {"start 1", "start 2"}},
      {"sweep", {"model on worker", "rule on worker", "start 1", "start 2"}},
  };
  for (const Row& r : rows) {
    for (const char* f : r.failures) {
      for (unsigned threads : {2u, 3u}) {
        if (QByteArray(f) == "start 2" && threads < 3) continue;  // only one start to fail
        QTest::addRow("%s, %s, threads %u", r.path, f, threads) << r.path << f << threads;
      }
    }
  }
}

namespace {

// The mapper settings of a mapping path (failureReachesTheCaller_data).
MapperSettings settingsOf(const QString& path) {
  MapperSettings s;
  s.model = "hpf";
  s.rule = "bayes";
  if (path.startsWith("totals")) s.rule = "addition";
  if (path == "himm on one thread") s.model = s.rule = "himm";
  return s;
}

// Sixteen of paper 002's 1440 sets, spread over its grid.
std::vector<ParameterSet> sweepSets() {
  const std::vector<ParameterSet> all =
      paper002Table1Sets(defaultParameters("parameterized", "bayes-recursive"));
  std::vector<ParameterSet> sets;
  // 32 sets: enough batches of the batched sweep for three threads.
  for (std::size_t i = 0; i < all.size(); i += 45) sets.push_back(all[i]);
  return sets;
}

}  // namespace

void TstConcurrency::failureReachesTheCaller() {
  QFETCH(QString, path);
  QFETCH(QString, failure);
  QFETCH(unsigned, threads);
  const ScopedThreadCount policy(threads);
  Fault fault;
  fault.onCaller = failure.endsWith("on caller");
  fault.runs = !path.endsWith("without runs");
  // A snapshot calls writeLevels once per thread: its first call on a worker fails.
  fault.after = path == "snapshot" ? 0 : 200;
  // Models and rules are wrapped when they are made, so before the mapper is built; a thread
  // start is made to fail after, so that it is the path's own start that fails (and not, say,
  // that of the beam tables a new mapper may build).
  std::optional<ModelsFail> models;
  std::optional<RulesFail> rules;
  if (failure.startsWith("model")) models.emplace(fault);
  if (failure.startsWith("rule")) rules.emplace(fault);
  std::optional<StartFails> starts;
  auto armStarts = [&] {
    if (failure == "start 1") starts.emplace(0);
    if (failure == "start 2") starts.emplace(1);
  };

  const Dataset& d = room();
  const Watchdog watchdog(QTest::currentDataTag());
  std::exception_ptr error;
  try {
    if (path == "snapshot") {
      // 0.02 m cells: 200 000 cells, split between up to six threads.
      Mapper m(d.ring, d.fittingGrid(PoseSource::Odometry, 0.02), settingsOf(path));
      for (std::size_t k = 0; k < 40; ++k) m.integrate(d.scans[k]);
      armStarts();
      m.snapshot();
    } else if (path == "beam tables") {
      armStarts();
      // 16 tables of 129² entries, above the size filled on several threads; then through the
      // mapper, which builds its tables (at a cell size nothing else in the suite uses).
      try {
        const BeamTables direct(0.05, 64);
      } catch (const std::system_error&) {
        starts.reset();
        armStarts();
        Mapper m(d.ring, d.fittingGrid(PoseSource::Odometry, 0.0937), settingsOf(path));
      }
    } else if (path == "sweep") {
      Dataset part = d;
      part.scans.resize(100);  // 1600 readings
      SweepSettings sweep;
      sweep.grid = part.fittingGrid(PoseSource::Odometry, 0.1);
      // A failing model or rule needs the path that calls them on the workers, one map per set
      // (hpf); the parameterized sets are mapped in batches (batch_evaluation.h), whose thread
      // starts fail alike.
      if (!failure.startsWith("start")) {
        sweep.model = "hpf";
        sweep.rule = "bayes";
      }
      armStarts();
      runSweep(part, nullptr, sweepSets(), sweep);
    } else {
      Mapper m(d.ring, d.fittingGrid(PoseSource::Odometry, 0.05), settingsOf(path));
      CountingObserver observer;
      if (path == "pipeline observer") m.setObserver(&observer);
      armStarts();
      m.mapDataset(d);
    }
  } catch (...) {
    error = std::current_exception();
  }
  QVERIFY2(error, "the failure did not reach the caller");
  try {
    std::rethrow_exception(error);
  } catch (const std::system_error& e) {
    QVERIFY2(failure.startsWith("start"), e.what());
    QCOMPARE(e.code(), std::make_error_code(std::errc::resource_unavailable_try_again));
  } catch (const std::runtime_error& e) {
    QVERIFY2(!failure.startsWith("start"), e.what());
    const QByteArray expected =
        failure.startsWith("model") ? "injected model failure" : "injected rule failure";
    QCOMPARE(QByteArray(e.what()), expected);
    QVERIFY(fault.thrown.load());
  }
}

void TstConcurrency::sameGridAfterAFailure_data() {
  QTest::addColumn<QString>("path");
  for (const char* path : {"bands", "bands without runs", "totals", "totals without runs",
                           "pipeline observer", "himm on one thread"})
    QTest::newRow(path) << path;
}

void TstConcurrency::sameGridAfterAFailure() {
  // A mapper whose run failed maps the next run exactly as a fresh one: nothing of the failed run
  // (half-applied footprints, a halted count, a thread's stop flag) survives into it.
  QFETCH(QString, path);
  const ScopedThreadCount policy(3);
  const Dataset& d = room();
  const GridSpec grid = d.fittingGrid(PoseSource::Odometry, 0.05);
  Fault fault;
  // The only thread they map on.
  fault.onCaller = path == "himm on one thread" || path == "totals without runs";
  fault.runs = !path.endsWith("without runs");
  CountingObserver observer;
  const Watchdog watchdog(QTest::currentDataTag());
  {
    const ModelsFail models(fault);
    Mapper m(d.ring, grid, settingsOf(path));
    if (path == "pipeline observer") m.setObserver(&observer);
    QVERIFY_THROWS_EXCEPTION(std::runtime_error, m.mapDataset(d));
    fault.armed.store(false);
    QVERIFY(m.mapDataset(d));
    QCOMPARE(m.readingsIntegrated(), d.readingCount());
    if (path == "pipeline observer") QCOMPARE(observer.seen, d.readingCount());
    Mapper fresh(d.ring, grid, settingsOf(path));
    for (const Scan& scan : d.scans) fresh.integrate(scan);
    QVERIFY(sameLayers(m.snapshot(), fresh.snapshot()));
  }
}

QTEST_GUILESS_MAIN(TstConcurrency)
#include "tst_concurrency.moc"
