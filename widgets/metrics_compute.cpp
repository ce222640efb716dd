// SPDX-License-Identifier: GPL-3.0-or-later
#include "metrics_compute.h"

#include <QCoreApplication>
#include <QElapsedTimer>
#include <nlohmann/json.hpp>

#include "dmin_overlay.h"
#include "sonargrid/forward/catalog.h"
#include "sonargrid/metrics/index_of_performance.h"
#include "sonargrid/reference/actual_position_grid.h"
#include "sonargrid/sweep/sweep_grid.h"

namespace sg::ui {
namespace {

QString tr(const char* text) {
  return QCoreApplication::translate("sg::ui::Metrics", text);
}

const char* kPaper000 = "Paper 000: Raschke & Borenstein, ICRA 1990";
const char* kPaper001 = "Paper 001: O'Sullivan, Collins, Mansfield, Haskett & Eaton";
const char* kPaper002 = "Paper 002: Arafat, Hellström & Rashid";

QString source(const char* what, const char* paper, const char* where) {
  return QStringLiteral("%1\n%2, %3 (docs/metrics.md)").arg(tr(what), tr(paper), tr(where));
}

}  // namespace

const std::vector<MetricInfo>& referenceMetricInfo() {
  static const std::vector<MetricInfo> info = {
      {metricJsonKey(Metric::Iop), tr("IOP"), tr("mm"), 1,
       source("Index of Performance: Σ D_min·CV / Σ CV over the filled cells, D_min the "
              "distance to the nearest reference (APG) cell. Lower is better.",
              kPaper000, "§3, eq 9")},
      {metricJsonKey(Metric::Correlation), tr("Correlation"), tr("%"), 2,
       source("Pearson correlation of p(occ) with the ideal map over the evaluated cells "
              "(after Baron 1981). Higher is better.",
              kPaper001, "§4, benchmark 1"),
       false},
      {metricJsonKey(Metric::MapScore), tr("Map score"), tr("%"), 2,
       source("100 · mean (p − ideal)² over the evaluated cells (after Martin & Moravec 1996). "
              "Lower is better.",
              kPaper001, "§4, benchmark 2")},
      {metricJsonKey(Metric::MapScoreOccupied), tr("Map score, occupied"), tr("%"), 2,
       source("The map score over the cells occupied in either map (p > 0.5 or ideal "
              "occupied). Lower is better.",
              kPaper001, "§4, benchmark 3")},
      {metricJsonKey(Metric::Match), tr("Match"), tr("bits"), 1,
       source("Moravec–Blackwell match Σ (1 + log2(p·q + (1 − p)(1 − q))), after Martin & "
              "Moravec 1996. Higher is better.",
              kPaper001, "§4, benchmark 2 (the match it derives from)"),
       false},
      {metricJsonKey(Metric::PathFalsePositive), tr("Path false positives"), tr("%"), 1,
       source("Paths planned on the built map (A*, 8-connected) that collide with the ideal "
              "map's obstacles, of the paths found. Lower is better.",
              kPaper001, "§4, benchmark 4")},
      {metricJsonKey(Metric::PathFalseNegative), tr("Path false negatives"), tr("%"), 1,
       source("Start/goal pairs joined in the ideal map with no path on the built map. Lower is "
              "better.",
              kPaper001, "§4, benchmark 4 (its converse)")},
      {metricJsonKey(Metric::CrossEntropy), tr("Cross-entropy"), tr("bits/cell"), 4,
       source("Mean −log2 of the probability the map gives the ideal state. Beyond the papers; "
              "lower is better.",
              kPaper001, "ideal map of §4")},
      {metricJsonKey(Metric::Brier), tr("Brier score"), QString(), 4,
       source("Mean (p − ideal)², the map score / 100. Beyond the papers; lower is better.",
              kPaper001, "ideal map of §4")},
      {metricJsonKey(Metric::Auc), tr("ROC AUC"), QString(), 4,
       source("Area under the ROC curve of p(occ) for the ideal occupied cells. Beyond the papers; "
              "higher is better.",
              kPaper001, "ideal map of §4"),
       false},
      {metricJsonKey(Metric::Precision), tr("Precision (occupied)"), QString(), 4,
       source("TP / (TP + FP), occupied when p > 0.5. Beyond the papers; higher is better.",
              kPaper001, "ideal map of §4"),
       false},
      {metricJsonKey(Metric::Recall), tr("Recall (occupied)"), QString(), 4,
       source("TP / (TP + FN), occupied when p > 0.5. Beyond the papers; higher is better.",
              kPaper001, "ideal map of §4"),
       false},
      {metricJsonKey(Metric::F1), tr("F1 (occupied)"), QString(), 4,
       source("2 TP / (2 TP + FP + FN). Beyond the papers; higher is better.", kPaper001,
              "ideal map of §4"),
       false},
      {metricJsonKey(Metric::Iou), tr("IoU (occupied)"), QString(), 4,
       source("TP / (TP + FP + FN), the Jaccard index of the occupied cells. Beyond the papers; "
              "higher is better.",
              kPaper001, "ideal map of §4"),
       false},
      {"cells_evaluated", tr("Cells evaluated"), tr("cells"), 0,
       source("Cells the ideal map knows (free or occupied) and the built map observed: what "
              "every metric but IOP is computed over.",
              kPaper001, "§4 (ideal maps)"),
       false},
  };
  return info;
}

const std::vector<MetricInfo>& goodnessMetricInfo() {
  static const std::vector<MetricInfo> info = {
      {"vsdns", tr("VSDNS"), QString(), 4,
       source("Mean of the non-zero standard deviations of the values the sensor model gave each "
              "cell over the run. Lower is better.",
              kPaper002, "§5, first approach")},
      {"derivative_noise", tr("Derivative noise"), QString(), 2,
       source("D_map = Σ D(x, y), D the mean absolute difference of p(occ) to the 3 × 3 "
              "neighbours, over fully observed windows. Lower is better.",
              kPaper002, "§5, second approach")},
      {"derivative_noise_mean", tr("Derivative noise, mean"), tr("per cell"), 5,
       source("D_map divided by the number of cells scored (the paper's normalisation for maps "
              "of different sizes). Lower is better.",
              kPaper002, "§5, second approach")},
      {"entropy_bits", tr("Map entropy"), tr("bits"), 1,
       source("Σ H(p) = −p log2 p − (1 − p) log2 (1 − p) over the observed cells (Martin & "
              "Moravec 1996, named in paper 002). Lower is a more decided map, not a truer one.",
              kPaper002, "§5")},
      {"entropy_bits_mean", tr("Map entropy, mean"), tr("bits/cell"), 4,
       source("Map entropy divided by the number of observed cells.", kPaper002, "§5")},
      {"entropy_bits_grid", tr("Map entropy, grid"), tr("bits"), 1,
       source("Σ H(p) over every cell of the grid; a never-observed cell counts 1 bit.", kPaper002,
              "§5")},
      {"two_run_positive", tr("Two runs: agree"), tr("cells"), 0,
       source("Cells observed in both runs that are equal once both maps are thresholded at "
              "p > 0.5 (after Moravec & Elfes). Higher is better.",
              kPaper002, "§5, third approach"),
       false},
      {"two_run_negative", tr("Two runs: differ"), tr("cells"), 0,
       source("Cells observed in both runs that differ once thresholded. Lower is better.",
              kPaper002, "§5, third approach")},
  };
  return info;
}

std::vector<MetricsResult::Value> MetricsResult::values() const {
  std::vector<Value> out;
  if (score) {
    for (Metric m : allMetrics()) {
      if (score->computed.count(m) == 0) continue;  // as score --json: omitted
      out.push_back({metricJsonKey(m), score->value(m), false});
    }
    out.push_back({"cells_evaluated", static_cast<double>(score->cellsEvaluated), true});
  }
  if (goodness) {
    const SetEvaluation& g = *goodness;
    if (g.vsdns) out.push_back({"vsdns", g.vsdns->vsdns, false});
    if (g.derivative) {
      out.push_back({"derivative_noise", g.derivative->sum, false});
      out.push_back({"derivative_noise_mean", g.derivative->mean, false});
    }
    if (g.entropy) {
      out.push_back({"entropy_bits", g.entropy->observedBits, false});
      out.push_back({"entropy_bits_mean", g.entropy->meanBits, false});
      out.push_back({"entropy_bits_grid", g.entropy->totalBits, false});
    }
    if (g.vsdns || g.derivative || g.twoRun) {
      std::optional<double> positive, negative;
      if (g.twoRun) {
        positive = static_cast<double>(g.twoRun->positive);
        negative = static_cast<double>(g.twoRun->negative);
      }
      out.push_back({"two_run_positive", positive, true});
      out.push_back({"two_run_negative", negative, true});
    }
  }
  return out;
}

std::optional<double> MetricsResult::value(const std::string& key) const {
  for (const Value& v : values())
    if (v.key == key) return v.value;
  return std::nullopt;
}

GridSpec goodnessGrid(const Dataset& run, const Dataset* secondRun, PoseSource pose,
                      double cellSize) {
  const GridSpec a = run.fittingGrid(pose, cellSize);
  if (!secondRun) return a;
  // As `sonargrid-cli goodness`: one grid over both runs, their cells lined up.
  return gridOverRuns(a, secondRun->fittingGrid(pose, cellSize));
}

std::optional<MetricsResult> computeMetrics(const MetricsInput& in,
                                            const std::atomic<bool>* cancel) {
  QElapsedTimer clock;
  clock.start();
  auto cancelled = [cancel] { return cancel && cancel->load(std::memory_order_relaxed); };
  MetricsResult out;
  if (in.map) out.spec = in.map->spec;
  if (in.map && in.reference) {
    try {
      out.score = scoreAgainstReference(*in.map, *in.reference, in.score);
      if (in.dminOverlay) {
        const ActualPositionGrid apg = ActualPositionGrid::rasterise(*in.reference, in.map->spec);
        out.dminTint = std::make_shared<const QImage>(dminTintImage(*in.map, distanceToApg(apg)));
      }
    } catch (const std::exception& e) {
      out.scoreError = QString::fromUtf8(e.what());
    }
  }
  if (cancelled()) return std::nullopt;
  const bool twoRuns = in.secondRun != nullptr;
  if (in.run && (in.goodness || twoRuns) && forward::isForwardModel(in.settings.model)) {
    out.goodnessError = QStringLiteral(
        "VSDNS, derivative noise and the two-run comparison replay an inverse "
        "model's evidence reading by reading; the forward model learns its map by "
        "EM and has none (docs/forward-model.md)");
  } else if (in.run && (in.goodness || twoRuns)) {
    try {
      SetEvaluationInput e;
      e.run = in.run.get();
      e.secondRun = in.secondRun.get();
      e.settings.model = in.settings.model;
      e.settings.rule = in.settings.rule;
      e.settings.pose = in.settings.pose;
      e.settings.grid = goodnessGrid(*in.run, in.secondRun.get(), in.settings.pose, in.cellSize);
      e.measures.vsdns = in.goodness;
      e.measures.derivative = in.goodness;
      e.measures.entropy = in.goodness;
      e.measures.twoRun = twoRuns;
      out.goodness = evaluateSet(e, in.settings.parameters, cancel);
      if (!out.goodness) return std::nullopt;  // cancelled
    } catch (const std::exception& e) {
      out.goodnessError = QString::fromUtf8(e.what());
    }
  }
  if (cancelled()) return std::nullopt;
  out.elapsedMs = static_cast<double>(clock.nsecsElapsed()) / 1e6;
  return out;
}

std::string metricsJson(const MetricsResult& result) {
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  for (const MetricsResult::Value& v : result.values()) {
    if (!v.value)
      out[v.key] = nullptr;
    else if (v.integer)
      out[v.key] = static_cast<std::uint64_t>(*v.value);
    else
      out[v.key] = *v.value;
  }
  return out.dump();
}

QString formatValue(const std::optional<double>& value, int precision) {
  if (!value) return QStringLiteral("—");
  return QString::number(*value, 'f', precision);
}

}  // namespace sg::ui
