// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/sweep/optimal_sets.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>

namespace sg {

double Histogram::upperEdge(int bin) const {
  return bin + 1 == static_cast<int>(counts.size()) ? max : lowerEdge(bin + 1);
}

Histogram histogramOf(std::span<const std::optional<double>> values, int bins) {
  if (bins < 1) throw std::invalid_argument("a histogram needs at least one bin");
  Histogram h;
  bool any = false;
  for (const std::optional<double>& v : values) {
    if (!v) continue;
    h.min = any ? std::min(h.min, *v) : *v;
    h.max = any ? std::max(h.max, *v) : *v;
    any = true;
  }
  if (!any) throw std::invalid_argument("no defined value to put in a histogram");
  h.width = (h.max - h.min) / bins;
  h.counts.assign(static_cast<std::size_t>(bins), 0);
  h.binOf.reserve(values.size());
  for (const std::optional<double>& v : values) {
    if (!v) {
      h.binOf.push_back(-1);
      continue;
    }
    int k = 0;
    if (h.width > 0.0) {
      k = std::clamp(static_cast<int>(std::floor((*v - h.min) / h.width)), 0, bins - 1);
      // The division may land a value on the wrong side of an edge by one rounding; the edges
      // as lowerEdge() states them decide.
      while (k + 1 < bins && *v >= h.lowerEdge(k + 1)) ++k;
      while (k > 0 && *v < h.lowerEdge(k)) --k;
    }
    h.binOf.push_back(k);
    ++h.counts[static_cast<std::size_t>(k)];
  }
  return h;
}

ParameterSet averageParameters(const std::vector<ParameterSet>& sets,
                               const std::vector<std::size_t>& members) {
  if (members.empty()) throw std::invalid_argument("no parameter set to average");
  std::map<std::string, double> sums;
  for (std::size_t i : members) {
    for (const auto& [name, value] : sets.at(i).values()) sums[name] += value;
  }
  ParameterSet out = sets.at(members.front());
  for (const auto& entry : sums) {
    // (A named copy, not a structured binding: clang 14, the fuzz build's compiler, cannot
    // capture bindings in a lambda.)
    const std::string& name = entry.first;
    const double mean = entry.second / static_cast<double>(members.size());
    // A parameter every member shares keeps its exact value (no rounding of a constant).
    const bool constant = std::all_of(members.begin(), members.end(), [&](std::size_t i) {
      return sets[i].get(name) == out.get(name);
    });
    if (constant) continue;
    // A whole-number parameter (HIMM's increments, a switch) cannot take a mean such as 2.5, and
    // a whole mean may be a value never swept (the mean of 1, 6, 10, 15 is 8): it takes the
    // members' value nearest the mean, the first member's on a tie, so the result is a set the
    // sweep mapped in that parameter.
    const auto spec = std::find_if(out.specs().begin(), out.specs().end(),
                                   [&](const ParameterSpec& s) { return s.name == name; });
    if (spec != out.specs().end() && spec->integer) {
      double nearest = sets[members.front()].get(name);
      for (std::size_t i : members) {
        const double v = sets[i].get(name);
        if (std::abs(v - mean) < std::abs(nearest - mean)) nearest = v;
      }
      out.set(name, nearest);
    } else {
      out.set(name, mean);
    }
  }
  return out;
}

namespace {

void requireSameSize(std::size_t values, std::size_t sets) {
  if (values != sets)
    throw std::invalid_argument("the sweep has " + std::to_string(sets) + " sets but " +
                                std::to_string(values) + " values");
}

// The index of the defined value that `better` prefers (strictly, so the earliest wins ties).
template <class Value, class Better>
std::size_t bestIndex(std::span<const std::optional<Value>> values, Better better,
                      const char* what) {
  std::optional<std::size_t> best;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (values[i] && (!best || better(*values[i], *values[*best]))) best = i;
  }
  if (!best) throw std::invalid_argument(std::string("no set has a defined ") + what);
  return *best;
}

OptimalSet single(const std::vector<ParameterSet>& sets, std::size_t i, double criterion) {
  OptimalSet o;
  o.parameters = sets[i];
  o.members = {i};
  o.criterion = criterion;
  return o;
}

}  // namespace

OptimalSet lowestBinAverage(std::span<const std::optional<double>> values,
                            const std::vector<ParameterSet>& sets, int bins) {
  requireSameSize(values.size(), sets.size());
  const Histogram h = histogramOf(values, bins);
  OptimalSet o;
  o.criterion = h.min;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (h.binOf[i] == 0) {
      o.members.push_back(i);
      o.criterion = std::max(o.criterion, *values[i]);
    }
  }
  o.parameters = averageParameters(sets, o.members);
  return o;
}

OptimalSet minimumVsdns(std::span<const std::optional<double>> values,
                        const std::vector<ParameterSet>& sets) {
  requireSameSize(values.size(), sets.size());
  const std::size_t i = bestIndex(values, std::less<double>(), "VSDNS");
  return single(sets, i, *values[i]);
}

OptimalSet nearestMeanVsdns(std::span<const std::optional<double>> values,
                            const std::vector<ParameterSet>& sets) {
  requireSameSize(values.size(), sets.size());
  double sum = 0.0;
  std::size_t n = 0;
  for (const std::optional<double>& v : values) {
    if (v) {
      sum += *v;
      ++n;
    }
  }
  if (n == 0) throw std::invalid_argument("no set has a defined VSDNS");
  const double mean = sum / static_cast<double>(n);
  std::vector<std::optional<double>> distance(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (values[i]) distance[i] = std::abs(*values[i] - mean);
  }
  const std::size_t i =
      bestIndex(std::span<const std::optional<double>>(distance), std::less<double>(), "VSDNS");
  return single(sets, i, mean);
}

OptimalSet minimumDerivativeNoise(const std::vector<SweepRow>& rows,
                                  const std::vector<ParameterSet>& sets) {
  requireSameSize(rows.size(), sets.size());
  std::vector<std::optional<double>> noise(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].noise.cellsScored > 0) noise[i] = rows[i].noise.sum;
  }
  const std::size_t i = bestIndex(std::span<const std::optional<double>>(noise),
                                  std::less<double>(), "derivative noise");
  return single(sets, i, *noise[i]);
}

OptimalSet bestTwoRunAgreement(const std::vector<SweepRow>& rows,
                               const std::vector<ParameterSet>& sets) {
  requireSameSize(rows.size(), sets.size());
  using Score = std::pair<double, double>;  // (positive − negative, −negative): larger is better
  std::vector<std::optional<Score>> scores(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (const auto& t = rows[i].twoRuns) {
      const auto pos = static_cast<double>(t->positive);
      const auto neg = static_cast<double>(t->negative);
      scores[i] = Score{pos - neg, -neg};
    }
  }
  const std::size_t i = bestIndex(std::span<const std::optional<Score>>(scores),
                                  std::greater<Score>(), "two-run comparison");
  return single(sets, i, scores[i]->first);
}

}  // namespace sg
