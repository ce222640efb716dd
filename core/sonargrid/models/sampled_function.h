// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A smooth function of one variable sampled on a uniform grid and read back with linear
// interpolation: how the hot path evaluates exp and erf without calling them per cell. Outside
// [x0, x1] it returns the end values.

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <vector>

#include "sonargrid/simd/lanes.h"

namespace sg {

class SampledFunction {
 public:
  SampledFunction() = default;
  SampledFunction(double x0, double x1, int intervals, const std::function<double(double)>& f)
      : x0_(x0),
        x1_(x1),
        scale_(intervals / (x1 - x0)),
        samples_(static_cast<std::size_t>(intervals) + 2) {
    for (std::size_t i = 0; i < samples_.size(); ++i) {
      samples_[i] = f(x0 + std::min<double>(static_cast<double>(i), intervals) / scale_);
    }
    lanes_.clear();
    for (std::size_t i = 0; i + 1 < samples_.size(); ++i) {
      lanes_.push_back(
          {static_cast<float>(samples_[i]), static_cast<float>(samples_[i + 1] - samples_[i])});
    }
    lanes_.push_back(lanes_.back());  // read, never used, by the lanes of the last interval
  }

  double operator()(double x) const {
    if (!(x > x0_)) return samples_.front();
    if (x >= x1_) return samples_[samples_.size() - 2];
    // t > 0 here, so truncation is floor; std::floor is a library call on baseline x86-64.
    const double t = (x - x0_) * scale_;
    const std::size_t k = static_cast<std::size_t>(t);
    const double w = t - static_cast<double>(k);
    return samples_[k] + w * (samples_[k + 1] - samples_[k]);
  }

  // The same per float lane (in single precision).
  [[gnu::always_inline]] lanes::Floats operator()(lanes::Floats x) const {
    const float last = static_cast<float>(lanes_.size() - 2);  // the interval count
    const lanes::Floats t = lanes::clamp((x - static_cast<float>(x0_)) * static_cast<float>(scale_),
                                         lanes::Floats{}, lanes::Floats{} + last);
    const lanes::Ints k = __builtin_convertvector(t, lanes::Ints);
    const lanes::Floats w = t - __builtin_convertvector(k, lanes::Floats);
    // Each lane loads its sample, step and the next pair (lanes_ ends with a spare pair); the
    // transpose puts the samples in `value` and the steps in `slope`.
    lanes::Floats value = lanes::load(lanes_[static_cast<std::size_t>(k[0])].data());
    lanes::Floats slope = lanes::load(lanes_[static_cast<std::size_t>(k[1])].data());
    lanes::Floats c = lanes::load(lanes_[static_cast<std::size_t>(k[2])].data());
    lanes::Floats d = lanes::load(lanes_[static_cast<std::size_t>(k[3])].data());
    lanes::transpose(value, slope, c, d);
    return value + w * slope;
  }
#ifdef SG_WIDE_LANES
  // Eight lanes as two fours: the same operations per lane.
  template <class V>
  [[gnu::always_inline]] V operator()(V x) const requires std::is_same_v<V, lanes::WideFloats<>> {
    return lanes::join((*this)(lanes::low(x)), (*this)(lanes::high(x)));
  }
#endif

 private:
  double x0_ = 0.0, x1_ = 1.0, scale_ = 1.0;
  std::vector<double> samples_{0.0, 0.0};
  std::vector<std::array<float, 2>> lanes_{{0.0f, 0.0f}, {0.0f, 0.0f}};  // sample, step to next
};

}  // namespace sg
