// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/reference/reference_json.h"

#include <charconv>
#include <cmath>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <stdexcept>
#include <vector>

#include "sonargrid/base/atomic_file.h"
#include "sonargrid/base/file_text.h"

namespace sg {
namespace {

using nlohmann::json;

// ---------------------------------------------------------------------------------------------
// Where each value sits in the file. nlohmann's DOM keeps no positions, so a first, SAX pass feeds
// the parser through an iterator that counts newlines and records, for every value, the line of
// the last non-blank byte read when the parser reports it: the value's own last byte (a number's
// one byte of look-ahead is a delimiter on the same line or blank, so it never moves the line).

struct LineCounter {
  std::size_t line = 1;       // line of the next byte to be read
  std::size_t tokenLine = 1;  // line of the last non-blank byte read
};

class CountingIterator {
 public:
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  CountingIterator() = default;
  CountingIterator(const char* p, LineCounter* counter) : p_(p), counter_(counter) {}
  reference operator*() const { return *p_; }
  CountingIterator& operator++() {
    const char c = *p_;
    if (c == '\n') {
      ++counter_->line;
    } else if (c != ' ' && c != '\t' && c != '\r') {
      counter_->tokenLine = counter_->line;
    }
    ++p_;
    return *this;
  }
  CountingIterator operator++(int) {
    CountingIterator old = *this;
    ++*this;
    return old;
  }
  bool operator==(const CountingIterator& o) const { return p_ == o.p_; }
  bool operator!=(const CountingIterator& o) const { return p_ != o.p_; }

 private:
  const char* p_ = nullptr;
  LineCounter* counter_ = nullptr;
};

// Rejects repeated keys (nlohmann would silently keep the last one) and keeps the first syntax
// error. Given a target JSON pointer ("/objects/1/corners"), it stops at that value and says on
// which line it is: validation errors are rare, so their lines are found by a second pass rather
// than by recording the line of every value of a large file.
class LineRecorder {
 public:
  LineRecorder(const LineCounter& counter, std::optional<std::string> target = std::nullopt)
      : counter_(counter), target_(std::move(target)) {}

  std::size_t targetLine = 0;
  std::string error;
  std::size_t errorLine = 0;
  std::size_t errorByte = 0;
  bool syntaxError = false;

  bool null() { return value(); }
  bool boolean(bool) { return value(); }
  bool number_integer(json::number_integer_t) { return value(); }
  bool number_unsigned(json::number_unsigned_t) { return value(); }
  bool number_float(json::number_float_t, const json::string_t&) { return value(); }
  bool string(json::string_t&) { return value(); }
  bool binary(json::binary_t&) { return value(); }
  bool start_object(std::size_t) {
    if (reached()) return false;
    frames_.push_back(Frame{false, 0, {}, {}});
    return true;
  }
  bool key(json::string_t& k) {
    Frame& f = frames_.back();
    if (!f.keys.insert(k).second) {
      error = "the key \"" + file_text::shown(k) + "\" appears twice in one object";
      errorLine = counter_.tokenLine;
      return false;
    }
    f.key = k;
    return true;
  }
  bool end_object() { return end(); }
  bool start_array(std::size_t) {
    if (reached()) return false;
    frames_.push_back(Frame{true, 0, {}, {}});
    return true;
  }
  bool end_array() { return end(); }
  bool parse_error(std::size_t position, const std::string&,
                   const nlohmann::detail::exception& ex) {
    syntaxError = true;
    errorByte = position;
    error = ex.what();
    return false;
  }

  static std::string pointerOf(const std::vector<std::string>& parts) {
    std::string out;
    for (const std::string& p : parts) out += "/" + p;
    return out;
  }

 private:
  struct Frame {
    bool array;
    std::size_t index;
    std::string key;
    std::set<std::string> keys;
  };

  std::string pointer() const {
    std::string out;
    for (const Frame& f : frames_) out += "/" + (f.array ? std::to_string(f.index) : f.key);
    return out;
  }
  // Whether the value being reported is the target (then its line is kept and the pass stops).
  bool reached() {
    if (!target_ || pointer() != *target_) return false;
    targetLine = counter_.tokenLine;
    return true;
  }
  bool value() {
    if (reached()) return false;
    advance();
    return true;
  }
  bool end() {
    frames_.pop_back();
    advance();
    return true;
  }
  void advance() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
  }

  const LineCounter& counter_;
  std::optional<std::string> target_;
  std::vector<Frame> frames_;
};

// nlohmann's message without its "[json.exception...] parse error at line L, column C: " prefix:
// our LogError prefix already names the file and line.
std::string bareMessage(std::string what) {
  if (!what.empty() && what.front() == '[') {
    const auto close = what.find("] ");
    if (close != std::string::npos) what.erase(0, close + 2);
  }
  if (what.rfind("parse error", 0) == 0) {
    const auto colon = what.find(": ");
    if (colon != std::string::npos) what.erase(0, colon + 2);
  }
  return what;
}

std::size_t lineOfByte(std::string_view text, std::size_t byte) {
  const std::size_t end = byte == 0 ? 0 : std::min(byte - 1, text.size());
  std::size_t line = 1;
  for (std::size_t i = 0; i < end; ++i) line += text[i] == '\n' ? 1 : 0;
  return line;
}

// ---------------------------------------------------------------------------------------------
// Validation of the parsed document, each error at the line of the offending value.

class Validator {
 public:
  Validator(const std::string& file, std::string_view text) : file_(file), text_(text) {}

  [[noreturn]] void fail(const std::vector<std::string>& where, const std::string& field,
                         const std::string& message) const {
    LineCounter counter;
    LineRecorder finder(counter, LineRecorder::pointerOf(where));
    json::sax_parse(CountingIterator(text_.data(), &counter),
                    CountingIterator(text_.data() + text_.size(), &counter), &finder);
    throw LogError(file_, finder.targetLine, field, message);
  }

  ReferenceMap build(const json& doc) const {
    if (!doc.is_object())
      fail({}, "",
           "expected a JSON object {\"format\": \"" + std::string(kReferenceFormat) + "\", ...}");
    for (const auto& [k, v] : doc.items()) {
      if (k != "format" && k != "version" && k != "units" && k != "objects" && k != "start") {
        fail({k}, k, "unknown key (expected format, version, units, objects, start)");
      }
    }
    const auto format = doc.find("format");
    if (format == doc.end())
      fail({}, "format", "missing; expected \"" + std::string(kReferenceFormat) + "\"");
    if (!format->is_string() || format->get<std::string>() != kReferenceFormat) {
      fail({"format"}, "format",
           "expected \"" + std::string(kReferenceFormat) + "\", got " + shownJson(*format));
    }
    const auto version = doc.find("version");
    if (version == doc.end()) fail({}, "version", "missing; expected 1");
    if (!version->is_number() || version->get<double>() != kReferenceVersion) {
      fail({"version"}, "version",
           "this program reads version " + std::to_string(kReferenceVersion) + ", got " +
               shownJson(*version));
    }
    ReferenceMap map;
    const auto units = doc.find("units");
    if (units == doc.end()) fail({}, "units", "missing; expected \"m\", \"cm\" or \"mm\"");
    const auto unit =
        units->is_string() ? lengthUnitFromName(units->get<std::string>()) : std::nullopt;
    if (!unit)
      fail({"units"}, "units", "expected \"m\", \"cm\" or \"mm\", got " + shownJson(*units));
    map.unit = *unit;
    if (const auto start = doc.find("start"); start != doc.end()) map.start = startPose(*start);

    const auto objects = doc.find("objects");
    if (objects == doc.end()) fail({}, "objects", "missing; expected an array of objects");
    if (!objects->is_array())
      fail({"objects"}, "objects", "expected an array, got " + shownJson(*objects));
    std::map<std::string, std::size_t> seen;
    for (std::size_t i = 0; i < objects->size(); ++i) {
      ReferenceObject o = object((*objects)[i], i);
      const auto [it, inserted] = seen.emplace(o.name, i);
      if (!inserted) {
        fail({"objects", std::to_string(i), "name"}, "objects[" + std::to_string(i) + "].name",
             "the name \"" + file_text::shown(o.name) + "\" is already used by objects[" +
                 std::to_string(it->second) + "]; names must be unique");
      }
      map.objects.push_back(std::move(o));
    }
    return map;
  }

 private:
  static std::string shownJson(const json& v) {
    return file_text::shown(v.dump(-1, ' ', false, json::error_handler_t::replace), 40);
  }

  StartPose startPose(const json& v) const {
    const char* expected = "expected {\"x\": X, \"y\": Y, \"heading_deg\": DEGREES}";
    if (!v.is_object()) fail({"start"}, "start", std::string(expected) + ", got " + shownJson(v));
    for (const auto& [k, value] : v.items()) {
      if (k != "x" && k != "y" && k != "heading_deg")
        fail({"start", k}, "start." + k, "unknown key (expected x, y, heading_deg)");
    }
    StartPose out;
    double* fields[] = {&out.position.x(), &out.position.y(), &out.headingDeg};
    const char* names[] = {"x", "y", "heading_deg"};
    for (int f = 0; f < 3; ++f) {
      const auto it = v.find(names[f]);
      if (it == v.end()) fail({"start"}, std::string("start.") + names[f], "missing");
      *fields[f] = finiteNumber(*it, {"start", names[f]}, std::string("start.") + names[f]);
    }
    return out;
  }

  double finiteNumber(const json& v, const std::vector<std::string>& where,
                      const std::string& field) const {
    if (!v.is_number()) fail(where, field, "expected a number, got " + shownJson(v));
    const double d = v.get<double>();
    if (!std::isfinite(d)) fail(where, field, "expected a finite number");
    return d;
  }

  ReferenceObject object(const json& o, std::size_t i) const {
    const std::string index = std::to_string(i);
    const std::string field = "objects[" + index + "]";
    if (!o.is_object())
      fail({"objects", index}, field, "expected an object {\"name\", \"closed\", \"corners\"}");
    const bool isCircle = o.contains("radius") || o.contains("centre");
    for (const auto& [k, v] : o.items()) {
      const bool common = k == "name" || k == "surface" || k == "specular_limit_deg";
      const bool shape =
          isCircle ? (k == "centre" || k == "radius") : (k == "closed" || k == "corners");
      if (!common && !shape) {
        fail({"objects", index, k}, field + "." + k,
             isCircle ? "unknown key for a circle (expected name, centre, radius, surface, "
                        "specular_limit_deg)"
                      : "unknown key (expected name, closed, corners, surface, "
                        "specular_limit_deg; or centre and radius for a circle)");
      }
    }
    ReferenceObject out;
    const auto name = o.find("name");
    if (name == o.end()) fail({"objects", index}, field + ".name", "missing");
    if (!name->is_string() || name->get<std::string>().empty()) {
      fail({"objects", index, "name"}, field + ".name",
           "expected a non-empty string, got " + shownJson(*name));
    }
    if (isCircle) {
      out = circle(o, index, field, name->get<std::string>());
    } else {
      out.name = name->get<std::string>();
      polygon(o, index, field, out);
    }
    if (const auto surface = o.find("surface"); surface != o.end()) {
      const auto kind =
          surface->is_string() ? surfaceFromName(surface->get<std::string>()) : std::nullopt;
      if (!kind) {
        fail({"objects", index, "surface"}, field + ".surface",
             "expected \"specular\" or \"diffuse\", got " + shownJson(*surface));
      }
      out.surface = *kind;
    }
    if (const auto limit = o.find("specular_limit_deg"); limit != o.end()) {
      out.specularLimitDeg = finiteNumber(*limit, {"objects", index, "specular_limit_deg"},
                                          field + ".specular_limit_deg");
    }
    const std::string problem = objectProblem(out);
    if (!problem.empty()) {
      const char* key = out.specularLimitDeg && problem.find("specular") != std::string::npos
                            ? "specular_limit_deg"
                        : out.circle ? "radius"
                                     : "corners";
      fail({"objects", index, key}, field + "." + key,
           "object \"" + file_text::shown(out.name) + "\": " + problem +
               (out.circle || std::string(key) == "specular_limit_deg"
                    ? std::string()
                    : " (it has " + std::to_string(out.corners.size()) + ")"));
    }
    return out;
  }

  ReferenceObject circle(const json& o, const std::string& index, const std::string& field,
                         const std::string& name) const {
    ReferenceCircle c;
    const auto centre = o.find("centre");
    if (centre == o.end()) fail({"objects", index}, field + ".centre", "missing; expected [x, y]");
    if (!centre->is_array() || centre->size() != 2 || !(*centre)[0].is_number() ||
        !(*centre)[1].is_number()) {
      fail({"objects", index, "centre"}, field + ".centre",
           "expected [x, y] of two numbers, got " + shownJson(*centre));
    }
    c.centre = Eigen::Vector2d((*centre)[0].get<double>(), (*centre)[1].get<double>());
    if (!std::isfinite(c.centre.x()) || !std::isfinite(c.centre.y()))
      fail({"objects", index, "centre"}, field + ".centre", "the centre must be finite numbers");
    const auto radius = o.find("radius");
    if (radius == o.end()) fail({"objects", index}, field + ".radius", "missing");
    c.radius = finiteNumber(*radius, {"objects", index, "radius"}, field + ".radius");
    if (c.radius <= 0.0)
      fail({"objects", index, "radius"}, field + ".radius", "a circle's radius must be above 0");
    return circleObject(name, c);
  }

  void polygon(const json& o, const std::string& index, const std::string& field,
               ReferenceObject& out) const {
    const auto closed = o.find("closed");
    if (closed == o.end())
      fail({"objects", index}, field + ".closed", "missing; expected true or false");
    if (!closed->is_boolean()) {
      fail({"objects", index, "closed"}, field + ".closed",
           "expected true or false, got " + shownJson(*closed));
    }
    out.closed = closed->get<bool>();
    const auto corners = o.find("corners");
    if (corners == o.end())
      fail({"objects", index}, field + ".corners", "missing; expected [[x, y], ...]");
    if (!corners->is_array()) {
      fail({"objects", index, "corners"}, field + ".corners",
           "expected [[x, y], ...], got " + shownJson(*corners));
    }
    for (std::size_t k = 0; k < corners->size(); ++k) {
      const json& c = (*corners)[k];
      const std::string ck = std::to_string(k);
      if (!c.is_array() || c.size() != 2 || !c[0].is_number() || !c[1].is_number()) {
        fail({"objects", index, "corners", ck}, field + ".corners[" + ck + "]",
             "expected a corner [x, y] of two numbers, got " + shownJson(c));
      }
      const Eigen::Vector2d p(c[0].get<double>(), c[1].get<double>());
      if (!std::isfinite(p.x()) || !std::isfinite(p.y())) {
        fail({"objects", index, "corners", ck}, field + ".corners[" + ck + "]",
             "corners must be finite numbers");
      }
      out.corners.push_back(p);
    }
  }

  const std::string& file_;
  std::string_view text_;
};

// Shortest text that reads back as the same double; integers without a fraction, as users type
// corners measured in whole millimetres or centimetres.
std::string numberText(double v) {
  if (v == std::floor(v) && std::abs(v) < 1e15) {
    return std::to_string(static_cast<long long>(v));
  }
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, result.ptr);
}

}  // namespace

ReferenceMap parseReferenceJson(std::string_view text, const std::string& displayName) {
  if (text.find_first_not_of(" \t\r\n") == std::string_view::npos) {
    throw LogError(displayName, 0, "",
                   "the file is empty; expected a sonargrid-reference JSON object");
  }
  LineCounter counter;
  LineRecorder recorder(counter);
  const char* begin = text.data();
  const char* end = text.data() + text.size();
  const bool ok = json::sax_parse(CountingIterator(begin, &counter),
                                  CountingIterator(end, &counter), &recorder);
  if (!ok) {
    if (recorder.syntaxError) {
      throw LogError(displayName, lineOfByte(text, recorder.errorByte), "",
                     "not valid JSON: " + bareMessage(recorder.error));
    }
    throw LogError(displayName, recorder.errorLine, "", recorder.error);
  }
  const json doc = json::parse(text.begin(), text.end(), nullptr, false);
  if (doc.is_discarded()) throw LogError(displayName, 0, "", "not valid JSON");
  return Validator(displayName, text).build(doc);
}

ReferenceMap readReferenceJson(const std::string& path) {
  const std::string bytes = file_text::readFileBytes(path);
  return parseReferenceJson(bytes, path);
}

std::string referenceJsonText(const ReferenceMap& map) {
  if (map.raster) {
    throw std::invalid_argument(
        "a reference with an obstacle raster (imported from an image) cannot be saved as "
        "sonargrid-reference JSON, which holds corner objects only");
  }
  std::set<std::string> names;
  std::string out;
  out += "{\n  \"format\": \"";
  out += kReferenceFormat;
  out += "\",\n  \"version\": " + std::to_string(kReferenceVersion) + ",\n  \"units\": \"";
  out += lengthUnitName(map.unit);
  out += "\",\n";
  if (map.start) {
    out += "  \"start\": {\"x\": " + numberText(map.start->position.x()) +
           ", \"y\": " + numberText(map.start->position.y()) +
           ", \"heading_deg\": " + numberText(map.start->headingDeg) + "},\n";
  }
  out += "  \"objects\": [";
  for (std::size_t i = 0; i < map.objects.size(); ++i) {
    const ReferenceObject& o = map.objects[i];
    const std::string problem = objectProblem(o);
    if (!problem.empty()) {
      throw std::invalid_argument("reference object " + std::to_string(i) + " (\"" + o.name +
                                  "\"): " + problem);
    }
    if (!names.insert(o.name).second) {
      throw std::invalid_argument("reference object name \"" + o.name +
                                  "\" is used twice; names must be unique");
    }
    std::string name;
    try {
      name = json(o.name).dump(-1, ' ', false, json::error_handler_t::strict);
    } catch (const json::exception&) {
      throw std::invalid_argument("reference object " + std::to_string(i) +
                                  ": the name is not valid UTF-8");
    }
    out += i == 0 ? "\n" : ",\n";
    out += "    {\"name\": " + name;
    if (o.circle) {
      out += ", \"centre\": [" + numberText(o.circle->centre.x()) + ", " +
             numberText(o.circle->centre.y()) + "], \"radius\": " + numberText(o.circle->radius);
    } else {
      out += ", \"closed\": " + std::string(o.closed ? "true" : "false") + ", \"corners\": [";
      for (std::size_t k = 0; k < o.corners.size(); ++k) {
        if (k != 0) out += ", ";
        out += "[" + numberText(o.corners[k].x()) + ", " + numberText(o.corners[k].y()) + "]";
      }
      out += "]";
    }
    if (o.surface != Surface::Unspecified)
      out += ", \"surface\": \"" + std::string(surfaceName(o.surface)) + "\"";
    if (o.specularLimitDeg) out += ", \"specular_limit_deg\": " + numberText(*o.specularLimitDeg);
    out += "}";
  }
  out += map.objects.empty() ? "]\n}\n" : "\n  ]\n}\n";
  return out;
}

void writeReferenceJson(const ReferenceMap& map, const std::string& path) {
  writeFileAtomically(path, referenceJsonText(map));
}

}  // namespace sg
