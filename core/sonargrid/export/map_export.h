#pragma once
// Exports of a built map: a PNG coloured by the 16 levels (north up, one pixel per cell times
// `scale`, optional legend) and a ROS map_server pair (`.yaml` + `.pgm`).

#include <string>

#include "sonargrid/export/palette.h"
#include "sonargrid/occupancy_map.h"

namespace sg {

struct PngOptions {
  int scale = 1;         // pixels per cell
  bool legend = false;   // a strip with the 16 levels and their numbers below the map
  const LevelPalette* palette = nullptr;  // nullptr: defaultLevelPalette()
};

// Throws std::runtime_error naming the path when the file cannot be written.
void writeMapPng(const OccupancyMap& map, const std::string& path, const PngOptions& options = {});

// Writes BASENAME.yaml and BASENAME.pgm (map_server convention, negate 0: pixel = 255 (1 - p),
// never-observed cells 205). Throws std::runtime_error naming the path on failure.
void writeRosMap(const OccupancyMap& map, const std::string& basename);

}  // namespace sg
