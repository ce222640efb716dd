// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/io/bag/bag.h"

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <system_error>
#include <utility>

namespace sg::bag {
namespace {

std::string compose(const std::string& file, std::uint64_t offset, const std::string& topic,
                    const std::string& message) {
  std::string text = file + ": offset " + std::to_string(offset);
  if (!topic.empty()) text += " (topic " + topic + ")";
  return text + ": " + message;
}

// "file ends at byte X, Y bytes short of the record" for `n` bytes wanted at `offset`.
BagError cutShort(const std::string& file, std::uint64_t size, std::uint64_t offset,
                  std::uint64_t n) {
  // How far the wanted range goes past the end, saturating instead of wrapping on garbage.
  const std::uint64_t start = offset > size ? offset - size : 0;
  const std::uint64_t avail = offset < size ? size - offset : 0;
  const std::uint64_t tail = n > avail ? n - avail : 0;
  const std::uint64_t shortBy = tail > std::numeric_limits<std::uint64_t>::max() - start
                                    ? std::numeric_limits<std::uint64_t>::max()
                                    : start + tail;
  return BagError(file, offset, "",
                  "the file is cut short: file ends at byte " + std::to_string(size) + ", " +
                      std::to_string(shortBy) + " bytes short of the record");
}

bool fits(std::uint64_t size, std::uint64_t offset, std::uint64_t n) {
  return offset <= size && n <= size - offset;
}

// A file read piece by piece: only what read() asks for is in memory.
class FileSource final : public ByteSource {
 public:
  explicit FileSource(std::string path) : path_(std::move(path)) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::file_status status = fs::status(path_, ec);
    if (ec || !fs::exists(status)) {
      const std::string reason =
          ec ? ec.message() : std::make_error_code(std::errc::no_such_file_or_directory).message();
      throw BagError(path_, 0, "", "cannot open: " + reason);
    }
    if (fs::is_directory(status)) throw BagError(path_, 0, "", "cannot open: it is a directory");
    if (!fs::is_regular_file(status)) {
      throw BagError(path_, 0, "", "cannot open: not a regular file");
    }
    size_ = fs::file_size(path_, ec);
    if (ec) throw BagError(path_, 0, "", "cannot open: " + ec.message());
    errno = 0;
    in_.open(path_, std::ios::binary);
    if (!in_) {
      const int err = errno != 0 ? errno : EACCES;
      throw BagError(path_, 0, "",
                     "cannot open: " + std::error_code(err, std::generic_category()).message());
    }
  }

  std::uint64_t size() const override { return size_; }
  const std::string& name() const override { return path_; }

  void read(std::uint64_t offset, std::size_t n, std::string& out) const override {
    if (!fits(size_, offset, n)) throw cutShort(path_, size_, offset, n);
    out.resize(n);
    if (n == 0) return;
    in_.clear();
    in_.seekg(static_cast<std::streamoff>(offset));
    in_.read(out.data(), static_cast<std::streamsize>(n));
    const auto got = static_cast<std::uint64_t>(in_.gcount());
    if (got != n) {
      // The file shrank since it was opened (a bag still being written, or truncated).
      throw BagError(path_, offset, "",
                     "read error: " + std::to_string(got) + " of " + std::to_string(n) +
                         " bytes read (the file changed while it was read?)");
    }
  }

 private:
  std::string path_;
  std::uint64_t size_ = 0;
  mutable std::ifstream in_;
};

// Bytes in memory; the source keeps its own copy, so that the caller's buffer may go away.
class MemorySource final : public ByteSource {
 public:
  MemorySource(std::string_view bytes, std::string name) : bytes_(bytes), name_(std::move(name)) {}

  std::uint64_t size() const override { return bytes_.size(); }
  const std::string& name() const override { return name_; }

  void read(std::uint64_t offset, std::size_t n, std::string& out) const override {
    if (!fits(bytes_.size(), offset, n)) throw cutShort(name_, bytes_.size(), offset, n);
    out.assign(bytes_, static_cast<std::size_t>(offset), n);
  }

 private:
  std::string bytes_;
  std::string name_;
};

}  // namespace

BagError::BagError(std::string file, std::uint64_t offset, std::string topic, std::string message)
    : std::runtime_error(compose(file, offset, topic, message)),
      file_(std::move(file)),
      offset_(offset),
      topic_(std::move(topic)),
      message_(std::move(message)) {}

std::unique_ptr<ByteSource> fileSource(const std::string& path) {
  return std::make_unique<FileSource>(path);
}

std::unique_ptr<ByteSource> memorySource(std::string_view bytes, std::string name) {
  return std::make_unique<MemorySource>(bytes, std::move(name));
}

Container detectContainer(std::string_view head) {
  // ROS 1 bag format 2.0's version line (http://wiki.ros.org/Bags/Format/2.0), MCAP's magic and
  // the first 16 bytes of every SQLite 3 database (rosbag2's default storage before Iron).
  if (head.starts_with("#ROSBAG V2.0\n")) return Container::Ros1;
  if (head.starts_with(std::string_view("\x89MCAP0\r\n", 8))) return Container::Mcap;
  if (head.starts_with(std::string_view("SQLite format 3\0", 16))) return Container::Sqlite;
  return Container::Unknown;
}

}  // namespace sg::bag
