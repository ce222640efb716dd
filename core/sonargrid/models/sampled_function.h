#pragma once
// A smooth function of one variable sampled on a uniform grid and read back with linear
// interpolation: how the hot path evaluates exp and erf without calling them per cell. Outside
// [x0, x1] it returns the end values.

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

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

 private:
  double x0_ = 0.0, x1_ = 1.0, scale_ = 1.0;
  std::vector<double> samples_{0.0, 0.0};
};

}  // namespace sg
