// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A `.sglog` written while it is recorded (docs/formats.md, "Streamed logs"): the header first,
// then each scan appended as it comes, and 'end' when the recording finishes. Each scan goes to
// the file at once (a process killed with SIGKILL loses nothing it appended) and the file is
// fsync'd at least every `syncInterval` seconds of appending and on sync() (a machine that loses
// power loses at most that much). The header carries the 'streamed' record, so the file reads as
// a valid log whenever it is cut after a complete line, and the reader leaves out a last line cut
// short. Unlike writeSglog this is not atomic: the file is there, and growing, from the start.

#include <chrono>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>

#include "sonargrid/base/atomic_file.h"
#include "sonargrid/data/dataset.h"

namespace sg {

class SglogRecorder {
 public:
  // Creates `path` (replacing a file of that name), writes the header of `header` (its name and
  // ring; its scans are ignored), `startPose` (the robot's pose at the first scan in the map's
  // frame, when known) as its 'start_pose' record, and makes the file and its directory entry
  // durable. Throws std::runtime_error naming the path when it cannot (FileWriteError for the
  // file itself).
  SglogRecorder(const std::string& path, const Dataset& header, double syncInterval = 1.0,
                const std::optional<Pose2D>& startPose = std::nullopt);
  ~SglogRecorder();
  SglogRecorder(const SglogRecorder&) = delete;
  SglogRecorder& operator=(const SglogRecorder&) = delete;

  // Appends a scan. Throws std::runtime_error when the scan cannot be written (earlier than the
  // last one, a reading of a sonar outside the ring, a non-finite number) or the file cannot
  // (the disk is full); the file then still ends after the last complete scan.
  void append(const Scan& scan);
  // Appends `text` as a comment line ('# ' and the text, its line breaks made blanks): the reader
  // skips it. Throws like append().
  void comment(const std::string& text);
  // fsync when something was appended since the last one.
  void sync();
  // Appends 'end', syncs and closes; later calls do nothing. Throws like append().
  void finish();

  const std::string& path() const { return path_; }
  const SonarRing& ring() const { return ring_; }
  std::size_t scans() const { return scans_; }
  std::size_t readings() const { return readings_; }
  bool finished() const { return !file_; }

 private:
  [[noreturn]] void fail(const std::string& why) const;

  std::string path_;
  SonarRing ring_;
  std::optional<AppendFile> file_;  // none once finished
  std::chrono::steady_clock::duration syncInterval_;
  std::chrono::steady_clock::time_point lastSync_;
  bool dirty_ = false;
  double lastTime_ = -std::numeric_limits<double>::infinity();
  std::size_t scans_ = 0;
  std::size_t readings_ = 0;
  std::string buffer_;
};

}  // namespace sg
