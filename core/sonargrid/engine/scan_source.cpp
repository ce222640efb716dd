// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/engine/scan_source.h"

#include <algorithm>
#include <limits>
#include <utility>

namespace sg {

namespace {

// Appends to a source whose last chunk holds fewer scans than this are merged into a copy of it,
// so that a link appending a scan at a time leaves few chunks (a prefix copies the list of them).
constexpr std::size_t kSmallChunk = 512;

// Whether the readings of `scans` are in time order, after a reading at `last`; moves `last` on.
bool readingsOrdered(std::span<const Scan> scans, double& last) {
  bool ordered = true;
  for (const Scan& s : scans)
    for (const Reading& r : s.readings) {
      if (r.time < last) ordered = false;
      last = r.time;
    }
  return ordered;
}

}  // namespace

const Scan& ScanPrefix::operator[](std::size_t i) const {
  if (i >= size_) throw std::out_of_range("scan " + std::to_string(i) + " is past the prefix");
  const std::vector<Chunk>& chunks = *chunks_;
  const auto it = std::upper_bound(chunks.begin(), chunks.end(), i,
                                   [](std::size_t k, const Chunk& c) { return k < c.start; });
  const Chunk& c = *(it - 1);
  return (*c.scans)[i - c.start];
}

std::vector<std::span<const Scan>> ScanPrefix::spans(std::size_t from, std::size_t to) const {
  std::vector<std::span<const Scan>> out;
  to = std::min(to, size_);
  if (from >= to) return out;
  for (const Chunk& c : *chunks_) {
    const std::size_t end = c.start + c.scans->size();
    if (end <= from || c.start >= to) continue;
    const std::size_t a = std::max(from, c.start) - c.start;
    const std::size_t b = std::min(to, end) - c.start;
    out.emplace_back(c.scans->data() + a, b - a);
  }
  return out;
}

std::vector<Scan> ScanPrefix::copy(std::size_t from, std::size_t to) const {
  std::vector<Scan> out;
  for (std::span<const Scan> s : spans(from, to)) out.insert(out.end(), s.begin(), s.end());
  return out;
}

ScanSource::ScanSource(std::string name, SonarRing ring)
    : name_(std::move(name)),
      ring_(std::move(ring)),
      lastScanTime_(-std::numeric_limits<double>::infinity()),
      lastReadingTime_(-std::numeric_limits<double>::infinity()) {
  state_.chunks_ = std::make_shared<const std::vector<ScanPrefix::Chunk>>();
}

ScanSource::ScanSource(Dataset log) : ScanSource(std::make_shared<const Dataset>(std::move(log))) {}

ScanSource::ScanSource(std::shared_ptr<const Dataset> log)
    : ScanSource(log ? log->name : std::string(), log ? log->ring : SonarRing()) {
  if (log && !log->scans.empty()) {
    state_.size_ = log->scans.size();
    state_.ordered_ = readingsOrdered(log->scans, lastReadingTime_);
    lastScanTime_ = log->scans.back().time;
    // The chunk shares the log's scans: it keeps the log alive.
    std::shared_ptr<const std::vector<Scan>> scans(log, &log->scans);
    state_.chunks_ = std::make_shared<const std::vector<ScanPrefix::Chunk>>(
        std::vector<ScanPrefix::Chunk>{{0, std::move(scans)}});
  }
  state_.complete_ = true;
  view_ = log ? std::move(log) : std::make_shared<const Dataset>(Dataset{name_, ring_, {}});
}

void ScanSource::append(std::vector<Scan> scans) {
  if (scans.empty()) return;
  std::lock_guard lock(mutex_);
  if (state_.complete_) throw ScanSourceError("scans appended to a source that is complete");
  double last = lastScanTime_;
  for (const Scan& s : scans) {
    if (s.time < last) {
      throw ScanSourceError("a scan at t = " + std::to_string(s.time) +
                            " s came after one at t = " + std::to_string(last) +
                            " s; scans must arrive in time order");
    }
    last = s.time;
  }
  // Nothing is changed before this point, so a refused batch leaves the source as it was.
  lastScanTime_ = last;
  const bool ordered = readingsOrdered(scans, lastReadingTime_);

  auto chunks = std::make_shared<std::vector<ScanPrefix::Chunk>>(*state_.chunks_);
  if (!chunks->empty() && chunks->back().scans->size() < kSmallChunk) {
    // Readers may hold the old chunk: merge into a copy.
    auto merged = std::make_shared<std::vector<Scan>>(*chunks->back().scans);
    merged->insert(merged->end(), std::make_move_iterator(scans.begin()),
                   std::make_move_iterator(scans.end()));
    chunks->back().scans = std::move(merged);
  } else {
    chunks->push_back({state_.size_, std::make_shared<const std::vector<Scan>>(std::move(scans))});
  }
  state_.size_ = chunks->back().start + chunks->back().scans->size();
  state_.ordered_ = state_.ordered_ && ordered;
  state_.chunks_ = std::move(chunks);
}

void ScanSource::finish() {
  std::lock_guard lock(mutex_);
  state_.complete_ = true;
}

bool ScanSource::complete() const {
  std::lock_guard lock(mutex_);
  return state_.complete_;
}

std::size_t ScanSource::size() const {
  std::lock_guard lock(mutex_);
  return state_.size_;
}

ScanPrefix ScanSource::prefix() const {
  std::lock_guard lock(mutex_);
  return state_;
}

std::shared_ptr<const Dataset> ScanSource::view() const {
  const ScanPrefix p = prefix();
  {
    const std::lock_guard lock(mutex_);
    if (view_ && view_->scans.size() == p.size()) return view_;
  }
  auto d = std::make_shared<const Dataset>(Dataset{name_, ring_, p.copy(0, p.size())});
  const std::lock_guard lock(mutex_);
  // Another thread may have made a longer one meanwhile: keep the longest.
  if (!view_ || view_->scans.size() < d->scans.size()) view_ = d;
  return d;
}

Dataset ScanSource::dataset(std::size_t count) const {
  const ScanPrefix p = prefix();
  Dataset d;
  d.name = name_;
  d.ring = ring_;
  d.scans = p.copy(0, count);
  return d;
}

}  // namespace sg
