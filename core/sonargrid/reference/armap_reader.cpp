// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/reference/armap_reader.h"

#include <array>
#include <charconv>
#include <cstdint>

#include "sonargrid/base/file_text.h"

namespace sg {
namespace {

// Far beyond any building (1000 km) yet small enough that a corner in metres stays exact.
constexpr std::int64_t kMaxCoordinateMm = 1'000'000'000;
// A line longer than this is not a map line; saying so beats splitting a binary file into tokens.
constexpr std::size_t kMaxLineBytes = 64 * 1024;

enum class Section { Header, Lines, Data, Other };

bool isBlank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && isBlank(s.front())) s.remove_prefix(1);
  while (!s.empty() && isBlank(s.back())) s.remove_suffix(1);
  return s;
}

// Splits on blanks; at most `max` + 1 tokens are kept, so that "too many fields" can be told.
std::vector<std::string_view> tokens(std::string_view s, std::size_t max) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < s.size() && out.size() <= max) {
    while (i < s.size() && isBlank(s[i])) ++i;
    if (i >= s.size()) break;
    const std::size_t start = i;
    while (i < s.size() && !isBlank(s[i])) ++i;
    out.push_back(s.substr(start, i - start));
  }
  return out;
}

// Section keywords stand alone on their line. ARIA's later formats add more sections (e.g.
// "LINES" and "DATA" per sensor in 2D-Map-Ex2); all but these two are skipped.
Section sectionOf(std::string_view line) {
  if (line == "LINES") return Section::Lines;
  if (line == "DATA") return Section::Data;
  return Section::Other;
}

bool looksLikeKeyword(std::string_view line) {
  if (line.empty()) return false;
  for (char c : line) {
    if (!((c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_')) return false;
  }
  return line.front() >= 'A' && line.front() <= 'Z';
}

}  // namespace

ReferenceMap parseArMap(std::string_view text, const std::string& displayName) {
  using file_text::shown;
  // A UTF-8 byte-order mark is not part of the magic word.
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  const std::vector<std::string_view> lines = file_text::splitLines(text);
  if (lines.empty())
    throw LogError(displayName, 0, "", "the file is empty; expected an ArMap (first line 2D-Map)");
  const std::string_view magic = trim(lines.front());
  if (magic.substr(0, 6) != "2D-Map") {
    throw LogError(displayName, 1, "magic",
                   "expected an ArMap first line \"2D-Map\", got \"" + shown(magic) + "\"");
  }

  ReferenceMap map;
  map.unit = LengthUnit::Millimetre;
  Section section = Section::Header;
  bool sawLines = false;
  static const std::array<const char*, 4> kFields{"x1", "y1", "x2", "y2"};
  for (std::size_t n = 1; n < lines.size(); ++n) {
    const std::size_t lineNo = n + 1;
    if (lines[n].size() > kMaxLineBytes) {
      throw LogError(displayName, lineNo, "",
                     "line longer than " + std::to_string(kMaxLineBytes) + " bytes");
    }
    const std::string_view line = trim(lines[n]);
    if (line.empty()) continue;
    // Header lines are "Key: values"; a bare upper-case word starts a section.
    if (looksLikeKeyword(line)) {
      section = sectionOf(line);
      sawLines = sawLines || section == Section::Lines;
      continue;
    }
    if (section != Section::Lines) continue;  // header, DATA points, other sections

    const std::vector<std::string_view> t = tokens(line, 4);
    if (t.size() != 4) {
      throw LogError(displayName, lineNo, t.size() < 4 ? kFields[t.size()] : "LINES",
                     t.size() < 4 ? "missing; a LINES entry is x1 y1 x2 y2 in integer millimetres"
                                  : "too many fields; a LINES entry is x1 y1 x2 y2");
    }
    std::array<std::int64_t, 4> v{};
    for (std::size_t k = 0; k < 4; ++k) {
      const char* first = t[k].data();
      const char* last = first + t[k].size();
      const auto [ptr, ec] = std::from_chars(first, last, v[k]);
      if (ec != std::errc() || ptr != last) {
        throw LogError(displayName, lineNo, kFields[k],
                       "expected an integer (millimetres), got \"" + shown(t[k]) + "\"");
      }
      if (v[k] > kMaxCoordinateMm || v[k] < -kMaxCoordinateMm) {
        throw LogError(displayName, lineNo, kFields[k],
                       "coordinate " + std::string(t[k]) + " mm is beyond +-" +
                           std::to_string(kMaxCoordinateMm) + " mm");
      }
    }
    ReferenceObject o;
    o.name = "line " + std::to_string(map.objects.size() + 1);
    o.closed = false;
    o.corners = {Eigen::Vector2d(static_cast<double>(v[0]), static_cast<double>(v[1])),
                 Eigen::Vector2d(static_cast<double>(v[2]), static_cast<double>(v[3]))};
    map.objects.push_back(std::move(o));
  }
  if (!sawLines) {
    throw LogError(displayName, 0, "LINES",
                   "the map has no LINES section; only its wall segments can serve as a reference "
                   "(DATA points are "
                   "laser returns, not measured geometry)");
  }
  if (map.objects.empty())
    throw LogError(displayName, 0, "LINES", "the LINES section holds no segment");
  return map;
}

ReferenceMap readArMap(const std::string& path) {
  const std::string bytes = file_text::readFileBytes(path);
  return parseArMap(bytes, path);
}

}  // namespace sg
