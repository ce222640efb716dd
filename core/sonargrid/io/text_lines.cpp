// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/io/text_lines.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <istream>
#include <system_error>
#include <utility>

#include "sonargrid/io/log_options.h"

namespace sg::text {
namespace {

// Long enough to recognise a token in an error message, short enough to keep the message on a line.
constexpr std::size_t kMaxShownBytes = 40;

std::string osReason(int err) {
  return std::error_code(err, std::generic_category()).message();
}

bool isBlank(char c) {
  return c == ' ' || c == '\t';
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Sources

FileSource::FileSource(const std::string& path) : path_(path) {
  f_ = std::fopen(path.c_str(), "rb");
  if (f_ == nullptr) throw LogError(path, 0, "", "cannot open: " + osReason(errno));
  // A directory opens on Linux and fails on the first read with EISDIR; the size is only a hint
  // for progress, so a failed seek (a pipe) leaves it unknown.
  if (std::fseek(f_, 0, SEEK_END) == 0) {
    const long end = std::ftell(f_);
    if (end > 0) size_ = static_cast<std::uint64_t>(end);
  }
  std::clearerr(f_);
  if (std::fseek(f_, 0, SEEK_SET) != 0) size_ = 0;
}

FileSource::~FileSource() {
  if (f_ != nullptr) std::fclose(f_);
}

std::size_t FileSource::read(char* dst, std::size_t n) {
  const std::size_t got = std::fread(dst, 1, n, f_);
  if (got == 0 && std::ferror(f_)) throw LogError(path_, 0, "", "cannot read: " + osReason(errno));
  return got;
}

bool FileSource::rewind() {
  std::clearerr(f_);
  return std::fseek(f_, 0, SEEK_SET) == 0;
}

std::size_t StreamSource::read(char* dst, std::size_t n) {
  in_.read(dst, static_cast<std::streamsize>(n));
  const auto got = static_cast<std::size_t>(in_.gcount());
  if (in_.bad()) throw LogError(file_, 0, "", "cannot read: the input stream failed");
  return got;
}

std::size_t MemorySource::read(char* dst, std::size_t n) {
  const std::size_t got = std::min(n, bytes_.size() - pos_);
  if (got != 0) std::memcpy(dst, bytes_.data() + pos_, got);
  pos_ += got;
  return got;
}

// ---------------------------------------------------------------------------------------------
// Lines

LineReader::LineReader(ByteSource& src, const std::string& file, const LoadHooks* hooks)
    : src_(src), file_(file), hooks_(hooks) {
  // A small input known in advance gets a buffer its size (refill grows it should the input turn
  // out longer), which keeps parsing many short texts (tests, fuzzing) cheap.
  const std::uint64_t size = src.size();
  buf_.resize(size != 0 && size < kFullBytes ? static_cast<std::size_t>(size) + 1 : kFullBytes);
}

bool LineReader::next(std::string_view& line) {
  std::size_t scanFrom = begin_;
  for (;;) {
    char* base = buf_.data();
    const void* nl = std::memchr(base + scanFrom, '\n', end_ - scanFrom);
    if (nl != nullptr) {
      const auto pos = static_cast<std::size_t>(static_cast<const char*>(nl) - base);
      ++line_;
      if (pos - begin_ > kMaxLineBytes) throwTooLong();
      line = std::string_view(base + begin_, pos - begin_);
      begin_ = pos + 1;
      ended_ = true;
      break;
    }
    if (end_ - begin_ > kMaxLineBytes) {
      ++line_;
      throwTooLong();
    }
    if (eof_) {
      if (begin_ == end_) return false;
      ++line_;  // a last line without '\n'
      line = std::string_view(base + begin_, end_ - begin_);
      begin_ = end_;
      ended_ = false;
      break;
    }
    // Keep the partial line and refill behind it; at most kMaxLineBytes move, so this stays linear.
    if (begin_ > 0) {
      std::memmove(base, base + begin_, end_ - begin_);
      end_ -= begin_;
      begin_ = 0;
    }
    scanFrom = end_;
    refill();
  }
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return true;
}

void LineReader::refill() {
  if (end_ == buf_.size()) buf_.resize(kFullBytes);
  const std::size_t got = src_.read(buf_.data() + end_, buf_.size() - end_);
  if (got == 0) {
    eof_ = true;
  } else {
    end_ += got;
    bytesRead_ += got;
  }
  if (hooks_ == nullptr) return;
  if (hooks_->cancel != nullptr && hooks_->cancel->load(std::memory_order_relaxed)) {
    throw LoadCancelled(file_);
  }
  if (hooks_->progress) hooks_->progress(bytesRead_, std::max(src_.size(), bytesRead_));
}

void LineReader::throwTooLong() const {
  throw LogError(
      file_, line_, "",
      "expected a line of at most " + std::to_string(kMaxLineBytes) + " bytes, found a longer one");
}

// ---------------------------------------------------------------------------------------------
// Text checks

bool isControl(unsigned char c) {
  return (c < 0x20 && c != '\t') || c == 0x7F;
}

char hexDigit(unsigned v) {
  return "0123456789abcdef"[v & 0xF];
}

// RFC 3629: no overlongs, no surrogates, <= U+10FFFF.
std::size_t utf8Sequence(const unsigned char* p, std::size_t n) {
  const unsigned char c = p[0];
  std::size_t len = 0;
  unsigned char lo = 0x80;
  unsigned char hi = 0xBF;
  if (c >= 0xC2 && c <= 0xDF) {
    len = 2;
  } else if (c >= 0xE0 && c <= 0xEF) {
    len = 3;
    if (c == 0xE0) lo = 0xA0;
    if (c == 0xED) hi = 0x9F;
  } else if (c >= 0xF0 && c <= 0xF4) {
    len = 4;
    if (c == 0xF0) lo = 0x90;
    if (c == 0xF4) hi = 0x8F;
  } else {
    return 0;
  }
  if (n < len || p[1] < lo || p[1] > hi) return 0;
  for (std::size_t k = 2; k < len; ++k) {
    if (p[k] < 0x80 || p[k] > 0xBF) return 0;
  }
  return len;
}

std::size_t firstBadByte(std::string_view s) {
  const auto* p = reinterpret_cast<const unsigned char*>(s.data());
  const std::size_t n = s.size();
  std::size_t i = 0;
  while (i < n) {
    if (p[i] < 0x80) {
      if (isControl(p[i])) return i;
      ++i;
    } else {
      const std::size_t len = utf8Sequence(p + i, n - i);
      if (len == 0) return i;
      i += len;
    }
  }
  return std::string_view::npos;
}

void requireText(std::string_view line, const std::string& file, std::size_t lineNumber) {
  const std::size_t bad = firstBadByte(line);
  if (bad == std::string_view::npos) return;
  const auto byte = static_cast<unsigned char>(line[bad]);
  std::string hex = "0x";
  hex += hexDigit(byte >> 4U);
  hex += hexDigit(byte);
  throw LogError(
      file, lineNumber, "",
      "expected UTF-8 text, found byte " + hex + " at column " + std::to_string(bad + 1));
}

// ---------------------------------------------------------------------------------------------
// Fields and numbers

void splitFields(std::string_view line, std::vector<std::string_view>& out) {
  out.clear();
  const char* p = line.data();
  const char* end = p + line.size();
  for (;;) {
    while (p != end && isBlank(*p)) ++p;
    if (p == end || *p == '#') return;
    const char* start = p;
    while (p != end && !isBlank(*p)) ++p;
    out.emplace_back(start, static_cast<std::size_t>(p - start));
  }
}

void splitDelimited(std::string_view line, char delimiter, std::vector<std::string_view>& out) {
  out.clear();
  std::size_t first = 0;
  while (first < line.size() && isBlank(line[first])) ++first;
  if (first == line.size() || line[first] == '#') return;
  std::size_t start = 0;
  for (;;) {
    const std::size_t stop = line.find(delimiter, start);
    std::string_view field =
        line.substr(start, stop == std::string_view::npos ? std::string_view::npos : stop - start);
    while (!field.empty() && isBlank(field.front())) field.remove_prefix(1);
    while (!field.empty() && isBlank(field.back())) field.remove_suffix(1);
    out.push_back(field);
    if (stop == std::string_view::npos) return;
    start = stop + 1;
  }
}

NumberText parseNumber(std::string_view t, double& v) {
  // from_chars reads everything printf writes for %f, %e and %g (leading zeros, exponents, inf and
  // nan in any case, "-nan") except the '+' that the '+' flag puts in front; that sign is taken
  // off here, and only when a digit, '.', 'i' or 'n' follows ("+-1" and a lone "+" stay refused).
  if (!t.empty() && t.front() == '+') {
    t.remove_prefix(1);
    if (t.empty() || t.front() == '-' || t.front() == '+') return NumberText::kNotANumber;
  }
  const char* end = t.data() + t.size();
  double parsed = 0.0;
  const auto [ptr, ec] = std::from_chars(t.data(), end, parsed);
  if (ptr != end) return NumberText::kNotANumber;
  if (ec == std::errc::result_out_of_range) return NumberText::kOutOfRange;
  if (ec != std::errc()) return NumberText::kNotANumber;
  v = parsed;
  return std::isfinite(parsed) ? NumberText::kFinite : NumberText::kNotFinite;
}

bool parseFinite(std::string_view t, double& v) {
  return parseNumber(t, v) == NumberText::kFinite;
}

bool parseUnsigned(std::string_view t, unsigned long& v) {
  const char* end = t.data() + t.size();
  const auto [ptr, ec] = std::from_chars(t.data(), end, v, 10);
  return ec == std::errc() && ptr == end;
}

std::string number(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string shown(std::string_view token) {
  if (token.size() <= kMaxShownBytes) return std::string(token);
  std::size_t n = kMaxShownBytes;
  while (n > 0 && (static_cast<unsigned char>(token[n]) & 0xC0) == 0x80) --n;
  return std::string(token.substr(0, n)) + "...";
}

std::string found(std::string_view token) {
  if (token.empty()) return "found nothing";
  return "found '" + shown(token) + "'";
}

std::string foundNumber(std::string_view token) {
  double v = 0.0;
  switch (parseNumber(token, v)) {
    case NumberText::kNotFinite:
      return found(token) + ", which is not finite";
    case NumberText::kOutOfRange:
      return found(token) + ", which is out of the range of a double";
    case NumberText::kFinite:
    case NumberText::kNotANumber:
      break;
  }
  return found(token);
}

// ---------------------------------------------------------------------------------------------
// LineParser

LineParser::LineParser(ByteSource& source, const std::string& file, const LogOptions& options,
                       LoadReport& report)
    : file_(file),
      hooks_{options.progress, options.cancel},
      lines_(source, file, &hooks_),
      lenient_(options.lenient),
      report_(report) {}

void LineParser::fail(const std::string& field, const std::string& message) const {
  throw LogError(file_, lines_.lineNumber(), field, message);
}

double LineParser::finite(std::size_t i, const std::string& field,
                          std::string_view expected) const {
  double v = 0.0;
  if (!parseFinite(fields_[i], v))
    fail(field, "expected " + std::string(expected) + ", " + foundNumber(fields_[i]));
  return v;
}

}  // namespace sg::text
