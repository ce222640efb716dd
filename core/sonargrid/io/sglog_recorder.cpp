// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/io/sglog_recorder.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "sonargrid/io/sglog.h"

namespace sg {
namespace {

std::string osReason(int err) {
  return std::error_code(err, std::generic_category()).message();
}

// The directory entry of a new file survives a power loss only once its directory is synced.
void syncDirectoryOf(const std::string& path) {
  std::filesystem::path dir = std::filesystem::path(path).parent_path();
  if (dir.empty()) dir = ".";
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;  // best effort: the file itself is synced either way
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

SglogRecorder::SglogRecorder(const std::string& path, const Dataset& header, double syncInterval)
    : path_(path),
      ring_(header.ring),
      syncInterval_(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
          std::chrono::duration<double>(syncInterval))) {
  std::string text;
  try {
    text = sglogHeaderText(header, true);
  } catch (const std::runtime_error& e) {
    fail(e.what());
  }
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd_ < 0) fail(osReason(errno));
  try {
    writeAll(text);
    if (::fsync(fd_) != 0) fail(osReason(errno));
  } catch (...) {
    ::close(fd_);
    fd_ = -1;
    throw;
  }
  syncDirectoryOf(path);
  lastSync_ = std::chrono::steady_clock::now();
}

SglogRecorder::~SglogRecorder() {
  try {
    finish();
  } catch (const std::exception&) {
    // A destructor must not throw; the file still ends after its last complete scan.
  }
  if (fd_ >= 0) ::close(fd_);
}

void SglogRecorder::fail(const std::string& why) const {
  throw std::runtime_error("cannot write '" + path_ + "': " + why);
}

void SglogRecorder::writeAll(const std::string& bytes) {
  const char* p = bytes.data();
  std::size_t left = bytes.size();
  while (left > 0) {
    const ssize_t n = ::write(fd_, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail(osReason(errno));
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
}

void SglogRecorder::append(const Scan& scan) {
  if (fd_ < 0) fail("the recording is finished");
  buffer_.clear();
  try {
    appendSglogScan(buffer_, scan, ring_, lastTime_);
  } catch (const std::runtime_error& e) {
    fail(e.what());
  }
  // One write per scan: the file grows by whole scans, so that a crash of this process leaves it
  // ending after a complete line.
  writeAll(buffer_);
  dirty_ = true;
  lastTime_ = scan.time;
  ++scans_;
  readings_ += scan.readings.size();
  if (std::chrono::steady_clock::now() - lastSync_ >= syncInterval_) sync();
}

void SglogRecorder::sync() {
  if (fd_ < 0 || !dirty_) return;
  if (::fsync(fd_) != 0) fail(osReason(errno));
  dirty_ = false;
  lastSync_ = std::chrono::steady_clock::now();
}

void SglogRecorder::finish() {
  if (fd_ < 0) return;
  writeAll(std::string(kSglogEndLine));
  dirty_ = true;
  sync();
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail(osReason(errno));
}

}  // namespace sg
