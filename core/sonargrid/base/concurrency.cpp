// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/base/concurrency.h"

#include <algorithm>
#include <atomic>
#include <charconv>
#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <deque>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

#if defined(__linux__)
#include <sched.h>
#endif

namespace sg {
namespace {

std::atomic<unsigned> explicitCount{0};
std::atomic<int> startsBeforeFailure{-1};
// Set while this thread runs the work of a runParallel(): parallel paths inside it use one thread.
thread_local bool insideParallelRun = false;

class InsideParallelRun {
 public:
  InsideParallelRun() : previous_(insideParallelRun) { insideParallelRun = true; }
  ~InsideParallelRun() { insideParallelRun = previous_; }
  InsideParallelRun(const InsideParallelRun&) = delete;
  InsideParallelRun& operator=(const InsideParallelRun&) = delete;

 private:
  bool previous_;
};

// The test hook: throws as std::thread's constructor does when the system refuses a thread.
void checkInjectedStartFailure() {
  for (int left = startsBeforeFailure.load(); left >= 0;) {
    const int next = left == 0 ? -1 : left - 1;
    if (startsBeforeFailure.compare_exchange_weak(left, next)) {
      if (left == 0) {
        throw std::system_error(std::make_error_code(std::errc::resource_unavailable_try_again),
                                "cannot start a thread (injected by a test)");
      }
      return;
    }
  }
}

}  // namespace

unsigned affinityThreadCount() {
#if defined(__linux__)
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0) {
    const int count = CPU_COUNT(&set);
    if (count > 0) return static_cast<unsigned>(count);
  }
#endif
  const unsigned hardware = std::thread::hardware_concurrency();
  return hardware == 0 ? 1u : hardware;
}

unsigned parseThreadCount(std::string_view text, std::string_view what) {
  unsigned value = 0;
  const char* const end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc() || ptr != end || value < 1 || value > kMaxThreads) {
    throw ThreadCountError(std::string(what) + " expects a whole number of threads from 1 to " +
                           std::to_string(kMaxThreads) + ", got '" + std::string(text) + "'");
  }
  return value;
}

std::optional<unsigned> environmentThreadCount() {
  const char* value = std::getenv(kThreadsVariable);
  if (value == nullptr || *value == '\0') return std::nullopt;
  return parseThreadCount(value, kThreadsVariable);
}

void setThreadCount(unsigned count) {
  explicitCount.store(count);
}

unsigned explicitThreadCount() {
  return explicitCount.load();
}

unsigned automaticThreadCount() {
  try {
    if (const std::optional<unsigned> fromEnvironment = environmentThreadCount())
      return *fromEnvironment;
  } catch (const ThreadCountError&) {
    // Reported by the front end that started us (see the header).
  }
  return affinityThreadCount();
}

unsigned threadCount() {
  const unsigned count = explicitThreadCount();
  return count != 0 ? count : automaticThreadCount();
}

namespace {

// The share of the ThreadLease this thread holds; 0: none.
thread_local unsigned leasedHere = 0;

struct Budget {
  std::mutex mutex;
  std::condition_variable freed;
  unsigned leased = 0;            // every class
  unsigned leasedBackground = 0;  // of those, background leases
  std::uint64_t nextTicket = 0;
  std::deque<std::uint64_t> waiting[2];  // tickets in the order they came, by class
};

Budget& budget() {
  static Budget b;
  return b;
}

// The threads a lease of class `c` may take now.
unsigned freeFor(const Budget& b, LeaseClass c, unsigned capacity) {
  const unsigned all = capacity > b.leased ? capacity - b.leased : 0;
  if (c == LeaseClass::Interactive) return all;
  if (!b.waiting[int(LeaseClass::Interactive)].empty()) return 0;
  const unsigned share = capacity > 1 ? capacity - 1 : 1;
  return std::min(all, share > b.leasedBackground ? share - b.leasedBackground : 0u);
}

}  // namespace

unsigned parallelThreads() {
  if (insideParallelRun) return 1u;
  return leasedHere > 0 ? leasedHere : threadCount();
}

ThreadLease::ThreadLease(unsigned wanted, const std::atomic<bool>* cancel, LeaseClass leaseClass)
    : class_(leaseClass) {
  previous_ = leasedHere;
  if (previous_ > 0) {
    // A lease inside one: a share of the threads this thread holds, none taken anew (waiting here
    // for more would wait on itself).
    nested_ = true;
    threads_ = wanted == 0 ? previous_ : std::min(wanted, previous_);
    leasedHere = threads_;
    return;
  }
  Budget& b = budget();
  std::deque<std::uint64_t>& line = b.waiting[int(class_)];
  std::unique_lock lock(b.mutex);
  const std::uint64_t ticket = b.nextTicket++;
  line.push_back(ticket);
  for (;;) {
    if (cancel && cancel->load()) {
      line.erase(std::find(line.begin(), line.end(), ticket));
      lock.unlock();
      b.freed.notify_all();  // the one behind may be first now
      return;
    }
    // The capacity is read each time: the preference may change while a job waits.
    const unsigned free = line.front() == ticket ? freeFor(b, class_, threadCount()) : 0;
    if (free > 0) {
      threads_ = wanted == 0 ? free : std::min(wanted, free);
      break;
    }
    b.freed.wait_for(lock, std::chrono::milliseconds(5));
  }
  line.pop_front();
  b.leased += threads_;
  if (class_ == LeaseClass::Background) b.leasedBackground += threads_;
  leasedHere = threads_;
  lock.unlock();
  b.freed.notify_all();  // the next in line may take what is left
}

ThreadLease::~ThreadLease() {
  if (threads_ == 0) return;
  if (nested_) {
    leasedHere = previous_;
    return;
  }
  Budget& b = budget();
  {
    const std::lock_guard lock(b.mutex);
    b.leased -= threads_;
    if (class_ == LeaseClass::Background) b.leasedBackground -= threads_;
  }
  leasedHere = previous_;
  b.freed.notify_all();
}

unsigned ThreadLease::leased() {
  Budget& b = budget();
  const std::lock_guard lock(b.mutex);
  return b.leased;
}

void runParallel(unsigned count, const std::function<void(unsigned)>& work,
                 const std::function<void()>& stop) {
  if (count <= 1) {
    const InsideParallelRun inside;
    work(0);
    return;
  }
  std::mutex mutex;  // guards failure
  std::exception_ptr failure;
  // The first failure is kept and stops the others; a later one (often a consequence) is dropped.
  auto fail = [&](std::exception_ptr error) noexcept {
    {
      const std::lock_guard lock(mutex);
      if (failure) return;
      failure = std::move(error);
    }
    if (stop) stop();
  };
  auto guarded = [&](unsigned k) noexcept {
    const InsideParallelRun inside;
    try {
      work(k);
    } catch (...) {
      fail(std::current_exception());
    }
  };
  std::vector<std::thread> helpers;
  bool started = true;
  try {
    helpers.reserve(count - 1);
    for (unsigned k = 1; k < count; ++k) {
      checkInjectedStartFailure();
      helpers.emplace_back(guarded, k);
    }
  } catch (...) {
    // The work is shared out by thread: without this one the run cannot finish. Stop the others.
    fail(std::current_exception());
    started = false;
  }
  if (started) guarded(0);
  for (std::thread& t : helpers) t.join();
  if (failure) std::rethrow_exception(failure);
}

namespace testing {
void failThreadStartAfter(int succeed) {
  startsBeforeFailure.store(succeed < 0 ? -1 : succeed);
}
}  // namespace testing

}  // namespace sg
