// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/export/map_export.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "sonargrid/base/atomic_file.h"

namespace sg {
namespace {

namespace fs = std::filesystem;

// ---- shared helpers

// A grid with no cells has nothing to draw, and a negative size would make cellCount() wrap.
void requireNonEmptyGrid(const GridSpec& spec, const char* what) {
  if (spec.width <= 0 || spec.height <= 0)
    throw std::invalid_argument(std::string(what) + ": the grid is empty (" +
                                std::to_string(spec.width) + " x " + std::to_string(spec.height) +
                                " cells)");
}

template <typename Layer>
void requireLayerSize(const GridSpec& spec, const Layer& layer, const char* layerName,
                      const char* what) {
  if (layer.size() != spec.cellCount())
    throw std::invalid_argument(std::string(what) + ": layer '" + layerName + "' has " +
                                std::to_string(layer.size()) + " entries, the grid has " +
                                std::to_string(spec.cellCount()) + " cells");
}

// ---- PNG

// Beyond this many pixels the BGR buffer alone would pass 800 MB: a caller's scale is wrong.
constexpr long long kMaxPixels = 1LL << 28;

// Legend layout (docs/exports.md): 16 swatch columns of `swatch` pixels, at least kMinSwatch so
// that the numbers stay readable under tiny maps, wider when the map is wider than 16 of them.
constexpr int kMinSwatch = 32;
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

struct LegendLayout {
  int swatch = 0;     // width of one column
  int pad = 0;        // white space above, between and below the rows
  int boxHeight = 0;  // height of a coloured swatch
  int gap = 0;        // white space either side of a swatch inside its column
  int thickness = 1;  // text stroke
  double fontScale = 1.0;
  int textHeight = 0;
  int stripHeight = 0;
};

LegendLayout legendLayout(int mapWidthPixels) {
  LegendLayout l;
  l.swatch = std::max(kMinSwatch, mapWidthPixels / kLevels);
  l.pad = l.swatch / 4;
  l.boxHeight = l.swatch / 2;
  l.gap = std::max(1, l.swatch / 16);
  l.thickness = std::max(1, l.swatch / 40);
  // The widest label, "15", gets 70 % of a column.
  int baseline = 0;
  const cv::Size unit = cv::getTextSize("15", kFont, 1.0, l.thickness, &baseline);
  l.fontScale = 0.7 * l.swatch / unit.width;
  l.textHeight = cv::getTextSize("15", kFont, l.fontScale, l.thickness, &baseline).height;
  l.stripHeight = l.pad + l.boxHeight + l.pad + l.textHeight + l.pad;
  return l;
}

cv::Scalar bgr(const Rgb& c) {
  return cv::Scalar(c.b, c.g, c.r);
}

void drawLegend(cv::Mat& image, int top, const LegendLayout& l, const LevelPalette& palette) {
  // An outline keeps the near-white level 0 visible on the white strip.
  const cv::Scalar outline(160, 160, 160);
  const cv::Scalar ink(0, 0, 0);
  for (int k = 0; k < kLevels; ++k) {
    const int x0 = k * l.swatch + l.gap;
    const int x1 = (k + 1) * l.swatch - l.gap;  // exclusive
    const cv::Rect box(x0, top + l.pad, x1 - x0, l.boxHeight);
    cv::rectangle(image, box, bgr(palette[static_cast<std::size_t>(k)]), cv::FILLED);
    cv::rectangle(image, box, outline, 1);

    const std::string label = std::to_string(k);
    int baseline = 0;
    const cv::Size size = cv::getTextSize(label, kFont, l.fontScale, l.thickness, &baseline);
    const cv::Point origin(k * l.swatch + (l.swatch - size.width) / 2,
                           top + l.pad + l.boxHeight + l.pad + l.textHeight);
    cv::putText(image, label, origin, kFont, l.fontScale, ink, l.thickness, cv::LINE_AA);
  }
}

// Lines and markers in world metres, anti-aliased at sub-pixel precision (4 fractional bits), and
// clipped to the map so that they never run into the legend.
void drawOverlay(cv::Mat& image, int mw, int mh, const GridSpec& spec, const PngOptions& options) {
  constexpr int kShift = 4;
  const double perMetre = options.scale / spec.cellSize * (1 << kShift);
  auto pixel = [&](const Position& p) {
    return cv::Point(static_cast<int>(std::lround((p.x() - spec.origin.x()) * perMetre)),
                     static_cast<int>(std::lround(mh * double(1 << kShift) -
                                                  (p.y() - spec.origin.y()) * perMetre)));
  };
  cv::Mat area = image(cv::Rect(0, 0, mw, mh));
  const cv::Scalar colour = bgr(options.overlayColour);
  const int thickness = std::max(1, options.scale / 3);
  for (const auto& [a, b] : options.lines)
    cv::line(area, pixel(a), pixel(b), colour, thickness, cv::LINE_AA, kShift);
  const int radius = std::max(2, options.scale) << kShift;
  for (const Position& m : options.markers)
    cv::circle(area, pixel(m), radius, colour, thickness, cv::LINE_AA, kShift);
}

cv::Mat renderBgr(const OccupancyMap& map, const PngOptions& options) {
  constexpr const char* what = "map PNG";
  if (options.scale < 1)
    throw std::invalid_argument(std::string(what) + ": scale must be at least 1, got " +
                                std::to_string(options.scale));
  const GridSpec& spec = map.spec;
  requireNonEmptyGrid(spec, what);
  requireLayerSize(spec, map.level, "level", what);
  for (std::size_t i = 0; i < map.level.size(); ++i)
    if (map.level[i] >= kLevels)
      throw std::invalid_argument(std::string(what) + ": cell " + std::to_string(i) +
                                  " has level " + std::to_string(map.level[i]) +
                                  ", levels are 0.." + std::to_string(kLevels - 1));

  const long long mapWidth = static_cast<long long>(spec.width) * options.scale;
  const long long mapHeight = static_cast<long long>(spec.height) * options.scale;
  // Each side is checked first so that the product cannot overflow for an absurd scale.
  if (mapWidth > kMaxPixels || mapHeight > kMaxPixels || mapWidth * mapHeight > kMaxPixels)
    throw std::invalid_argument(std::string(what) + ": " + std::to_string(mapWidth) + " x " +
                                std::to_string(mapHeight) + " pixels is too large");
  const int mw = static_cast<int>(mapWidth);
  const int mh = static_cast<int>(mapHeight);

  LegendLayout legend;
  int width = mw;
  int height = mh;
  if (options.legend) {
    legend = legendLayout(mw);
    width = std::max(mw, kLevels * legend.swatch);
    height = mh + legend.stripHeight;
  }

  const LevelPalette& palette = options.palette ? *options.palette : defaultLevelPalette();
  cv::Mat image(height, width, CV_8UC3, cv::Scalar(255, 255, 255));

  // Image row 0 is the grid's top row (north up); build one pixel row per grid row and repeat it
  // `scale` times.
  for (int iy = spec.height - 1, block = 0; iy >= 0; --iy, ++block) {
    auto* first = image.ptr<cv::Vec3b>(block * options.scale);
    for (int ix = 0; ix < spec.width; ++ix) {
      const std::size_t i = spec.linear(CellIndex(ix, iy));
      const bool unknown =
          options.unknown && map.observed.size() == map.level.size() && map.observed[i] == 0;
      const Rgb& c = unknown ? *options.unknown : palette[map.level[i]];
      const cv::Vec3b px(c.b, c.g, c.r);
      std::fill_n(first + static_cast<std::ptrdiff_t>(ix) * options.scale, options.scale, px);
    }
    for (int r = 1; r < options.scale; ++r)
      std::copy_n(first, mw, image.ptr<cv::Vec3b>(block * options.scale + r));
  }

  if (!options.lines.empty() || !options.markers.empty()) drawOverlay(image, mw, mh, spec, options);
  if (options.legend) drawLegend(image, mh, legend, palette);
  return image;
}

// ---- ROS map_server

// Shortest text that parses back to exactly `v`, always with a decimal point so that YAML 1.1
// readers (PyYAML) see a float: "2" -> "2.0", "1e-05" -> "1.0e-05".
std::string formatNumber(double v) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  std::string s(buffer, result.ptr);
  if (s.find('.') == std::string::npos) {
    const auto e = s.find('e');
    s.insert(e == std::string::npos ? s.size() : e, ".0");
  }
  return s;
}

// The image key: plain when the name is unambiguous in YAML, double-quoted otherwise.
std::string yamlScalar(const std::string& text) {
  const bool plain =
      !text.empty() && text.front() != '-' && std::all_of(text.begin(), text.end(), [](char ch) {
        return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') ||
               ch == '.' || ch == '_' || ch == '-';
      });
  if (plain) return text;
  std::string out = "\"";
  for (char ch : text) {
    const auto u = static_cast<unsigned char>(ch);
    if (ch == '"' || ch == '\\') {
      out += '\\';
      out += ch;
    } else if (u < 0x20 || u == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", static_cast<unsigned>(u));
      out += hex;
    } else {
      out += ch;
    }
  }
  out += '"';
  return out;
}

// map_server's value for a cell never written; with negate 0 it reads as p = 50/255 = 0.196,
// which trinary mode classifies as unknown (not below free_thresh 0.196, not above 0.65).
constexpr std::uint8_t kRosUnknown = 205;

std::string pgmBytes(const OccupancyMap& map) {
  const GridSpec& spec = map.spec;
  // No comment line: the minimal header every PGM reader accepts.
  std::string out =
      "P5\n" + std::to_string(spec.width) + " " + std::to_string(spec.height) + "\n255\n";
  const std::size_t header = out.size();
  out.resize(header + spec.cellCount());
  std::size_t o = header;
  // PGM row 0 is the top of the picture, while the YAML origin is the bottom-left cell, so the
  // grid's top row iy = height - 1 comes first.
  for (int iy = spec.height - 1; iy >= 0; --iy) {
    for (int ix = 0; ix < spec.width; ++ix) {
      const std::size_t i = spec.linear(CellIndex(ix, iy));
      std::uint8_t value = kRosUnknown;
      if (map.observed[i] != 0) {
        const double p = map.probability[i];
        if (!std::isfinite(p))
          throw std::invalid_argument("ROS map: cell " + std::to_string(i) +
                                      " has a non-finite probability");
        // map_server (negate 0) reads occupancy as (255 - pixel) / 255.
        const double clamped = std::clamp(p, 0.0, 1.0);
        value = static_cast<std::uint8_t>(std::lround(255.0 * (1.0 - clamped)));
      }
      out[o++] = static_cast<char>(value);
    }
  }
  return out;
}

std::string yamlText(const OccupancyMap& map, const std::string& imageName) {
  const GridSpec& spec = map.spec;
  std::string out;
  out += "image: " + yamlScalar(imageName) + "\n";
  out += "resolution: " + formatNumber(spec.cellSize) + "\n";
  out += "origin: [" + formatNumber(spec.origin.x()) + ", " + formatNumber(spec.origin.y()) +
         ", 0.0]\n";
  out += "negate: 0\n";
  out += "occupied_thresh: 0.65\n";
  out += "free_thresh: 0.196\n";
  out += "mode: trinary\n";
  return out;
}

}  // namespace

RgbImage renderMapImage(const OccupancyMap& map, const PngOptions& options) {
  const cv::Mat bgrImage = renderBgr(map, options);
  RgbImage out;
  out.width = bgrImage.cols;
  out.height = bgrImage.rows;
  out.pixels.reserve(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height));
  for (int y = 0; y < bgrImage.rows; ++y) {
    const auto* row = bgrImage.ptr<cv::Vec3b>(y);
    for (int x = 0; x < bgrImage.cols; ++x)
      out.pixels.push_back(Rgb{row[x][2], row[x][1], row[x][0]});
  }
  return out;
}

void writeMapPng(const OccupancyMap& map, const std::string& path, const PngOptions& options) {
  const cv::Mat image = renderBgr(map, options);

  // Encoded in memory and written by the one atomic writer: cv::imwrite would pick the encoder from
  // the name's extension, says nothing about why it failed, and neither syncs nor renames.
  std::vector<uchar> png;
  bool encoded = false;
  std::string reason = "cv::imencode failed";
  try {
    encoded = cv::imencode(".png", image, png);
  } catch (const cv::Exception& e) {
    reason = e.what();
  }
  if (!encoded) throw FileWriteError(path, reason, "PNG");
  try {
    writeFileAtomically(path,
                        std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
  } catch (const FileWriteError& e) {
    throw FileWriteError(e.path(), e.reason(), "PNG");
  }
}

void writeRosMap(const OccupancyMap& map, const std::string& basename) {
  constexpr const char* what = "ROS map";
  const GridSpec& spec = map.spec;
  requireNonEmptyGrid(spec, what);
  requireLayerSize(spec, map.probability, "probability", what);
  requireLayerSize(spec, map.observed, "observed", what);
  if (!(std::isfinite(spec.cellSize) && spec.cellSize > 0.0))
    throw std::invalid_argument(std::string(what) + ": cell size must be positive and finite");
  if (!std::isfinite(spec.origin.x()) || !std::isfinite(spec.origin.y()))
    throw std::invalid_argument(std::string(what) + ": the grid origin is not finite");

  const std::string pgmPath = basename + ".pgm";
  const std::string yamlPath = basename + ".yaml";
  // map_server resolves `image` relative to the YAML file, which sits in the same directory.
  const std::string imageName = fs::path(pgmPath).filename().string();

  const std::string pgm = pgmBytes(map);
  const std::string yaml = yamlText(map, imageName);
  // The image first: the YAML is what users open, so it never points at a missing image.
  writeFileAtomically(pgmPath, pgm);
  writeFileAtomically(yamlPath, yaml);
}

}  // namespace sg
