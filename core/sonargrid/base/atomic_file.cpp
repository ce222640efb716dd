// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/base/atomic_file.h"

// POSIX calls: open(O_EXCL), fsync and a folder's fsync have no portable C++ spelling, and the
// project builds on Linux (.ci).
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <filesystem>
#include <random>
#include <system_error>
#include <utility>

namespace sg {
namespace {

namespace fs = std::filesystem;

// strerror's text, without strerror's shared buffer (writers run on several threads).
std::string osReason(int err) {
  return std::error_code(err, std::generic_category()).message();
}

// Longest file name most Linux file systems take (NAME_MAX).
constexpr std::size_t kMaxNameBytes = 255;
// ".<16 hex digits>.tmp"
constexpr std::size_t kSuffixBytes = 1 + 16 + 4;
// Names drawn before giving up; each is 64 random bits, so a second draw is already rare.
constexpr int kNameAttempts = 64;

// 64 bits that no other writer draws: a per-thread generator seeded from the system's entropy,
// mixed with the process id and a process-wide counter, so that even a generator seeded alike in
// two processes (a poor random_device) or two threads gives different names.
std::uint64_t uniqueBits() {
  static std::atomic<std::uint64_t> counter{0};
  thread_local std::mt19937_64 random{(std::uint64_t{std::random_device{}()} << 32U) ^
                                      std::random_device{}()};
  std::uint64_t z = random() ^ (static_cast<std::uint64_t>(::getpid()) << 40U) ^
                    counter.fetch_add(1, std::memory_order_relaxed);
  // splitmix64's finaliser spreads the pid and counter bits over the whole word.
  z = (z ^ (z >> 30U)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27U)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31U);
}

// PATH.<16 hex>.tmp beside the target; a name too long for that is shortened (never its folder).
std::string temporaryNameFor(const fs::path& folder, const std::string& name) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string stem = name;
  if (stem.size() + kSuffixBytes > kMaxNameBytes) {
    std::size_t cut = kMaxNameBytes - kSuffixBytes;
    // Not inside a UTF-8 sequence: back to the byte that starts it.
    while (cut > 0 && (static_cast<unsigned char>(stem[cut]) & 0xC0U) == 0x80U) --cut;
    stem.resize(cut);
  }
  stem += '.';
  std::uint64_t bits = uniqueBits();
  for (int i = 0; i < 16; ++i, bits >>= 4U) stem += kHex[bits & 0xFU];
  stem += ".tmp";
  return (folder / stem).string();
}

void closeQuietly(int fd) {
  if (fd >= 0) ::close(fd);
}

void removeQuietly(const std::string& file) {
  if (!file.empty()) ::unlink(file.c_str());
}

// Retries the calls a signal may interrupt.
int syncRetrying(int fd) {
  int rc = 0;
  do {
    rc = ::fsync(fd);
  } while (rc != 0 && errno == EINTR);
  return rc;
}

// Writes all of `bytes` to `fd` (a short write, or one a signal interrupts, continues where it
// stopped); returns why it could not, or nothing.
std::string writeWhole(int fd, std::string_view bytes) {
  const char* data = bytes.data();
  std::size_t left = bytes.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, data, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      return osReason(errno);
    }
    // write() of a positive count does not return 0 on a file; do not spin if it ever does.
    if (n == 0) return "the system accepted no bytes";
    data += n;
    left -= static_cast<std::size_t>(n);
  }
  return {};
}

// Makes a new or renamed file's name in `folder` durable. A folder we may not open for reading
// (write and search permission only) cannot be synced by us; file systems that cannot sync a
// folder say EINVAL. `what` starts the message: what is in place although the folder is not synced.
void syncFolderOf(const fs::path& folder, const std::string& path, const std::string& what) {
  const int dir = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir < 0) return;
  const int rc = syncRetrying(dir);
  const int err = errno;
  ::close(dir);
  if (rc != 0 && err != EINVAL && err != ENOTSUP && err != EROFS)
    throw FileWriteError(path, what + " but the directory '" + folder.string() +
                                   "' cannot be synced: " + osReason(err));
}

fs::path folderOf(const std::string& path) {
  const fs::path folder = fs::path(path).parent_path();
  return folder.empty() ? fs::path(".") : folder;
}

}  // namespace

FileWriteError::FileWriteError(std::string path, std::string reason, const std::string& kind)
    : std::runtime_error("cannot write " + (kind.empty() ? std::string() : kind + " ") + "'" +
                         path + "': " + reason),
      path_(std::move(path)),
      reason_(std::move(reason)) {}

FileSink::FileSink(int fd, const std::string& path, const std::string& temporary)
    : fd_(fd), path_(path), temporary_(temporary) {
  buffer_.reserve(kBlockBytes);
}

void FileSink::write(std::string_view bytes) {
  if (buffer_.size() + bytes.size() <= kBlockBytes) {
    buffer_.append(bytes);
    return;
  }
  flush();
  if (bytes.size() < kBlockBytes)
    buffer_.append(bytes);
  else
    writeAll(bytes);  // a large block goes to the file without a copy
}

void FileSink::flush() {
  writeAll(buffer_);
  buffer_.clear();
}

void FileSink::writeAll(std::string_view bytes) {
  const std::string reason = writeWhole(fd_, bytes);
  if (!reason.empty())
    throw FileWriteError(path_, "cannot write the temporary file '" + temporary_ + "': " + reason);
}

// One write from start to finish: the temporary file's descriptor and name, removed again unless
// the rename took it.
struct AtomicFileWriter {
  std::string path;  // as the caller gave it: every message names it
  fs::path target;   // what is replaced: `path`, or the file its symbolic link points to
  fs::path folder;
  std::string temporary;
  int fd = -1;

  explicit AtomicFileWriter(std::string p) : path(std::move(p)) {
    if (path.empty()) throw FileWriteError(path, "no file name given");
    target = fs::path(path);
    std::error_code ec;
    if (fs::is_symlink(fs::symlink_status(target, ec))) {
      // Replace the file the link names, keep the link (as editors and QSaveFile do).
      const fs::path resolved = fs::canonical(target, ec);
      if (!ec) target = resolved;
    }
    if (!target.has_filename()) throw FileWriteError(path, "the path names a folder, not a file");
    folder = target.parent_path();
    if (folder.empty()) folder = ".";
    if (fs::is_directory(fs::status(target, ec))) throw FileWriteError(path, "it is a directory");
  }

  ~AtomicFileWriter() {
    closeQuietly(fd);
    removeQuietly(temporary);
  }
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;

  void create() {
    const std::string name = target.filename().string();
    for (int attempt = 0; attempt < kNameAttempts; ++attempt) {
      const std::string candidate = temporaryNameFor(folder, name);
      // 0666 less the umask: the permissions a plain new file would get.
      const int f = ::open(candidate.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
      if (f >= 0) {
        fd = f;
        temporary = candidate;
        keepPermissions();
        return;
      }
      const int err = errno;
      if (err == EEXIST || err == EINTR) continue;  // another writer drew that name
      // The system's "No such file or directory" reads as if the target itself were meant.
      std::error_code ec;
      const fs::file_status folderStatus = fs::status(folder, ec);
      if ((err == ENOENT || err == ENOTDIR) && !fs::exists(folderStatus))
        throw FileWriteError(path, "directory '" + folder.string() + "' does not exist");
      if (err == ENOTDIR && !fs::is_directory(folderStatus))
        throw FileWriteError(path, "'" + folder.string() + "' is not a directory");
      throw FileWriteError(
          path, "cannot create the temporary file '" + candidate + "': " + osReason(err));
    }
    throw FileWriteError(path, "cannot create a temporary file in '" + folder.string() +
                                   "': every name drawn was taken");
  }

  void fill(const std::function<void(FileSink&)>& produce) {
    FileSink sink(fd, path, temporary);
    produce(sink);
    sink.flush();
  }

  // A file replaced keeps who may read it (a private log stays private).
  void keepPermissions() const {
    struct stat old {};
    if (::stat(target.c_str(), &old) == 0 && S_ISREG(old.st_mode))
      ::fchmod(fd, old.st_mode & 07777);  // best effort: the new file is written either way
  }

  void commit() {
    if (syncRetrying(fd) != 0)
      throw FileWriteError(
          path, "cannot sync the temporary file '" + temporary + "': " + osReason(errno));
    const int f = fd;
    fd = -1;
    // Linux closes the descriptor even when close() reports EINTR; only a real error counts.
    if (::close(f) != 0 && errno != EINTR)
      throw FileWriteError(
          path, "cannot close the temporary file '" + temporary + "': " + osReason(errno));
    if (::rename(temporary.c_str(), target.c_str()) != 0)
      throw FileWriteError(path, "cannot rename '" + temporary + "' to it: " + osReason(errno));
    temporary.clear();  // it is the target now
    syncFolder();
  }

  // Makes the rename itself durable.
  void syncFolder() const { syncFolderOf(folder, path, "the new file is in place"); }
};

void writeFileAtomically(const std::string& path, const std::function<void(FileSink&)>& produce) {
  AtomicFileWriter writer(path);
  writer.create();
  writer.fill(produce);
  writer.commit();
}

std::string temporarySiblingName(const std::string& path) {
  const fs::path target(path);
  return temporaryNameFor(target.parent_path(), target.filename().string());
}

void writeFileAtomically(const std::string& path, std::string_view bytes) {
  writeFileAtomically(path, [bytes](FileSink& sink) { sink.write(bytes); });
}

AppendFile::AppendFile(std::string path, Start start) : path_(std::move(path)) {
  struct stat old {};
  folderToSync_ = ::stat(path_.c_str(), &old) != 0;  // created here
  const int flags = O_WRONLY | O_CREAT | O_CLOEXEC | (start == Start::Empty ? O_TRUNC : O_APPEND);
  do {
    fd_ = ::open(path_.c_str(), flags, 0666);
  } while (fd_ < 0 && errno == EINTR);
  if (fd_ < 0) throw FileWriteError(path_, osReason(errno));
}

AppendFile::~AppendFile() {
  closeQuietly(fd_);
}

void AppendFile::append(std::string_view bytes) {
  if (fd_ < 0) throw FileWriteError(path_, "the file is closed");
  const std::string reason = writeWhole(fd_, bytes);
  if (!reason.empty()) throw FileWriteError(path_, reason);
}

void AppendFile::sync() {
  if (fd_ < 0) throw FileWriteError(path_, "the file is closed");
  if (syncRetrying(fd_) != 0) throw FileWriteError(path_, "cannot sync it: " + osReason(errno));
  if (folderToSync_) {
    syncFolderOf(folderOf(path_), path_, "the file is synced");
    folderToSync_ = false;
  }
}

void AppendFile::close() {
  if (fd_ < 0) return;
  const int f = fd_;
  fd_ = -1;
  // Linux closes the descriptor even when close() reports EINTR; only a real error counts.
  if (::close(f) != 0 && errno != EINTR) throw FileWriteError(path_, osReason(errno));
}

}  // namespace sg
