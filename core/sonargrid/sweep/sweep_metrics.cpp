// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/sweep/sweep_metrics.h"

#include <algorithm>
#include <iterator>

#include "sonargrid/sweep/sweep_grid.h"

namespace sg {
namespace {

std::optional<Metric> referenceMetric(const std::string& name) {
  for (Metric m : allMetrics()) {
    if (name == metricName(m)) return m;
  }
  return std::nullopt;
}

const char* const kGoodness[] = {"vsdns", "derivative", "entropy", "two-run"};

}  // namespace

std::vector<std::string> allSweepMetrics() {
  std::vector<std::string> out(std::begin(kGoodness), std::end(kGoodness));
  for (Metric m : allMetrics()) out.push_back(metricName(m));
  return out;
}

std::vector<std::string> parseSweepMetrics(const std::vector<std::string>& texts) {
  std::vector<std::string> asked;
  for (const std::string& text : texts) {
    for (const std::string& name : splitCommas(text)) {
      if (name == "path") {
        asked.push_back(metricName(Metric::PathFalsePositive));
        asked.push_back(metricName(Metric::PathFalseNegative));
        continue;
      }
      const bool goodness =
          std::find(std::begin(kGoodness), std::end(kGoodness), name) != std::end(kGoodness);
      if (!goodness && !referenceMetric(name)) {
        std::string names = "vsdns, derivative, entropy, two-run, path";
        for (Metric m : allMetrics()) names += std::string(", ") + metricName(m);
        throw SweepSpecError(
            "--metric: " +
            (name.empty() ? std::string("an empty metric name") : "unknown metric '" + name + "'") +
            "; choose from " + names);
      }
      asked.push_back(name);
    }
  }
  std::vector<std::string> out;
  for (const char* g : kGoodness) {
    if (std::find(asked.begin(), asked.end(), g) != asked.end()) out.push_back(g);
  }
  for (Metric m : allMetrics()) {
    if (std::find(asked.begin(), asked.end(), metricName(m)) != asked.end())
      out.push_back(metricName(m));
  }
  return out;
}

bool isReferenceMetric(const std::string& name) {
  return referenceMetric(name).has_value();
}

std::vector<std::string> metricColumns(const std::vector<std::string>& metrics) {
  std::vector<std::string> out;
  for (const std::string& m : metrics) {
    if (m == "vsdns") {
      out.push_back("vsdns");
    } else if (m == "derivative") {
      out.push_back("derivative_noise");
      out.push_back("derivative_noise_mean");
    } else if (m == "entropy") {
      out.push_back("map_entropy");  // `goodness --json`'s entropy_bits
    } else if (m == "two-run") {
      out.push_back("two_run_positive");
      out.push_back("two_run_negative");
    } else if (const auto r = referenceMetric(m)) {
      out.push_back(metricJsonKey(*r));
    }
  }
  return out;
}

SetMeasures measuresOf(const std::vector<std::string>& metrics) {
  SetMeasures s;
  for (const std::string& m : metrics) {
    if (m == "vsdns") s.vsdns = true;
    if (m == "derivative") s.derivative = true;
    if (m == "entropy") s.entropy = true;
    if (m == "two-run") s.twoRun = true;
    if (const auto r = referenceMetric(m)) s.reference.insert(*r);
  }
  return s;
}

std::vector<std::optional<double>> metricValues(const std::vector<std::string>& metrics,
                                                const SetEvaluation& e) {
  std::vector<std::optional<double>> out;
  for (const std::string& m : metrics) {
    if (m == "vsdns") {
      out.push_back(e.vsdns ? e.vsdns->vsdns : std::nullopt);
    } else if (m == "derivative") {
      out.push_back(e.derivative ? std::optional<double>(e.derivative->sum) : std::nullopt);
      out.push_back(e.derivative ? e.derivative->mean : std::nullopt);
    } else if (m == "entropy") {
      out.push_back(e.entropy ? std::optional<double>(e.entropy->observedBits) : std::nullopt);
    } else if (m == "two-run") {
      out.push_back(e.twoRun ? std::optional<double>(static_cast<double>(e.twoRun->positive))
                             : std::nullopt);
      out.push_back(e.twoRun ? std::optional<double>(static_cast<double>(e.twoRun->negative))
                             : std::nullopt);
    } else if (const auto r = referenceMetric(m)) {
      out.push_back(e.reference ? e.reference->value(*r) : std::nullopt);
    }
  }
  return out;
}

int betterDirection(const std::string& column) {
  static const char* const kHigher[] = {"correlation_pct",
                                        "map_score_pct",
                                        "map_score_occupied_pct",
                                        "match_bits",
                                        "auc",
                                        "precision",
                                        "recall",
                                        "f1",
                                        "iou",
                                        "two_run_positive"};
  for (const char* h : kHigher) {
    if (column == h) return 1;
  }
  return -1;
}

}  // namespace sg
