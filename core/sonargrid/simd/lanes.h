// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Four single-precision lanes, for evaluating a cone model on a row of cells at a time (GCC and
// Clang vector extensions: SSE on x86-64, plain scalar code on a target without vectors).
// The helpers below are written so that the same model formula compiles for one double (the
// model's evaluate(), what the beam view shows) and for four floats (the footprint): a comparison
// gives a bool or a lane mask, and `mask ? a : b` picks per lane.

#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace sg {

// The code a cone model's rows are evaluated with: four float lanes (any x86-64), or eight built
// for AVX2, or the same eight built for AVX-512; and the rules' run kernels (run_kernels.cpp):
// four double lanes (any x86-64, or AVX2), or eight with masks built for AVX-512. Every one gives
// the same bits.
enum class ConeLanes : int { Four, Avx2, Avx512 };

// What coneRuns() evaluates rows with, and the run kernels update cells with: the widest of
// ConeLanes the CPU has, unless a test asked for less (testing::limitConeLanes, registry_hooks.h).
ConeLanes coneLanes();

}  // namespace sg

namespace sg::lanes {

using Floats = float __attribute__((vector_size(16)));
using Ints = std::int32_t __attribute__((vector_size(16)));
constexpr int kWidth = 4;

// std::max / std::min / std::clamp, for a double or per lane.
template <class T>
[[gnu::always_inline]] inline T max(T a, T b) {
  return a < b ? b : a;
}
template <class T>
[[gnu::always_inline]] inline T min(T a, T b) {
  return b < a ? b : a;
}
template <class T>
[[gnu::always_inline]] inline T clamp(T v, T lo, T hi) {
  return min(max(v, lo), hi);
}
inline double abs(double x) {
  return std::abs(x);
}
inline Floats abs(Floats x) {
  return reinterpret_cast<Floats>(reinterpret_cast<Ints>(x) & 0x7fffffff);
}

// Whether every lane of a mask is set.
inline bool all(Ints m) {
  std::uint64_t w[2];
  std::memcpy(w, &m, sizeof w);
  return (w[0] & w[1]) == ~std::uint64_t{0};
}

// Four unaligned floats from memory.
inline Floats load(const float* p) {
  Floats v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// Rows a, b, c, d of a 4 × 4 matrix become its columns.
inline void transpose(Floats& a, Floats& b, Floats& c, Floats& d) {
  const Floats t0 = __builtin_shufflevector(a, b, 0, 4, 1, 5);
  const Floats t1 = __builtin_shufflevector(c, d, 0, 4, 1, 5);
  const Floats t2 = __builtin_shufflevector(a, b, 2, 6, 3, 7);
  const Floats t3 = __builtin_shufflevector(c, d, 2, 6, 3, 7);
  a = __builtin_shufflevector(t0, t1, 0, 1, 4, 5);
  b = __builtin_shufflevector(t0, t1, 2, 3, 6, 7);
  c = __builtin_shufflevector(t2, t3, 0, 1, 4, 5);
  d = __builtin_shufflevector(t2, t3, 2, 3, 6, 7);
}

// Eight lanes, for the cone models' rows on a CPU with AVX2 (cone_model.h, GCC on x86-64 only:
// Clang refuses 32-byte vectors between functions built for the baseline even when inlined).
// Templates, so that only a file that evaluates a row in eight lanes instantiates them (GCC notes
// the ABI of 32-byte vector arguments in every function it compiles for the baseline).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define SG_WIDE_LANES 1
constexpr int kWideWidth = 8;
template <class = void>
using WideFloats = float __attribute__((vector_size(32)));
template <class = void>
using WideInts = std::int32_t __attribute__((vector_size(32)));

template <class V>
[[gnu::always_inline]] inline V abs(V x) requires std::is_same_v<V, WideFloats<>> {
  return reinterpret_cast<V>(reinterpret_cast<WideInts<>>(x) & 0x7fffffff);
}
template <class V>
[[gnu::always_inline]] inline bool all(V m) requires std::is_same_v<V, WideInts<>> {
  std::uint64_t w[4];
  std::memcpy(w, &m, sizeof w);
  return (w[0] & w[1] & w[2] & w[3]) == ~std::uint64_t{0};
}
// The low and high four lanes, and back.
template <class V>
[[gnu::always_inline]] inline Floats low(V x) requires std::is_same_v<V, WideFloats<>> {
  return __builtin_shufflevector(x, x, 0, 1, 2, 3);
}
template <class V>
[[gnu::always_inline]] inline Floats high(V x) requires std::is_same_v<V, WideFloats<>> {
  return __builtin_shufflevector(x, x, 4, 5, 6, 7);
}
template <class V = WideFloats<>>
[[gnu::always_inline]] inline V join(Floats a, Floats b) {
  return __builtin_shufflevector(a, b, 0, 1, 2, 3, 4, 5, 6, 7);
}
#endif

}  // namespace sg::lanes
