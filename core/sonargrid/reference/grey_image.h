// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The 8-bit grey images of map_server maps. PGM (P5 binary and P2 text, maxval <= 255) is read
// here, so that its errors name the header line and field; any other format (PNG...) is decoded by
// OpenCV, 8-bit only, colour channels averaged with integer division as map_server does, alpha
// ignored. At most 100 million pixels.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "sonargrid/base/log_error.h"

namespace sg {

struct GreyImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  // row-major, row 0 at the top
};

// Throws LogError naming the file, the line (PGM header lines) and the field.
GreyImage readGreyImage(const std::string& path);
GreyImage parsePgm(std::string_view bytes, const std::string& displayName);

}  // namespace sg
