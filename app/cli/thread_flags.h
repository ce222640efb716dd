// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include "arguments.h"

namespace sg::cli {

// Consumes --threads N (1 to kMaxThreads; 0 or absent: SONARGRID_THREADS, else the CPUs the
// process may use) and sets the core's thread policy to it for the rest of the command. Throws
// UsageError for a bad --threads or a bad SONARGRID_THREADS (docs/cli.md, "Threads").
void applyThreadOptions(Arguments& args);

}  // namespace sg::cli
