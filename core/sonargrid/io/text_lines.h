// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What every text log reader shares: byte sources (a file, a stream, memory), a streaming line
// splitter with a line-length cap, progress and cancel, the UTF-8 check, field splitting and
// number parsing, and the quoting of offending tokens in error messages.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

#include "sonargrid/base/log_error.h"
#include "sonargrid/io/log_options.h"

namespace sg::text {

// A cap on line length keeps a corrupt or hostile file (one endless "line") from being buffered
// whole before we can say anything about it.
inline constexpr std::size_t kMaxLineBytes = 64 * 1024;

class ByteSource {
 public:
  virtual ~ByteSource() = default;
  // Reads up to n bytes; 0 means end of input. Throws LogError when the input cannot be read.
  virtual std::size_t read(char* dst, std::size_t n) = 0;
  // Total bytes, or 0 when unknown.
  virtual std::uint64_t size() const { return 0; }
  // Back to the first byte (after a format was sniffed); false when the source cannot.
  virtual bool rewind() { return false; }
};

// Opens `path` for reading (LogError "cannot open: ..." otherwise) and closes it when destroyed.
class FileSource : public ByteSource {
 public:
  explicit FileSource(const std::string& path);
  ~FileSource() override;
  FileSource(const FileSource&) = delete;
  FileSource& operator=(const FileSource&) = delete;
  std::size_t read(char* dst, std::size_t n) override;
  std::uint64_t size() const override { return size_; }
  bool rewind() override;

 private:
  std::FILE* f_ = nullptr;
  std::string path_;
  std::uint64_t size_ = 0;
};

class StreamSource : public ByteSource {
 public:
  StreamSource(std::istream& in, std::string file) : in_(in), file_(std::move(file)) {}
  std::size_t read(char* dst, std::size_t n) override;

 private:
  std::istream& in_;
  std::string file_;
};

class MemorySource : public ByteSource {
 public:
  explicit MemorySource(std::string_view bytes) : bytes_(bytes) {}
  std::size_t read(char* dst, std::size_t n) override;
  std::uint64_t size() const override { return bytes_.size(); }
  bool rewind() override {
    pos_ = 0;
    return true;
  }

 private:
  std::string_view bytes_;
  std::size_t pos_ = 0;
};

// Progress and cancel for a LineReader (LogOptions carries the user's).
struct LoadHooks {
  std::function<void(std::uint64_t done, std::uint64_t total)> progress;
  const std::atomic<bool>* cancel = nullptr;
};

// Splits the input into lines without copying them, in one pass, and enforces kMaxLineBytes
// before buffering more than that. After each block read it reports progress and honours cancel
// (throwing LoadCancelled).
class LineReader {
 public:
  LineReader(ByteSource& src, const std::string& file, const LoadHooks* hooks = nullptr);

  // The next line without its '\n' (or "\r\n"); valid until the following call. False at the end.
  bool next(std::string_view& line);
  std::size_t lineNumber() const { return line_; }
  // False when the line `next` returned last is a final line without its '\n' (a file cut short
  // inside its last line, or one that simply lacks the final line ending).
  bool lineEnded() const { return ended_; }

 private:
  static constexpr std::size_t kChunkBytes = 256 * 1024;
  static constexpr std::size_t kFullBytes = kMaxLineBytes + 1 + kChunkBytes;
  [[noreturn]] void throwTooLong() const;
  void refill();

  ByteSource& src_;
  const std::string& file_;
  const LoadHooks* hooks_;
  std::vector<char> buf_;
  std::size_t begin_ = 0;
  std::size_t end_ = 0;
  std::uint64_t bytesRead_ = 0;
  bool eof_ = false;
  bool ended_ = true;
  std::size_t line_ = 0;
};

// Throws LogError(file, line, "", "expected UTF-8 text, found byte 0x.. at column N") when the
// line holds a control byte (tab aside) or malformed UTF-8.
void requireText(std::string_view line, const std::string& file, std::size_t lineNumber);
// Offset of the first byte that is not printable UTF-8 text (tab allowed), or npos.
std::size_t firstBadByte(std::string_view s);
// Length of the well-formed UTF-8 sequence of two or more bytes that starts at p, or 0.
std::size_t utf8Sequence(const unsigned char* p, std::size_t n);
bool isControl(unsigned char c);
char hexDigit(unsigned v);

// The blank-separated fields of a line up to a '#' comment, appended to `out` after clearing it.
void splitFields(std::string_view line, std::vector<std::string_view>& out);
// The fields of a line split at `delimiter` (',' or ';'), each trimmed of blanks; a line that is
// empty or a comment gives none.
void splitDelimited(std::string_view line, char delimiter, std::vector<std::string_view>& out);

// What a number token of a log holds. Logs are written by C's printf (Player's writelog "%+07.3f",
// CARMEN's logger "%f"/"%lf", spreadsheets and scripts), so a token is read as printf writes
// one: an optional sign, '+' included, zero padding ("+00.500", "-01.250"), a fraction and an
// exponent ("1.5e+03"), and inf/nan in either case ("inf", "-INF", "+nan", "-nan").
enum class NumberText {
  kFinite,
  kNotFinite,   // inf or nan: a range, a pose or a time cannot be infinite
  kOutOfRange,  // a number too large or too small for a double ("1e400", "1e-400")
  kNotANumber,
};
NumberText parseNumber(std::string_view t, double& v);
// parseNumber() == kFinite.
bool parseFinite(std::string_view t, double& v);
bool parseUnsigned(std::string_view t, unsigned long& v);
// Shortest text that reads back to the same double.
std::string number(double v);

// A token as shown inside '...' in an error message: shortened, never cut inside UTF-8.
std::string shown(std::string_view token);
// "found 'TOKEN'", or "found nothing" for an empty token.
std::string found(std::string_view token);
// found(token), and for a token that reads as a number but not a finite one why it is refused:
// "found 'inf', which is not finite", "found '1e400', which is out of the range of a double".
std::string foundNumber(std::string_view token);

// The frame of a line-oriented reader: it feeds each line, checked as UTF-8 text and split into
// fields, to the reader's handler, and with LogOptions::lenient skips and counts the lines whose
// handler throws a LogError.
class LineParser {
 public:
  LineParser(ByteSource& source, const std::string& file, const LogOptions& options,
             LoadReport& report);

 protected:
  // `handle()` reads fields_ (blank-separated unless `delimiter` is ',' or ';'; empty for a blank
  // or comment line) and line_.
  template <class Handle>
  void eachLine(Handle&& handle, char delimiter = ' ') {
    while (lines_.next(line_)) {
      try {
        requireText(line_, file_, lines_.lineNumber());
        if (delimiter == ',' || delimiter == ';') {
          splitDelimited(line_, delimiter, fields_);
        } else {
          splitFields(line_, fields_);
        }
        handle();
      } catch (const LogError& e) {
        if (!lenient_) throw;
        report_.skip(e);
      }
    }
    report_.lines = lines_.lineNumber();
  }

  [[noreturn]] void fail(const std::string& field, const std::string& message) const;
  // fields_[i] as a finite number, else fail(field, "expected <expected>, " + foundNumber(...)).
  double finite(std::size_t i, const std::string& field, std::string_view expected) const;
  std::size_t lineNumber() const { return lines_.lineNumber(); }

  const std::string& file_;
  LoadHooks hooks_;
  LineReader lines_;
  bool lenient_;
  LoadReport& report_;
  std::string_view line_;
  std::vector<std::string_view> fields_;
};

}  // namespace sg::text
