// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The subcommands of sonargrid-cli (docs/cli.md). Each returns the process exit status.

#include "arguments.h"

namespace sg::cli {

int runModels(Arguments& args);
int runMap(Arguments& args);
int runScore(Arguments& args);
int runCompare(Arguments& args);
int runGoodness(Arguments& args);
int runSimulate(Arguments& args);
int runReproduce(Arguments& args);
int runConvert(Arguments& args);
int runRobot(Arguments& args);
int runRecord(Arguments& args);
int runSweepCommand(Arguments& args);
int runSweepMerge(Arguments& args);
int runOptimize(Arguments& args);
int runGoodnessStudy(Arguments& args);
int runBench(Arguments& args);

}  // namespace sg::cli
