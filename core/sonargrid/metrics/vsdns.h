// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// VSDNS, the first goodness measure of paper 002 §5: for each cell the sample standard deviation
//   σ = sqrt(Σ (X_k − X̄)² / (N − 1))
// of the values the sensor model gave it over the run, then the mean of the non-zero σ. The values
// are each reading's CellEvidence::probability, the model's P(occupied | this reading) (paper 002
// saves "the generated numerical values from our proposed model", the likelihoods its Bayes
// update consumes), not the evolving posterior.
//
// Streamed: the accumulator is a FootprintObserver that keeps Welford's running count, mean and
// M2 per cell, so no L × M × N cube of values is ever stored. A cell written once has no σ
// (N − 1 = 0) and, like a cell whose values never varied, does not enter the mean.

#include <cstdint>
#include <optional>
#include <vector>

#include "sonargrid/engine/mapper.h"

namespace sg {

class VsdnsAccumulator final : public FootprintObserver {
 public:
  void reset(std::size_t cells) override;
  void observe(const Footprint& footprint) override;

  // One value for one cell (what observe() does for each entry of a footprint).
  void add(std::size_t cell, double value);

  std::size_t cells() const { return count_.size(); }
  std::uint32_t samples(std::size_t cell) const { return count_[cell]; }
  double mean(std::size_t cell) const { return mean_[cell]; }
  // Sample standard deviation (N − 1); 0 below two samples.
  double sigma(std::size_t cell) const;

  struct Result {
    std::optional<double> vsdns;  // empty when no cell has σ ≠ 0
    std::size_t cellsWithSpread = 0;
  };
  Result result() const;

 private:
  std::vector<std::uint32_t> count_;
  std::vector<double> mean_;
  std::vector<double> m2_;
};

}  // namespace sg
