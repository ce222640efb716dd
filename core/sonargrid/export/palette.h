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

// The colour of a never-observed cell, in every rule and palette: a warm khaki that none of the
// levels is near, so that "never observed" is not read as free (level 0, HIMM's CV 0) nor as the
// grey of a cell observed to be uncertain (levels 7–8).
inline constexpr Rgb kUnknownColour{205, 192, 140};
const LevelPalette& greyLevelPalette();

}  // namespace sg
