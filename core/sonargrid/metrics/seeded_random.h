// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Random draws that are the same on every platform: std::mt19937_64 is fully specified by the
// standard, but std::uniform_int_distribution is not (each library maps bits to integers its own
// way), so the mapping from bits to a bounded integer is ours.

#include <cstdint>
#include <random>

namespace sg {

class SeededRandom {
 public:
  explicit SeededRandom(std::uint64_t seed) : engine_(seed) {}

  // Uniform in [0, n), n > 0, by rejection: draws below 2^64 mod n are discarded, so every
  // residue is equally likely.
  std::uint64_t below(std::uint64_t n) {
    const std::uint64_t threshold = (0 - n) % n;  // 2^64 mod n
    std::uint64_t x = engine_();
    while (x < threshold) x = engine_();
    return x % n;
  }

 private:
  std::mt19937_64 engine_;
};

}  // namespace sg
