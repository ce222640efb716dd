// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Every file SonarGrid writes (logs, map images, ROS maps, reference maps, reproduction tables,
// the GUI's exports) goes through this one helper, so that whoever opens the file — another
// program while we write, or this one after a crash or a power cut — finds either the old file or
// the complete new one, never a mixture or a prefix (docs/formats.md, "Writing files").
//
// The bytes go to a new file next to the target (same folder, so the rename stays within one file
// system), created exclusively under a name no other writer draws; the file is synced, renamed
// onto the target, and the folder is synced so that the rename itself survives a power cut.

#include <cstddef>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace sg {

// A file that could not be written. what() reads "cannot write 'PATH': REASON", or
// "cannot write KIND 'PATH': REASON" when a kind is given (e.g. "PNG"); REASON names the
// temporary file or the folder involved and the system's reason (strerror).
class FileWriteError : public std::runtime_error {
 public:
  FileWriteError(std::string path, std::string reason, const std::string& kind = {});

  const std::string& path() const { return path_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string path_;
  std::string reason_;
};

// Where the streaming form's bytes go: straight into the temporary file, in blocks.
class FileSink {
 public:
  FileSink(const FileSink&) = delete;
  FileSink& operator=(const FileSink&) = delete;

  // Throws FileWriteError when the bytes cannot be written (disk full, I/O error).
  void write(std::string_view bytes);
  FileSink& operator<<(std::string_view bytes) {
    write(bytes);
    return *this;
  }

 private:
  friend struct AtomicFileWriter;
  FileSink(int fd, const std::string& path, const std::string& temporary);
  void flush();
  void writeAll(std::string_view bytes);

  static constexpr std::size_t kBlockBytes = 64 * 1024;
  int fd_;
  const std::string& path_;
  const std::string& temporary_;
  std::string buffer_;
};

// A file grown by whole records while it is written: a recording's scans (SglogRecorder), a
// sweep's CSV rows. It is not atomic (the file is there, and growing, from the start); instead
// each append() is one write() of a whole record (retried until all of it is written), so that a
// process killed at any moment leaves whole records only, and sync() makes what was appended
// survive a power cut (fsync; the first sync after creating the file also syncs its folder, so
// that the new file's name survives too).
class AppendFile {
 public:
  enum class Start {
    Empty,  // create the file, or empty one that is there
    AtEnd,  // append to the file that is there, or create it
  };
  // Throws FileWriteError when the file cannot be opened.
  AppendFile(std::string path, Start start);
  // Closes without syncing (nothing throws); close() reports errors.
  ~AppendFile();
  AppendFile(const AppendFile&) = delete;
  AppendFile& operator=(const AppendFile&) = delete;

  // Throws FileWriteError (disk full, I/O error, closed): the file then ends after the records
  // appended before, unless the system wrote part of this one (a full disk).
  void append(std::string_view bytes);
  // Throws FileWriteError when the file or a new file's folder cannot be synced.
  void sync();
  // Closes; later calls do nothing. Throws FileWriteError when the system reports an error.
  void close();

  bool isOpen() const { return fd_ >= 0; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
  bool folderToSync_ = false;  // the file was created: its folder's entry is not durable yet
};

// The temporary name the writer draws for `path`: "PATH.<16 hex digits>.tmp" in the same folder
// (the file name shortened when the whole would pass 255 bytes). Each call gives another name; no
// two calls in any thread or process are meant to agree, and O_EXCL settles the rare case that they
// do.
std::string temporarySiblingName(const std::string& path);

// Replaces `path` by a file holding exactly `bytes`. On any failure the temporary file is removed,
// an existing file at `path` is left as it was, and FileWriteError says why; the one exception is
// a failure to sync the folder after the rename, which is reported although `path` already holds
// the new bytes. A symbolic link at `path` is followed: the file it points to is replaced.
void writeFileAtomically(const std::string& path, std::string_view bytes);

// The streaming form for outputs too large to hold twice in memory (long logs): `produce` writes
// the content to the sink. An exception thrown by `produce` removes the temporary file, leaves
// `path` as it was and propagates unchanged.
void writeFileAtomically(const std::string& path, const std::function<void(FileSink&)>& produce);

}  // namespace sg
