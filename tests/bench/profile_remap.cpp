// SPDX-License-Identifier: BSD-3-Clause
// A single-threaded re-map for instruction counts: the hot path without the pipeline's spinning,
// so callgrind's counts are deterministic. Also prints a digest of the map, to tell a change that
// keeps results from one that does not, and that of a batch re-map, which must be the same.
// Run: valgrind --tool=callgrind build/tests/bench/profile_remap murphy dempster-shafer 6400
//      then callgrind_annotate --inclusive=yes and divide remapOnce by the readings printed.
// With a fifth argument K, it also times K batch re-maps (mapDataset) on one thread and prints
// their median CPU time: on a loaded machine the CPU time of one thread varies far less than the
// wall-clock time, so two builds can be compared on it (a paired A/B of the engine). With a sixth
// argument N the re-maps run on N threads and the CPU time is all of theirs: what the threads
// spend in all, duplicated set-up included; the median wall-clock time is printed as well. In place
// of `sim` or `stress`, a path to an .sglog log (datasets/office/office.sglog: `sonargrid-cli
// bench`'s office re-map) maps that log on a grid fitted to its odometry at 5 cm; READINGS is then
// ignored.
// With PROFILE_PARTS=1 and K, it times instead the one-thread batch path's two parts, K times in
// turn (THREADS is then ignored): the model's rows alone (SensorModel::evidenceRuns for every
// reading), then the rows with the rule's run kernels (UpdateRule::applyRuns, and normalising
// addition's deferred arc) on a grid of its own, without the observed marks. The difference is
// the kernels' time, measured in one process a few hundred milliseconds apart, where two whole
// re-maps in turn on a loaded machine can differ by more than the kernels take. It prints the
// medians of both, the median of the pairs' shares of the kernels, and the cells and runs of a
// reading that writes.
// With PROFILE_PRECISION=fast, the digests and the timed re-maps (not PROFILE_PARTS's) use the
// fast engine (docs/models.md, "Exact and fast engines"); exact is the default.

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_workload.h"
#include "sonargrid/base/concurrency.h"
#include "sonargrid/engine/beam_tables.h"
#include "sonargrid/io/sglog.h"
#include "sonargrid/simd/lanes.h"
#include "sonargrid/testing/registry_hooks.h"

namespace {

// Not inlined, so that callgrind reports the re-map alone.
[[gnu::noinline]] void remapOnce(sg::Mapper& mapper, const sg::Dataset& d) {
  mapper.reset();
  for (const sg::Scan& scan : d.scans) mapper.integrate(scan);
}

// FNV-1a over the bytes of every layer a snapshot holds.
std::uint64_t digest(const sg::OccupancyMap& m) {
  std::uint64_t h = 1469598103934665603ull;
  auto add = [&h](const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ull;
  };
  const std::vector<double> probability = m.probability.values(), native = m.native.values();
  const std::vector<std::uint8_t> filled = m.filled.values();
  add(probability.data(), probability.size() * sizeof(double));
  add(native.data(), native.size() * sizeof(double));
  add(m.level.data(), m.level.size());
  add(filled.data(), filled.size());
  add(m.observed.data(), m.observed.size());
  return h;
}

// This thread's CPU time, or with `process` every thread's (the work a multi-threaded re-map
// spends in all, which the second thread's duplicated set-up per reading adds to).
double cpuMs(bool process = false) {
  timespec t{};
  clock_gettime(process ? CLOCK_PROCESS_CPUTIME_ID : CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

// PROFILE_PARTS (above). The beams as Mapper::beamOf places them, from the odometry.
int timeParts(const sg::Dataset& d, const sg::GridSpec& spec, const std::string& modelName,
              const std::string& ruleName, int times) {
  const std::unique_ptr<sg::SensorModel> model = sg::makeSensorModel(modelName);
  const std::unique_ptr<sg::UpdateRule> rule = sg::makeUpdateRule(ruleName);
  const sg::ParameterSet params = sg::defaultParameters(modelName, ruleName);
  model->configure(params);
  rule->configure(params);
  const auto tables = sg::BeamTables::shared(spec.cellSize, model->reach(d.ring.maxRange));
  std::vector<sg::Beam> beams;
  for (const sg::Scan& scan : d.scans) {
    const Eigen::Matrix2d rotation = scan.odometry.rotation();
    for (const sg::Reading& reading : scan.readings) {
      sg::Beam beam;
      beam.sensor = scan.odometry.compose(d.ring.sonars.at(reading.sonar).pose, rotation);
      beam.range = reading.range < d.ring.maxRange ? reading.range : sg::Reading::kNoEcho;
      beam.maxRange = d.ring.maxRange;
      beams.push_back(beam);
    }
  }
  sg::EvidenceRuns runs, deferred;
  if (beams.empty()) {
    std::printf("parts: the log has no readings\n");
    return 0;
  }
  if (!model->evidenceRuns(beams.front(), spec, *tables, sg::RowWindow{0, 0}, runs)) {
    std::printf("parts: %s gives no runs (the batch path maps its cells another way)\n",
                modelName.c_str());
    return 0;
  }
  const bool totals = rule->needsTotals();
  auto rowsOf = [&](const sg::Beam& beam) {
    runs.clear();
    model->evidenceRuns(beam, spec, *tables, sg::RowWindow{}, runs);
  };
  // What a reading writes, counted once, outside the timing.
  std::size_t cells = 0, runCount = 0, writing = 0;
  for (const sg::Beam& beam : beams) {
    rowsOf(beam);
    if (runs.runs.empty()) continue;
    ++writing;
    runCount += runs.runs.size();
    for (const sg::EvidenceRuns::Run& run : runs.runs) cells += static_cast<std::size_t>(run.count);
  }
  std::vector<double> alone, together, share;
  for (int k = 0; k < times; ++k) {
    sg::Grid grid(spec, rule->layout());
    const double t0 = cpuMs();
    for (const sg::Beam& beam : beams) rowsOf(beam);
    const double t1 = cpuMs();
    for (const sg::Beam& beam : beams) {
      rowsOf(beam);
      deferred.clear();
      rule->applyRuns(runs, grid, &deferred);
      if (totals)
        rule->applyDeferred(deferred, sg::FootprintTotals{sg::occupiedFixedPoint(deferred)}, grid);
    }
    const double t2 = cpuMs();
    alone.push_back(t1 - t0);
    together.push_back(t2 - t1);
    if (t2 > t1) share.push_back((t2 - t1 - (t1 - t0)) / (t2 - t1));
  }
  const double n = static_cast<double>(std::max<std::size_t>(writing, 1));
  std::printf(
      "parts on one thread, %d times in turn: rows alone median %.1f ms, rows and rule %.1f ms; "
      "the rule's kernels %.0f %% (median of the pairs); %zu readings write, %.1f cells in %.1f "
      "runs each\n",
      times, sg::workload::median(alone), sg::workload::median(together),
      100.0 * sg::workload::median(share), writing, static_cast<double>(cells) / n,
      static_cast<double>(runCount) / n);
  return 0;
}

int run(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(
        stderr,
        "usage: profile_remap MODEL RULE [READINGS] [sim|stress|LOG.sglog] [K [THREADS]]\n");
    return 2;
  }
  // PROFILE_LANES=four or avx2: the cone models' rows and the rules' run kernels no wider than
  // that (testing::limitConeLanes), to time the code a CPU without AVX-512 (or AVX2) runs.
  if (const char* lanes = std::getenv("PROFILE_LANES")) {
    const std::string limit = lanes;
    if (limit == "four")
      sg::testing::limitConeLanes(sg::ConeLanes::Four);
    else if (limit == "avx2")
      sg::testing::limitConeLanes(sg::ConeLanes::Avx2);
    else if (limit != "avx512")
      throw std::invalid_argument("PROFILE_LANES: four, avx2 or avx512");
  }
  const int readings = argc > 3 ? std::atoi(argv[3]) : 6400;
  const std::string source = argc > 4 ? argv[4] : "sim";
  const bool log = source.ends_with(".sglog");
  const sg::Dataset d = log                  ? sg::readSglog(source)
                        : source == "stress" ? bench::stressWorkload(readings)
                                             : bench::simulatedWorkload(readings);
  sg::MapperSettings settings;
  settings.model = argv[1];
  settings.rule = argv[2];
  // PROFILE_PRECISION=fast: the fast engine's cells (docs/models.md, "Exact and fast engines").
  if (const char* precision = std::getenv("PROFILE_PRECISION"))
    settings.precision = sg::precisionFromName(precision);
  sg::Mapper mapper(d.ring,
                    log ? d.fittingGrid(sg::PoseSource::Odometry, 0.05) : bench::benchmarkGrid(),
                    settings);
  remapOnce(mapper, d);
  const std::uint64_t h = digest(mapper.snapshot());
  // Counted on a second (batch) re-map, outside remapOnce.
  const double cells = bench::cellsPerReading(mapper, d);
  std::printf("%s/%s readings %zu cells/reading %.1f digest %016llx\n", argv[1], argv[2],
              mapper.readingsIntegrated(), cells, static_cast<unsigned long long>(h));
  // The batch path without an observer (the one timed below: the models' runs and the rules' run
  // kernels, where the digest above comes from footprints one reading at a time) must give the
  // same map.
  mapper.mapDataset(d);
  const std::uint64_t batch = digest(mapper.snapshot());
  std::printf("batch re-map digest %016llx (%s)\n", static_cast<unsigned long long>(batch),
              batch == h ? "the same" : "DIFFERENT");
  const int timed = argc > 5 ? std::atoi(argv[5]) : 0;
  const int threads = argc > 6 ? std::max(1, std::atoi(argv[6])) : 1;
  if (const char* parts = std::getenv("PROFILE_PARTS"); parts && std::string(parts) == "1") {
    if (timed <= 0) throw std::invalid_argument("PROFILE_PARTS=1 needs K, the times to run");
    return timeParts(d, mapper.snapshot().spec, argv[1], argv[2], timed);
  }
  if (timed > 0) {
    sg::ScopedThreadCount count(static_cast<unsigned>(threads));
    std::vector<double> ms, wall;
    for (int k = 0; k < timed; ++k) {
      const auto w0 = std::chrono::steady_clock::now();
      const double t0 = cpuMs(threads > 1);
      mapper.mapDataset(d);
      ms.push_back(cpuMs(threads > 1) - t0);
      wall.push_back(
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - w0).count());
    }
    std::sort(ms.begin(), ms.end());
    std::sort(wall.begin(), wall.end());
    // The wall-clock time too: at N threads, how much of it the threads spent waiting (for each
    // other, or for a core the machine gave to other work).
    std::printf("wall-clock median %.1f ms (min %.1f)\n", wall[wall.size() / 2], wall.front());
    if (threads == 1) {
      std::printf("batch re-map on one thread: median CPU %.1f ms of %d (min %.1f)\n",
                  ms[ms.size() / 2], timed, ms.front());
    } else {
      std::printf(
          "batch re-map on %d threads: median CPU of all threads %.1f ms of %d (min %.1f)\n",
          threads, ms[ms.size() / 2], timed, ms.front());
    }
  }
  return 0;
}

}  // namespace

// A log that cannot be read, or a model or rule that does not exist, is reported, not a crash.
int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "profile_remap: %s\n", e.what());
    return 1;
  }
}
