// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/export/palette.h"

namespace sg {

// A diverging blue - grey - red scheme. The colours were chosen in CIELAB: lightness L* falls
// evenly from 98 (level 0) to 8 (level 15), so the order survives greyscale printing and luma is
// strictly decreasing; the hue is blue on the free side, neutral around p = 0.5 (level 7 a cool
// grey, level 8 a warm one, so the two "unknown" levels still differ) and red on the occupied side;
// chroma peaks at levels 5 and 11 and was kept low where sRGB cannot hold it. Adjacent levels are
// at least ~8 CIE76 units apart (a difference of ~2 is just noticeable). docs/exports.md lists
// the table.
const LevelPalette& defaultLevelPalette() {
  static const LevelPalette palette{{
      {246, 249, 255},  // 0: certainly free
      {223, 234, 255},  // 1
      {197, 219, 255},  // 2
      {169, 203, 253},  // 3
      {143, 188, 247},  // 4
      {116, 170, 239},  // 5
      {120, 152, 199},  // 6
      {126, 135, 148},  // 7: unknown, cool grey
      {133, 115, 110},  // 8: unknown, warm grey
      {144, 90, 78},    // 9
      {146, 64, 50},    // 10
      {143, 34, 24},    // 11
      {120, 25, 19},    // 12
      {95, 20, 17},     // 13
      {70, 16, 13},     // 14
      {45, 14, 8},      // 15: certainly occupied
  }};
  return palette;
}

// White (free) to black (occupied) in equal steps: 255 / 15 = 17 exactly, so level k is 255 - 17k.
const LevelPalette& greyLevelPalette() {
  static const LevelPalette palette = [] {
    LevelPalette p{};
    for (int k = 0; k < static_cast<int>(p.size()); ++k) {
      const auto v = static_cast<std::uint8_t>(255 - 17 * k);
      p[static_cast<std::size_t>(k)] = Rgb{v, v, v};
    }
    return p;
  }();
  return palette;
}

}  // namespace sg
