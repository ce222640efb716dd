// SPDX-License-Identifier: BSD-3-Clause
// Konolige's multiple-target model (paper 001 §2.2, after Konolige 1997), in the reading
// docs/models.md gives ("Konolige"): the printed ratio of densities becomes the likelihood ratio
//   λ = p(D | cell occupied) / p(D | cell empty)
// of the first return D. An occupied cell at range r and angle θ echoes with probability
// g = a(r)·exp(-θ²/2σ²) (σ = ω/2, the printed lobe width), at a range spread N(r, d(r)²); false
// returns arrive at F per metre. With the other cells' contributions shared by both hypotheses:
//   p(D | occ) = g·N(D; r, d) + F·(1 − g·Φ((D − r)/d)),   p(D | emp) = F,
//   λ = g·φ(z)/(d·F) + 1 − g·Φ(z),  z = (D − r)/d.
// Cells well short of D get λ = 1 − g (free evidence, at most a0 strong: the gentle updates of
// paper 001 §6), cells at D get a strong occupied ratio that F keeps finite, cells beyond get
// λ → 1 (nothing). A no-echo reading gives λ = 1 − g over the whole cone: the occupied cell would
// have been heard with probability g.

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <numbers>
#include <type_traits>

#include "sonargrid/models/cone_model.h"
#include "sonargrid/models/model_classes.h"
#include "sonargrid/models/sampled_function.h"
#include "sonargrid/testing/registry_hooks.h"

namespace sg {
namespace {

struct KonoligeSettings {
  double omega = 0.436;            // rad, full aperture
  double falseRate = 0.05;         // F, per metre
  double attenuation = 0.6;        // a0
  double attenuationSlope = 0.4;   // k, 1/m: a(r) = a0 (1 - min(1, k r))
  double sd0 = 0.01, sd1 = 0.015;  // d(r) = d0 + d1 r, metres
  bool noEchoFree = false;
};

constexpr double kZMax = 8.0;  // |z| beyond which φ and Φ are 0/1 to double precision in effect
// Cells this many deviations past D are left alone. There λ − 1 = g φ(z)/(d F) − g Φ(z) is at most
// ~2e-3 at the paper's values (docs/models.md gives the bound); nearer cells carry the evidence.
// z < −5 ⟺ r > (D + 5 d₀)/(1 − 5 d₁), so the cut is the reading's reach, not a per-cell test.
constexpr double kZShadow = -5.0;

double shadowRange(const KonoligeSettings& s, double D) {
  return (D - kZShadow * s.sd0) / (1.0 + kZShadow * s.sd1);
}

// φ(z) and Φ(z) sampled together, so one index serves both; in double, and in float for lanes.
class NormalTable {
 public:
  NormalTable() {
    for (int i = 0; i <= kIntervals + 1; ++i) {
      const double z = -kZMax + std::min(i, kIntervals) / kScale;
      pdf_[static_cast<std::size_t>(i)] =
          std::exp(-0.5 * z * z) / std::sqrt(2.0 * std::numbers::pi);
      cdf_[static_cast<std::size_t>(i)] = 0.5 * std::erfc(-z / std::numbers::sqrt2);
    }
    for (std::size_t i = 0; i <= kIntervals; ++i) {
      lanes_[i] = {static_cast<float>(pdf_[i]), static_cast<float>(pdf_[i + 1] - pdf_[i]),
                   static_cast<float>(cdf_[i]), static_cast<float>(cdf_[i + 1] - cdf_[i])};
    }
    // The float lanes' last two rows, which a z within a few ulps of kZMax or above it reads
    // (KonoligeShape::flatEnd): Φ is 1 there to the last bit, φ at most the row before the last.
    const auto& edge = lanes_[kIntervals - 1];
    const auto& end = lanes_[kIntervals];
    flatCdfIsOne_ = edge[2] == 1.0f && end[2] == 1.0f && edge[3] >= 0.0f && edge[3] < 0x1p-26f &&
                    end[3] == 0.0f;
    flatPdf_ = static_cast<double>(edge[0]);
  }
  // Whether Φ reads exactly 1 in the lanes at z >= kZMax (to within a few ulps), and the largest
  // φ they read there.
  bool flatCdfIsOne() const { return flatCdfIsOne_; }
  double flatPdf() const { return flatPdf_; }
  // Linear interpolation; z is at least kZShadow here, and above kZMax both are flat.
  void operator()(double z, double& pdf, double& cdf) const {
    const double t = (std::min(z, kZMax) + kZMax) * kScale;
    const std::size_t k = static_cast<std::size_t>(t);
    const double w = t - static_cast<double>(k);
    pdf = pdf_[k] + w * (pdf_[k + 1] - pdf_[k]);
    cdf = cdf_[k] + w * (cdf_[k + 1] - cdf_[k]);
  }
  [[gnu::always_inline]] void operator()(lanes::Floats z, lanes::Floats& pdf,
                                         lanes::Floats& cdf) const {
    // z · kScale is exact (a power of two), and so is its distance w from the sample below it: in
    // float, (z + kZMax) · kScale would round w to 2.4e-4 of an interval, and λ multiplies φ by
    // 1/(d F), some 500.
    const lanes::Floats zs =
        lanes::clamp(z, lanes::Floats{} - float(kZMax), lanes::Floats{} + float(kZMax)) *
        float(kScale);
    lanes::Floats below = __builtin_convertvector(__builtin_convertvector(zs, lanes::Ints),
                                                  lanes::Floats);  // towards zero
    below = below > zs ? below - 1.0f : below;                     // floor
    const lanes::Ints k = __builtin_convertvector(below, lanes::Ints) + kIntervals / 2;
    const lanes::Floats w = zs - below;
    // One row {φ, Δφ, Φ, ΔΦ} per lane, transposed into four vectors.
    lanes::Floats p0 = lanes::load(lanes_[static_cast<std::size_t>(k[0])].data());
    lanes::Floats p1 = lanes::load(lanes_[static_cast<std::size_t>(k[1])].data());
    lanes::Floats c0 = lanes::load(lanes_[static_cast<std::size_t>(k[2])].data());
    lanes::Floats c1 = lanes::load(lanes_[static_cast<std::size_t>(k[3])].data());
    lanes::transpose(p0, p1, c0, c1);
    pdf = p0 + w * p1;
    cdf = c0 + w * c1;
  }
#ifdef SG_WIDE_LANES
  // Eight lanes as two fours: the same operations per lane.
  template <class V>
  [[gnu::always_inline]] void operator()(
      V z, V& pdf, V& cdf) const requires std::is_same_v<V, lanes::WideFloats<>> {
    lanes::Floats p0, c0, p1, c1;
    (*this)(lanes::low(z), p0, c0);
    (*this)(lanes::high(z), p1, c1);
    pdf = lanes::join(p0, p1);
    cdf = lanes::join(c0, c1);
  }
#endif

 private:
  static constexpr int kIntervals = 4096;
  static constexpr double kScale = kIntervals / (2.0 * kZMax);
  std::array<double, kIntervals + 2> pdf_{}, cdf_{};
  std::array<std::array<float, 4>, kIntervals + 1> lanes_{};
  bool flatCdfIsOne_ = false;
  double flatPdf_ = 1.0;
};

// testing::konoligeFlatEnd (registry_hooks.h).
std::atomic<bool> flatEndAllowed{true};

const NormalTable& normalTable() {
  static const NormalTable t;
  return t;
}

// Per reading; S is double for evaluate() and float for the footprint (cone_model.h).
template <class S>
struct KonoligeShape {
  bool echo = true;
  // The float lanes may take λ = 1 − g where every lane is at z >= kZMax (flatEnd, below).
  bool flatEnd = false;
  S range, invF;
  S attenuation, attenuationSlope, sd0, sd1;
  const SampledFunction* lobe = nullptr;
  const NormalTable* normal = nullptr;

  template <class T>
  [[gnu::always_inline]] ConeValue<T> value(T r, T t) const {
    const T a = attenuation * (S(1) - lanes::min(T{} + S(1), attenuationSlope * r));
    const T g = a * (*lobe)(t);
    T lambda = S(1) - g;  // no echo, or (float lanes) every lane well short of it
    if (echo && !allAtFlatEnd(r)) {
      const T invD = S(1) / (sd0 + sd1 * r);
      T pdf, cdf;
      (*normal)((range - r) * invD, pdf, cdf);
      lambda = g * pdf * invF * invD + S(1) - g * cdf;
    }
    // λ to the Footprint's three values: P = λ/(1 + λ), pO = 2P − 1 = (λ − 1)/(λ + 1), pE = −that.
    const T inv = S(1) / (S(1) + lambda);
    const auto occupied = lambda > S(1);
    // Past the detection range (a = 0) the reading says nothing.
    const auto heard = a > S(0);
    return {heard && occupied, heard && !occupied, occupied ? T{} : (S(1) - lambda) * inv,
            occupied ? (lambda - S(1)) * inv : T{}, lambda * inv};
  }

  // Whether every lane has D − r >= kZMax · d(r), which most groups of a cone short of the echo
  // have. There, in float lanes, the formula below gives λ = 1 − g bit for bit, without its
  // division: z = (D − r) · (1/d) is then at least kZMax to within a few ulps, so the look-up reads
  // the table's last two rows, where Φ is exactly 1 (g Φ = g) and g φ/(d F) is below 2⁻²⁶ (flatEnd
  // is set only then), which 1 absorbs: (g φ/(d F) + 1) − g Φ = 1 − g. Not in double (evaluate()),
  // where Φ(8) is 1 − 6·10⁻¹⁶.
  template <class T>
  [[gnu::always_inline]] bool allAtFlatEnd(T r) const {
    if constexpr (std::is_same_v<T, double>) {
      return false;
    } else {
      return flatEnd && lanes::all(range - r >= S(kZMax) * (sd0 + sd1 * r));
    }
  }
};

class KonoligeModel final : public ConeModel<KonoligeModel> {
 public:
  KonoligeModel();
  static const ModelInfo& staticInfo();
  void configure(const ParameterSet& params) override;
  double reach(double maxRange) const override;
  template <class S>
  ConeBeam<KonoligeShape<S>> prepare(double range, double maxRange) const;

 private:
  KonoligeSettings s_;
  SampledFunction lobe_;       // exp(-θ²/2σ²) over |θ| in [0, ω/2]
  bool flatEndExact_ = false;  // whether λ = 1 − g is exact at the flat end (configure())
};

}  // namespace

KonoligeModel::KonoligeModel() {
  configure(ParameterSet(staticInfo().parameters));
}

const ModelInfo& KonoligeModel::staticInfo() {
  static const ModelInfo info{
      "konolige",
      "Konolige multiple-target model",
      "paper 001 §2.2 (after Konolige 1997); likelihood-ratio reading (docs/models.md)",
      {
          {"omega", "ω", "deg", 5.0, 90.0, 25.0, "paper 001 §2.2 (lobe width follows the aperture)",
           "Full cone angle; the angular lobe is a Gaussian of σ = ω/2, cut at ±ω/2."},
          {"false_rate", "F", "1/m", 0.001, 1.0, 0.05, "paper 001 §2.2 (F = 0.05)",
           "Density of false returns; keeps the occupied likelihood ratio finite."},
          {"attenuation", "a₀", "", 0.0, 1.0, 0.6,
           "paper 001 §2.2: a(r) = 0.6 (1 − min(1, 0.4 r)), a₀ = 0.6",
           "Detection probability of an occupied cell at the transducer."},
          {"attenuation_slope", "k", "1/m", 0.0, 5.0, 0.4,
           "paper 001 §2.2: a(r) = 0.6 (1 − min(1, 0.4 r)), k = 0.4 /m",
           "a(r) falls to 0 at r = 1/k (2.5 m in the paper)."},
          {"range_sd0", "d₀", "m", 0.001, 0.5, 0.01,
           "paper 001 §2.2: d(r) = 0.01 + 0.015 r, d₀ = 0.01 m",
           "Fixed part of the range deviation (a standard deviation)."},
          {"range_sd1", "d₁", "m/m", 0.0, 0.19, 0.015,
           "paper 001 §2.2: d(r) = 0.01 + 0.015 r, d₁ = 0.015",
           "Growth of the range standard deviation per metre of range."},
          noEchoParameter("λ = 1 − g(r, θ) over the cone up to the detection range"),
      },
      // Paper 001 §5.1 compares its sonar models on the log update (§3.3).
      "log",
      {"occupied (λ > 1)", "free (λ < 1)", ""}};
  return info;
}

void KonoligeModel::configure(const ParameterSet& p) {
  s_.omega = degToRad(p.get("omega"));
  s_.falseRate = p.get("false_rate");
  s_.attenuation = p.get("attenuation");
  s_.attenuationSlope = p.get("attenuation_slope");
  s_.sd0 = p.get("range_sd0");
  s_.sd1 = p.get("range_sd1");
  s_.noEchoFree = p.get("no_echo") != 0.0;
  const double sigma = s_.omega / 2.0;
  lobe_ = SampledFunction(0.0, s_.omega / 2.0, 1024,
                          [sigma](double t) { return std::exp(-t * t / (2.0 * sigma * sigma)); });
  // KonoligeShape::allAtFlatEnd: g <= a0 (the lobe is at most 1, and k >= 0) and 1/d <= 1/d0 (d1,
  // r >= 0); the float lanes' products round by far less than the factor of 4 between 2⁻²⁶ and
  // 2⁻²⁴ (half an ulp of 1), below which 1 + x rounds to 1. At the sliders' limits a0 φ/(d0 F) is
  // 5.2·10⁻⁹ at most, under 2⁻²⁶ ≈ 1.5·10⁻⁸.
  const NormalTable& normal = normalTable();
  flatEndExact_ = normal.flatCdfIsOne() && s_.attenuation >= 0.0 && s_.attenuationSlope >= 0.0 &&
                  s_.sd0 > 0.0 && s_.sd1 >= 0.0 && s_.falseRate > 0.0 &&
                  s_.attenuation * normal.flatPdf() / (s_.sd0 * s_.falseRate) < 0x1p-26;
}

template <class S>
ConeBeam<KonoligeShape<S>> KonoligeModel::prepare(double range, double maxRange) const {
  ConeBeam<KonoligeShape<S>> b;
  const bool echo = std::isfinite(range);
  if (!echo && !s_.noEchoFree) return b;
  b.active = true;
  b.halfAngle = s_.omega / 2.0;
  // Beyond z = −5 (or the maximum range without an echo) and beyond the detection range 1/k the
  // reading says nothing: no cell there needs visiting.
  double reach = echo ? shadowRange(s_, range) : maxRange;
  if (s_.attenuationSlope > 0.0) reach = std::min(reach, 1.0 / s_.attenuationSlope);
  b.reach = reach;
  KonoligeShape<S>& k = b.shape;
  k.echo = echo;
  k.range = S(echo ? range : maxRange);
  k.invF = S(1.0 / s_.falseRate);
  k.attenuation = S(s_.attenuation);
  k.attenuationSlope = S(s_.attenuationSlope);
  k.sd0 = S(s_.sd0);
  k.sd1 = S(s_.sd1);
  k.lobe = &lobe_;
  k.normal = &normalTable();
  k.flatEnd = echo && flatEndExact_ && flatEndAllowed.load(std::memory_order_relaxed);
  return b;
}

double KonoligeModel::reach(double maxRange) const {
  double r = shadowRange(s_, maxRange);
  if (s_.attenuationSlope > 0.0) r = std::min(r, 1.0 / s_.attenuationSlope);
  return r;
}

bool testing::konoligeFlatEnd(bool allowed) {
  return flatEndAllowed.exchange(allowed);
}

std::unique_ptr<SensorModel> makeKonoligeModel() {
  return std::make_unique<KonoligeModel>();
}
const ModelInfo& konoligeModelInfo() {
  return KonoligeModel::staticInfo();
}

}  // namespace sg
