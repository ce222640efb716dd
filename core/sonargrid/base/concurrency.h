// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The thread policy every parallel path of the core reads (DESIGN.md, "Threading"), and the one way
// they run work on several threads.
//
// How many threads: an explicit count (the CLI's --threads, the app's preference) over the
// SONARGRID_THREADS environment variable over the CPUs this process may run on. The last is the
// process's affinity mask, not the machine's core count: a batch job that Slurm or `taskset` gave
// 4 of a node's 64 cores must not start 64 threads on them.
//
// How: runParallel() starts the threads, catches an exception thrown by any of them and a thread
// that cannot be started, stops and joins the rest, and rethrows to the caller. Nothing on a
// parallel path may end in std::terminate or wait forever for a thread that has failed.

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace sg {

// A thread count that is not a whole number from 1 to kMaxThreads.
class ThreadCountError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// More threads than this is a typing mistake, not a machine.
inline constexpr unsigned kMaxThreads = 1024;
inline constexpr const char* kThreadsVariable = "SONARGRID_THREADS";

// The number of CPUs in this process's affinity mask (sched_getaffinity), what Slurm, cgroups'
// cpusets and `taskset` grant; std::thread::hardware_concurrency() where the mask cannot be read.
// At least 1.
unsigned affinityThreadCount();

// `text` as a thread count: a whole number from 1 to kMaxThreads, nothing else (no sign, no
// spaces). Throws ThreadCountError naming `what` (e.g. "SONARGRID_THREADS") and the text.
unsigned parseThreadCount(std::string_view text, std::string_view what);

// SONARGRID_THREADS: empty when unset or set to the empty string; throws ThreadCountError for any
// other value that parseThreadCount() refuses.
std::optional<unsigned> environmentThreadCount();

// The explicit count, which beats everything else; 0 clears it. Thread-safe; a parallel run
// already started keeps the count it started with.
void setThreadCount(unsigned count);
unsigned explicitThreadCount();  // 0 when none is set

// The count without an explicit one: SONARGRID_THREADS, else affinityThreadCount(). A bad
// SONARGRID_THREADS is passed over here (the core has no one to tell): the front ends check it
// with environmentThreadCount() when they start and report it.
unsigned automaticThreadCount();

// The policy: explicitThreadCount() if set, else automaticThreadCount().
unsigned threadCount();

// The threads a parallel path started here may use: threadCount(), the share of a ThreadLease
// held by this thread, or 1 inside the work of a runParallel() (a sweep's sets already occupy every
// thread; a map's snapshot inside one must not start as many again).
unsigned parallelThreads();

// The thread budget that jobs running side by side share (the app's re-map, metrics, cell
// inspector, comparison and sweep, each on a worker of its own). A job takes a lease on its worker
// thread before it starts work; while the lease lives, parallelThreads() there returns its share,
// so the job's parallel paths start no more threads than it holds. The leases held at once never
// add up to more than threadCount(): a job whose turn comes while the threads it may take are
// leased waits for one to come back. Turns are first come, first served within a class, and a
// waiting interactive lease goes before every background one. Background leases together keep one
// thread for the interactive class when the policy grants two or more, so that the view's re-map
// starts at once whatever else runs. A lease is taken whole, never grown: a job never waits while
// holding one, so jobs cannot wait on each other. Results do not depend on the share (every
// parallel path is bit-identical at any thread count).
enum class LeaseClass { Interactive, Background };

class ThreadLease {
 public:
  // Waits for its turn and a free thread, then takes up to `wanted` of the threads free to its
  // class (0: all of them; at least 1). While waiting it looks at `cancel` every few milliseconds:
  // when that turns true it stops waiting and the lease holds nothing (threads() == 0).
  explicit ThreadLease(unsigned wanted = 0, const std::atomic<bool>* cancel = nullptr,
                       LeaseClass leaseClass = LeaseClass::Background);
  ~ThreadLease();  // gives the threads back and wakes the jobs waiting for them
  ThreadLease(const ThreadLease&) = delete;
  ThreadLease& operator=(const ThreadLease&) = delete;

  unsigned threads() const { return threads_; }

  // Threads leased now, over every lease of the process.
  static unsigned leased();

 private:
  unsigned threads_ = 0;
  unsigned previous_ = 0;  // this thread's share before, restored at the end
  bool nested_ = false;    // inside another lease of this thread: nothing taken from the budget
  LeaseClass class_;
};

// Sets an explicit count for its lifetime (a test, a batch step), then restores the one before.
class ScopedThreadCount {
 public:
  explicit ScopedThreadCount(unsigned count) : previous_(explicitThreadCount()) {
    setThreadCount(count);
  }
  ~ScopedThreadCount() { setThreadCount(previous_); }
  ScopedThreadCount(const ScopedThreadCount&) = delete;
  ScopedThreadCount& operator=(const ScopedThreadCount&) = delete;

 private:
  unsigned previous_;
};

// Runs work(0) on the calling thread and work(1) ... work(count − 1) on threads it starts (count 0
// counts as 1), and returns when every one has returned. If any throws, or a thread cannot be
// started (std::system_error), `stop` is called once, on the thread that failed, and must make the
// others return soon: set their stop flag and wake every thread waiting on another (a worker left
// waiting for the failed one would hang the run). When every started thread has been joined, the
// first failure is rethrown here. After a failed start the calling thread does not run work(0).
// `stop` must not throw.
void runParallel(unsigned count, const std::function<void(unsigned)>& work,
                 const std::function<void()>& stop = {});

namespace testing {
// Makes a thread start fail as it does when the system has no thread to give: the next `succeed`
// starts by runParallel() succeed, the one after throws std::system_error
// (resource_unavailable_try_again), and later starts succeed again. Negative: no failure (the
// default).
void failThreadStartAfter(int succeed);
}  // namespace testing

}  // namespace sg
