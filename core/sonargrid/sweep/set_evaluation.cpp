// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/sweep/set_evaluation.h"

#include <algorithm>
#include <limits>
#include <mutex>
#include <stdexcept>

#include "sonargrid/base/concurrency.h"
#include "sonargrid/data/scan_poses.h"
#include "sonargrid/engine/mapper.h"
#include "sonargrid/forward/catalog.h"
#include "sonargrid/forward/forward_em.h"
#include "sonargrid/sweep/batch_evaluation.h"

namespace sg {
namespace {

// One run; false when cancelled or stopped. Without `stop` (one set alone, optimize's
// evaluations) the mapper's own threads map it; inside a sweep, where the sets already occupy every
// thread, scan by scan on this one (Mapper guarantees the two bit-identical).
bool mapRun(Mapper& mapper, const Dataset& data, const std::atomic<bool>* cancel,
            const std::atomic<bool>* stop) {
  if (!stop) return mapper.mapDataset(data, std::numeric_limits<double>::infinity(), cancel);
  mapper.reset();
  for (const Scan& scan : data.scans) {
    if ((cancel && cancel->load(std::memory_order_relaxed)) ||
        (stop && stop->load(std::memory_order_relaxed)))
      return false;
    mapper.integrate(scan);
  }
  return true;
}

// The forward model's maps of the set: EM over each run (docs/forward-model.md). Inside a sweep
// (with `stop`) EM runs on this thread alone, as parallelThreads() grants there.
std::optional<SetEvaluation> evaluateForward(const SetEvaluationInput& in, const ParameterSet& set,
                                             const std::atomic<bool>* cancel,
                                             const std::atomic<bool>* stop) {
  if (in.measures.vsdns) {
    throw MapperError(
        "VSDNS replays an inverse model's evidence reading by reading; the forward model learns "
        "its map by EM and has none: sweep it by the reference metrics, derivative noise, entropy "
        "or two runs");
  }
  const forward::ForwardSettings settings = forward::settingsOf(set);
  const auto mapOf = [&](const Dataset& run) -> std::optional<OccupancyMap> {
    try {
      forward::EmResult em = forward::runEm(forward::beamsOf(run, in.settings.pose),
                                            in.settings.grid, settings, cancel, {}, stop);
      if (em.cancelled) return std::nullopt;
      return std::move(em.map);
    } catch (const forward::ForwardError& e) {
      throw MapperError(e.what());
    }
  };
  const std::optional<OccupancyMap> first = mapOf(*in.run);
  if (!first) return std::nullopt;
  if (!in.measures.twoRun) return measureSet(in, std::nullopt, &*first, nullptr);
  const std::optional<OccupancyMap> second = mapOf(*in.secondRun);
  if (!second) return std::nullopt;
  return measureSet(in, std::nullopt, &*first, &*second);
}

std::optional<SetEvaluation> evaluate(const SetEvaluationInput& in, const ParameterSet& set,
                                      const std::atomic<bool>* cancel,
                                      const std::atomic<bool>* stop) {
  checkSetEvaluationInput(in);
  if (forward::isForwardModel(in.settings.model)) return evaluateForward(in, set, cancel, stop);
  MapperSettings ms;
  ms.model = in.settings.model;
  ms.rule = in.settings.rule;
  ms.parameters = set;
  ms.pose = in.settings.pose;
  Mapper mapper(in.run->ring, in.settings.grid, ms);
  VsdnsAccumulator vsdns;
  if (in.measures.vsdns) mapper.setObserver(&vsdns);
  if (!mapRun(mapper, *in.run, cancel, stop)) return std::nullopt;
  std::optional<VsdnsAccumulator::Result> spread;
  if (in.measures.vsdns) spread = vsdns.result();
  if (!mapsNeeded(in.measures)) return measureSet(in, spread, nullptr, nullptr);
  const OccupancyMap first = mapper.snapshot();
  if (!in.measures.twoRun) return measureSet(in, spread, &first, nullptr);
  Mapper again(in.secondRun->ring, in.settings.grid, ms);
  if (!mapRun(again, *in.secondRun, cancel, stop)) return std::nullopt;
  const OccupancyMap second = again.snapshot();
  return measureSet(in, spread, &first, &second);
}

}  // namespace

void checkSetEvaluationInput(const SetEvaluationInput& in) {
  if (!in.run) throw std::invalid_argument("a sweep needs a log");
  if (in.measures.twoRun && !in.secondRun)
    throw std::invalid_argument("the two-run comparison needs a second log");
  if (!in.measures.reference.empty() && !in.reference)
    throw std::invalid_argument("reference metrics need a reference map");
  for (const Dataset* d : {in.run, in.secondRun}) {
    if (d && in.settings.pose == PoseSource::Truth && !anyScanHasPose(*d, PoseSource::Truth))
      throw MapperError(std::string(kNoTruePose) + "; map with odometry (--pose odom)");
  }
}

bool mapsNeeded(const SetMeasures& m) {
  return m.derivative || m.entropy || m.twoRun || !m.reference.empty();
}

SetEvaluation measureSet(const SetEvaluationInput& in,
                         const std::optional<VsdnsAccumulator::Result>& vsdns,
                         const OccupancyMap* first, const OccupancyMap* second) {
  SetEvaluation out;
  if (in.measures.vsdns) out.vsdns = vsdns;
  if (in.measures.derivative) out.derivative = derivativeNoise(*first);
  if (in.measures.entropy) out.entropy = mapEntropy(*first);
  if (in.measures.twoRun) out.twoRun = compareTwoRuns(*first, *second);
  if (!in.measures.reference.empty()) {
    ScoreOptions options = in.measures.score;
    options.metrics = in.measures.reference;
    out.reference = scoreAgainstReference(*first, *in.reference, options);
  }
  return out;
}

std::optional<SetEvaluation> evaluateSet(const SetEvaluationInput& input, const ParameterSet& set,
                                         const std::atomic<bool>* cancel) {
  return evaluate(input, set, cancel, nullptr);
}

bool evaluateSets(const SetEvaluationInput& input, const std::vector<ParameterSet>& sets,
                  const std::vector<std::size_t>& indices, const SetFinished& finished,
                  const std::atomic<bool>* cancel) {
  if (batchEvaluable(input)) return evaluateSetsBatched(input, sets, indices, finished, cancel);
  for (std::size_t i : indices) {
    if (i >= sets.size()) throw std::invalid_argument("a sweep index beyond its sets");
  }
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  std::atomic<std::size_t> done{0};
  std::mutex mutex;  // serialises `finished`
  // Sets are handed out one at a time, so a thread that draws quick sets takes more of them.
  auto work = [&](unsigned) {
    while (!stop.load(std::memory_order_relaxed)) {
      const std::size_t k = next.fetch_add(1, std::memory_order_relaxed);
      if (k >= indices.size()) return;
      const std::optional<SetEvaluation> e = evaluate(input, sets[indices[k]], cancel, &stop);
      if (!e) return;
      const std::lock_guard<std::mutex> lock(mutex);
      if (finished) finished(k, *e);
      done.fetch_add(1);
    }
  };
  const auto threads =
      static_cast<unsigned>(std::clamp<std::size_t>(indices.size(), 1, parallelThreads()));
  runParallel(threads, work, [&] { stop.store(true); });
  return done.load() == indices.size();
}

}  // namespace sg
