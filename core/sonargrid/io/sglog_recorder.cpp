// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/io/sglog_recorder.h"

#include <stdexcept>

#include "sonargrid/io/sglog.h"

namespace sg {

SglogRecorder::SglogRecorder(const std::string& path, const Dataset& header, double syncInterval,
                             const std::optional<Pose2D>& startPose)
    : path_(path),
      ring_(header.ring),
      syncInterval_(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
          std::chrono::duration<double>(syncInterval))) {
  std::string text;
  try {
    text = sglogHeaderText(header, true, startPose);
  } catch (const std::runtime_error& e) {
    fail(e.what());
  }
  // The header, durable with the file's name before the first scan (base/atomic_file.h).
  file_.emplace(path, AppendFile::Start::Empty);
  file_->append(text);
  file_->sync();
  lastSync_ = std::chrono::steady_clock::now();
}

SglogRecorder::~SglogRecorder() {
  try {
    finish();
  } catch (const std::exception&) {
    // A destructor must not throw; the file still ends after its last complete scan.
  }
}

void SglogRecorder::fail(const std::string& why) const {
  throw std::runtime_error("cannot write '" + path_ + "': " + why);
}

void SglogRecorder::append(const Scan& scan) {
  if (!file_) fail("the recording is finished");
  buffer_.clear();
  try {
    appendSglogScan(buffer_, scan, ring_, lastTime_);
  } catch (const std::runtime_error& e) {
    fail(e.what());
  }
  // One write per scan: the file grows by whole scans, so that a crash of this process leaves it
  // ending after a complete line.
  file_->append(buffer_);
  dirty_ = true;
  lastTime_ = scan.time;
  ++scans_;
  readings_ += scan.readings.size();
  if (std::chrono::steady_clock::now() - lastSync_ >= syncInterval_) sync();
}

void SglogRecorder::comment(const std::string& text) {
  if (!file_) fail("the recording is finished");
  buffer_ = "# ";
  for (const char c : text) buffer_ += static_cast<unsigned char>(c) < 0x20 || c == 0x7F ? ' ' : c;
  buffer_ += '\n';
  file_->append(buffer_);
  dirty_ = true;
}

void SglogRecorder::sync() {
  if (!file_ || !dirty_) return;
  file_->sync();
  dirty_ = false;
  lastSync_ = std::chrono::steady_clock::now();
}

void SglogRecorder::finish() {
  if (!file_) return;
  file_->append(kSglogEndLine);
  dirty_ = true;
  sync();
  try {
    file_->close();
  } catch (...) {
    file_.reset();
    throw;
  }
  file_.reset();
}

}  // namespace sg
