// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Exports of a built map: a PNG coloured by the 16 levels (north up, one pixel per cell times
// `scale`, optional legend) and a ROS map_server pair (`.yaml` + `.pgm`).

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sonargrid/engine/occupancy_map.h"
#include "sonargrid/export/palette.h"

namespace sg {

struct PngOptions {
  int scale = 1;        // pixels per cell
  bool legend = false;  // a strip with the 16 levels and their numbers below the map
  const LevelPalette* palette = nullptr;  // nullptr: defaultLevelPalette()
  // The colour of never-observed cells (e.g. kUnknownColour, as the app draws them); nullopt:
  // their level's colour, as paper 000 Fig. 4 prints them.
  std::optional<Rgb> unknown;
  // Drawn over the cells, in world metres: e.g. a reference map's edges (paper 000 Fig. 4 overlays
  // the obstacles as solid lines) and small circles at the robot's stops.
  std::vector<std::pair<Position, Position>> lines;
  std::vector<Position> markers;
  Rgb overlayColour{0, 0, 0};
};

// The exact pixels writeMapPng puts in the PNG (legend included), so that tests and callers without
// OpenCV can inspect the picture. Throws std::invalid_argument like writeMapPng.
struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<Rgb> pixels;  // row-major, row 0 at the top
  const Rgb& at(int x, int y) const {
    return pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                  static_cast<std::size_t>(x)];
  }
};
RgbImage renderMapImage(const OccupancyMap& map, const PngOptions& options = {});

// Encoded in memory (lossless PNG whatever the name's extension) and written atomically
// (base/atomic_file.h). Throws FileWriteError ("cannot write PNG 'PATH': REASON") when the file
// cannot be written, and std::invalid_argument for scale < 1, an empty grid, a level layer of the
// wrong size or a level above 15.
void writeMapPng(const OccupancyMap& map, const std::string& path, const PngOptions& options = {});

// Writes BASENAME.yaml and BASENAME.pgm (map_server convention, negate 0: pixel = 255 (1 - p),
// never-observed cells 205), each written atomically, the image first. Throws FileWriteError naming
// the file on failure, and
// std::invalid_argument for an empty grid, layers of the wrong size or a non-finite probability.
void writeRosMap(const OccupancyMap& map, const std::string& basename);

}  // namespace sg
