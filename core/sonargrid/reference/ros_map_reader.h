// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// ROS map_server maps (`.yaml` + image), read two ways (docs/metrics.md, "ROS map_server maps"):
//   - as a reference: the occupancy image says where obstacles are (p > occupied_thresh), where
//     space is free (p < free_thresh) and where nobody knows;
//   - as a built map to score (`sonargrid-cli score --map`): p(occ) from each pixel, and its
//     CV = round(15 p).
//
// The YAML is the small subset map_server writes: one `key: value` per line, `#` comments, plain
// or quoted scalars and the flow sequence of `origin`. Keys image, resolution, origin, negate,
// occupied_thresh and free_thresh are required (as ROS 1 map_server requires them); mode is
// optional (trinary). The image is read by readGreyImage (grey_image.h). Pixel (0, 0) is the
// top-left of the image; origin is the bottom-left cell.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "sonargrid/base/log_error.h"
#include "sonargrid/engine/occupancy_map.h"
#include "sonargrid/reference/reference_map.h"

namespace sg {

struct RosMap {
  std::string yamlPath;
  std::string imagePath;  // as resolved against the YAML's folder
  GridSpec spec;          // origin, resolution and the image's size
  bool negate = false;
  double occupiedThresh = 0.65;
  double freeThresh = 0.196;
  std::string mode = "trinary";      // trinary or scale ("raw" is refused)
  std::vector<std::uint8_t> pixels;  // grid order: index = iy * width + ix, iy = 0 the bottom row

  // map_server: p(occ) = (255 - v) / 255, with v = 255 - pixel when negate is set.
  double occupancy(std::size_t cell) const;
  // The value map_server's map_saver (and our exporter) writes for never-observed cells: 205 after
  // negation, p = 50/255.
  bool unknownPixel(std::size_t cell) const;
};

// Throws LogError naming the YAML or image file, the line (YAML lines, PGM header lines) and the
// key or field.
RosMap readRosMap(const std::string& yamlPath);

// The reference raster: p > occupied_thresh is an obstacle, p < free_thresh is free, the rest (205
// included) unknown.
ReferenceMap rosMapAsReference(const RosMap& map);

// A built map to score: p = occupancy(), level = CV = round(15 p), filled when CV > 0. Cells with
// the unknown pixel (205) are unobserved: p 0.5, level 8, never filled (docs/metrics.md).
OccupancyMap rosMapAsBuiltMap(const RosMap& map);

}  // namespace sg
