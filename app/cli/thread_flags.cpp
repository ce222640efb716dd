// SPDX-License-Identifier: GPL-3.0-or-later
// --threads and SONARGRID_THREADS (docs/cli.md, "Threads"): every command that maps takes them.

#include "thread_flags.h"
#include "sonargrid/base/concurrency.h"

namespace sg::cli {

void applyThreadOptions(Arguments& args) {
  const int threads = args.integer("--threads", 0, 0, static_cast<int>(kMaxThreads));
  // A bad SONARGRID_THREADS is an error even when --threads overrides it: the core would otherwise
  // pass it over, and the next command run without --threads would quietly use every CPU.
  try {
    environmentThreadCount();
  } catch (const ThreadCountError& e) {
    throw UsageError(e.what());
  }
  setThreadCount(static_cast<unsigned>(threads));
}

}  // namespace sg::cli
