// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Scans in time order as they arrive: the one road for scans (docs/architecture.md). A robot link
// appends them while a mapper and the views read them; a loaded log is a source that is complete
// (openLog(), io/log_reader.h), as PlotJuggler's loaders and streamers feed one data map. A
// Dataset is a source's complete view (view()): the scans so far with the name and ring, which
// the batch paths (metrics, the cell inspector, sweeps, exports) read. (docs/models.md, "Batch,
// incremental and live mapping".)
//
// One thread may append while others read. A reader takes a ScanPrefix, an immutable view of the
// scans appended so far, and reads it without locks for as long as it likes: appended scans are
// never moved or changed, so a prefix is always consistent (whole scans, in order).

#include <cstddef>
#include <memory>
#include <mutex>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "sonargrid/data/dataset.h"

namespace sg {

class ScanSourceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The first size() scans of a source, as they were when it was taken.
class ScanPrefix {
 public:
  ScanPrefix() = default;

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  // Whether the source was complete when this was taken: then this is the whole log.
  bool complete() const { return complete_; }
  // Whether every reading's time is at or after the one before it, over the whole prefix.
  bool readingsInTimeOrder() const { return ordered_; }
  const Scan& operator[](std::size_t i) const;
  // Scans [from, to) as contiguous spans, in order: what Mapper::append() takes.
  std::vector<std::span<const Scan>> spans(std::size_t from, std::size_t to) const;
  // Scans [from, to) copied out, e.g. for Dataset-based code.
  std::vector<Scan> copy(std::size_t from, std::size_t to) const;

 private:
  friend class ScanSource;
  struct Chunk {
    std::size_t start;  // index of its first scan in the source
    std::shared_ptr<const std::vector<Scan>> scans;
  };
  // Shared by every prefix taken between two appends.
  std::shared_ptr<const std::vector<Chunk>> chunks_;
  std::size_t size_ = 0;
  bool complete_ = false;
  bool ordered_ = true;
};

class ScanSource {
 public:
  // An empty live source for the ring that takes the scans.
  ScanSource(std::string name, SonarRing ring);
  // A loaded log: its scans, complete.
  explicit ScanSource(Dataset log);
  // The same, sharing the log (no copy): view() returns it.
  explicit ScanSource(std::shared_ptr<const Dataset> log);

  // Set at construction, never changed: read from any thread.
  const std::string& name() const { return name_; }
  const SonarRing& ring() const { return ring_; }

  // Appends scans after the last one. Throws ScanSourceError when the source is complete, or
  // when a scan's time is before the last scan's (a source is in time order).
  void append(std::vector<Scan> scans);
  // No more scans will come.
  void finish();

  bool complete() const;
  std::size_t size() const;
  ScanPrefix prefix() const;
  // The first `count` scans (at most size()) with the name and ring: a log, e.g. for saving.
  Dataset dataset(std::size_t count) const;
  // Every scan so far as a log, shared: for a loaded log the log itself; for a live source a copy
  // of its scans, made again only when scans came since the last call.
  std::shared_ptr<const Dataset> view() const;

 private:
  const std::string name_;
  const SonarRing ring_;
  mutable std::mutex mutex_;
  ScanPrefix state_;  // everything so far, replaced (not changed) by each append
  double lastScanTime_;
  double lastReadingTime_;
  mutable std::shared_ptr<const Dataset> view_;  // the last view(), of view_->scans.size() scans
};

}  // namespace sg
