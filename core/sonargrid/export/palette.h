// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The 16-level certainty palette shared by exports and views (level 0 = certainly free,
// 15 = certainly occupied).

#include <array>
#include <cstdint>

namespace sg {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Rgb&) const = default;
};

using LevelPalette = std::array<Rgb, 16>;

const LevelPalette& defaultLevelPalette();
const LevelPalette& greyLevelPalette();

}  // namespace sg
