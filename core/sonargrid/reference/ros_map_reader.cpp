// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/reference/ros_map_reader.h"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>

#include "sonargrid/base/file_text.h"
#include "sonargrid/reference/grey_image.h"

namespace sg {
namespace {

using file_text::shown;

// map_saver's value for a cell nobody observed (and what writeRosMap writes).
constexpr int kUnknownPixel = 205;

bool isBlank(char c) {
  return c == ' ' || c == '\t' || c == '\r';
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && isBlank(s.front())) s.remove_prefix(1);
  while (!s.empty() && isBlank(s.back())) s.remove_suffix(1);
  return s;
}

// ---------------------------------------------------------------------------------------------
// The YAML subset of map_server files.

struct YamlValue {
  std::size_t line = 0;
  bool sequence = false;
  std::string scalar;              // plain or unquoted text
  std::vector<std::string> items;  // a flow sequence [a, b, c]
};

class YamlReader {
 public:
  YamlReader(std::string_view text, const std::string& file) : file_(file) { parse(text); }

  const YamlValue* find(const std::string& key) const {
    const auto it = values_.find(key);
    return it == values_.end() ? nullptr : &it->second;
  }
  const YamlValue& require(const std::string& key) const {
    const YamlValue* v = find(key);
    if (!v)
      throw LogError(file_, 0, key,
                     "missing; map_server needs image, resolution, origin, negate, "
                     "occupied_thresh, free_thresh");
    return *v;
  }
  [[noreturn]] void fail(const YamlValue& v, const std::string& key,
                         const std::string& message) const {
    throw LogError(file_, v.line, key, message);
  }

  double number(const std::string& key, const std::string& text, const YamlValue& where) const {
    std::string_view s = trim(text);
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    double v = 0.0;
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (s.empty() || ec != std::errc() || ptr != s.data() + s.size() || !std::isfinite(v)) {
      fail(where, key, "expected a number, got \"" + shown(text) + "\"");
    }
    return v;
  }
  double number(const std::string& key) const {
    const YamlValue& v = require(key);
    if (v.sequence) fail(v, key, "expected a number, got a sequence");
    return number(key, v.scalar, v);
  }

 private:
  void parse(std::string_view text) {
    if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
    const std::vector<std::string_view> lines = file_text::splitLines(text);
    bool skippingBlock = false;  // indented lines under a key we do not read
    for (std::size_t n = 0; n < lines.size(); ++n) {
      const std::size_t lineNo = n + 1;
      const std::string_view raw = lines[n];
      if (raw.size() > 64 * 1024) throw LogError(file_, lineNo, "", "line longer than 65536 bytes");
      const std::string_view line = trim(raw);
      if (line.empty() || line.front() == '#' || line == "---" || line == "...") continue;
      if (isBlank(raw.front())) {
        if (skippingBlock) continue;
        throw LogError(file_, lineNo, "",
                       "expected \"key: value\" at the start of the line (nested YAML is not part "
                       "of a map_server file)");
      }
      const std::size_t colon = line.find(':');
      if (colon == std::string_view::npos || colon == 0) {
        throw LogError(file_, lineNo, "", "expected \"key: value\", got \"" + shown(line) + "\"");
      }
      const std::string key(trim(line.substr(0, colon)));
      std::string_view rest = line.substr(colon + 1);
      if (!rest.empty() && !isBlank(rest.front())) {
        throw LogError(file_, lineNo, key, "expected a space after \"" + shown(key) + ":\"");
      }
      rest = trim(rest);
      YamlValue value;
      value.line = lineNo;
      parseValue(rest, key, value);
      skippingBlock = !known(key);
      if (!known(key)) continue;  // map_server ignores keys it does not know; so do we
      if (values_.count(key) != 0) {
        throw LogError(file_, lineNo, key,
                       "given twice (first on line " + std::to_string(values_[key].line) + ")");
      }
      values_[key] = std::move(value);
    }
  }

  static bool known(const std::string& key) {
    return key == "image" || key == "resolution" || key == "origin" || key == "negate" ||
           key == "occupied_thresh" || key == "free_thresh" || key == "mode";
  }

  // What may follow a value: nothing, or a comment.
  void expectEnd(std::string_view after, const std::string& key, std::size_t line) const {
    after = trim(after);
    if (!after.empty() && after.front() != '#') {
      throw LogError(file_, line, key, "unexpected \"" + shown(after) + "\" after the value");
    }
  }

  void parseValue(std::string_view s, const std::string& key, YamlValue& out) const {
    if (s.empty() || s.front() == '#') return;  // empty value (a block may follow)
    if (s.front() == '"' || s.front() == '\'') {
      const char q = s.front();
      std::string text;
      std::size_t i = 1;
      bool closed = false;
      while (i < s.size()) {
        const char c = s[i];
        if (q == '\'' && c == '\'') {
          if (i + 1 < s.size() && s[i + 1] == '\'') {
            text += '\'';
            i += 2;
            continue;
          }
          closed = true;
          ++i;
          break;
        }
        if (q == '"' && c == '\\' && i + 1 < s.size()) {
          const char e = s[i + 1];
          text += e == 'n' ? '\n' : e == 't' ? '\t' : e;
          i += 2;
          continue;
        }
        if (q == '"' && c == '"') {
          closed = true;
          ++i;
          break;
        }
        text += c;
        ++i;
      }
      if (!closed) throw LogError(file_, out.line, key, "unterminated quoted string");
      expectEnd(s.substr(i), key, out.line);
      out.scalar = text;
      return;
    }
    if (s.front() == '[') {
      const std::size_t close = s.find(']');
      if (close == std::string_view::npos)
        throw LogError(file_, out.line, key, "unterminated sequence: expected ']'");
      expectEnd(s.substr(close + 1), key, out.line);
      out.sequence = true;
      const std::string_view inner = trim(s.substr(1, close - 1));
      if (inner.empty()) return;
      std::size_t start = 0;
      while (true) {
        const std::size_t comma = inner.find(',', start);
        const std::string_view item = trim(inner.substr(
            start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
        out.items.emplace_back(item);
        if (comma == std::string_view::npos) break;
        start = comma + 1;
      }
      return;
    }
    // A plain scalar ends at a comment ("value # note").
    std::size_t end = s.size();
    for (std::size_t i = 1; i < s.size(); ++i) {
      if (s[i] == '#' && isBlank(s[i - 1])) {
        end = i;
        break;
      }
    }
    out.scalar = std::string(trim(s.substr(0, end)));
  }

  const std::string& file_;
  std::map<std::string, YamlValue> values_;
};

}  // namespace

double RosMap::occupancy(std::size_t cell) const {
  const int v = negate ? 255 - pixels[cell] : pixels[cell];
  return (255.0 - v) / 255.0;
}

bool RosMap::unknownPixel(std::size_t cell) const {
  const int v = negate ? 255 - pixels[cell] : pixels[cell];
  return v == kUnknownPixel;
}

RosMap readRosMap(const std::string& yamlPath) {
  namespace fs = std::filesystem;
  const std::string text = file_text::readFileBytes(yamlPath, 1024 * 1024);
  const YamlReader yaml(text, yamlPath);

  RosMap map;
  map.yamlPath = yamlPath;
  const YamlValue& image = yaml.require("image");
  if (image.sequence || image.scalar.empty())
    yaml.fail(image, "image", "expected the image file name");

  const YamlValue& resolutionValue = yaml.require("resolution");
  const double resolution = yaml.number("resolution");
  if (!(resolution > 0.0) || resolution > 1000.0) {
    yaml.fail(resolutionValue, "resolution",
              "expected metres per pixel in (0, 1000], got " + resolutionValue.scalar);
  }
  const YamlValue& origin = yaml.require("origin");
  if (!origin.sequence || origin.items.size() != 3) {
    yaml.fail(origin, "origin", "expected [x, y, yaw]");
  }
  const double ox = yaml.number("origin", origin.items[0], origin);
  const double oy = yaml.number("origin", origin.items[1], origin);
  const double yaw = yaml.number("origin", origin.items[2], origin);
  if (std::abs(ox) > 1e7 || std::abs(oy) > 1e7)
    yaml.fail(origin, "origin", "x and y must be within 10000 km");
  if (std::abs(yaw) > 1e-9) {
    yaml.fail(
        origin, "origin",
        "a rotated map (yaw " + origin.items[2] + ") is not supported; grids are axis-aligned");
  }
  const YamlValue& negate = yaml.require("negate");
  if (negate.sequence) yaml.fail(negate, "negate", "expected 0 or 1");
  if (negate.scalar == "0" || negate.scalar == "false") {
    map.negate = false;
  } else if (negate.scalar == "1" || negate.scalar == "true") {
    map.negate = true;
  } else {
    yaml.fail(negate, "negate", "expected 0 or 1, got \"" + shown(negate.scalar) + "\"");
  }
  map.occupiedThresh = yaml.number("occupied_thresh");
  map.freeThresh = yaml.number("free_thresh");
  if (map.occupiedThresh < 0.0 || map.occupiedThresh > 1.0) {
    yaml.fail(yaml.require("occupied_thresh"), "occupied_thresh",
              "expected a probability in [0, 1]");
  }
  if (map.freeThresh < 0.0 || map.freeThresh > map.occupiedThresh) {
    yaml.fail(yaml.require("free_thresh"), "free_thresh",
              "expected a probability in [0, occupied_thresh]");
  }
  if (const YamlValue* mode = yaml.find("mode")) {
    if (mode->scalar == "raw")
      yaml.fail(*mode, "mode", "raw mode is not supported (use trinary or scale)");
    if (mode->scalar != "trinary" && mode->scalar != "scale") {
      yaml.fail(*mode, "mode", "expected trinary or scale, got \"" + shown(mode->scalar) + "\"");
    }
    map.mode = mode->scalar;
  }

  fs::path imagePath(image.scalar);
  if (imagePath.is_relative()) imagePath = fs::path(yamlPath).parent_path() / imagePath;
  map.imagePath = imagePath.string();
  const GreyImage grey = readGreyImage(map.imagePath);

  map.spec.origin = Position(ox, oy);
  map.spec.cellSize = resolution;
  map.spec.width = grey.width;
  map.spec.height = grey.height;
  map.pixels.resize(map.spec.cellCount());
  const auto w = static_cast<std::size_t>(grey.width);
  for (int r = 0; r < grey.height; ++r) {
    const auto iy = static_cast<std::size_t>(grey.height - 1 - r);
    std::copy_n(grey.pixels.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(r) * w),
                w, map.pixels.begin() + static_cast<std::ptrdiff_t>(iy * w));
  }
  return map;
}

ReferenceMap rosMapAsReference(const RosMap& map) {
  ReferenceMap ref;
  ref.unit = LengthUnit::Metre;
  ObstacleRaster raster;
  raster.spec = map.spec;
  raster.cells.resize(map.pixels.size());
  for (std::size_t i = 0; i < map.pixels.size(); ++i) {
    const double p = map.occupancy(i);
    raster.cells[i] = p > map.occupiedThresh ? RasterCell::Obstacle
                      : p < map.freeThresh   ? RasterCell::Free
                                             : RasterCell::Unknown;
  }
  ref.raster = std::move(raster);
  return ref;
}

OccupancyMap rosMapAsBuiltMap(const RosMap& map) {
  OccupancyMap m;
  m.spec = map.spec;
  m.model = "ros-map";
  m.rule = "map_server";
  const std::size_t n = map.pixels.size();
  m.probability.resize(n);
  m.native.resize(n);
  m.level.resize(n);
  m.filled.resize(n);
  m.observed.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (map.unknownPixel(i)) {
      m.probability[i] = 0.5;
      m.native[i] = 0.5;
      m.level[i] = levelOfProbability(0.5);
      m.filled[i] = 0;
      m.observed[i] = 0;
      continue;
    }
    const double p = map.occupancy(i);
    m.probability[i] = p;
    m.native[i] = p;
    m.level[i] = levelOfProbability(p);  // CV = round(15 p)
    m.filled[i] = m.level[i] > 0 ? 1 : 0;
    m.observed[i] = 1;
  }
  return m;
}

}  // namespace sg
