// SPDX-License-Identifier: GPL-3.0-or-later
// sonargrid-cli: the headless face of SonarGrid. Exit status: 0 success, 2 bad arguments or input
// the user must fix (one line on stderr says what), 1 anything else (e.g. an output not written).

#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "commands.h"
#include "sonargrid/engine/grid_spec.h"

namespace {

constexpr const char* kUsage = R"(usage: sonargrid-cli COMMAND [OPTIONS]

commands:
  models [--json | --markdown]
                             list sensor models, update rules, their parameters and allowed pairs
  map --log FILE --model M --rule R [--pose odom|truth] [--set NAME=VALUE]...
      [--cell METRES] [--until SECONDS] [--png FILE [--legend] [--scale N]]
      [--ros-map BASENAME] [--threads N] [--json]
                             build an occupancy grid from a log
  map --log FILE --model forward-em [--iterations N] [same flags as above]
                             the forward model's map, learned by EM (docs/forward-model.md)
  score --reference REF (--log FILE [map flags] | --map FILE.yaml)
      [--metrics LIST] [--pairs N] [--seed N] [--iop-weight evidence|level]
      [--filled-threshold CV] [--json]
                             score a map against a reference (JSON, ArMap .map or ROS
                             .yaml): IOP, correlation, map score, match, path comparison,
                             cross-entropy, Brier, AUC, precision/recall/F1/IoU
  compare --log FILE [--log FILE]... --reference REF --config MODEL/RULE[:P=V,...] ...
      [--cells common|own] [--cell M] [--pose odom|truth] [score's flags]
      [--csv OUT] [--markdown OUT] [--threads N] [--json]
                             every reference metric per configuration, mean and standard
                             deviation over the logs, on the cells all of them observed
  goodness --log FILE [map flags] [--second-log FILE] [--json]
                             map quality without a reference: VSDNS, derivative noise,
                             map entropy, two-run comparison
  simulate --world WORLD.json --robot k2a|p3dx|amigobot
      --route in-motion|stop-and-scan|u-turn [--route-file FILE] [--stops N]
      [--duration S] [--seed N] [--drift on|off] --out LOG.sglog
                             simulate a sonar log in a reference-map world
  reproduce raschke1990|osullivan|arafat|thrun2003 --out DIR [--datasets DIR] [--json]
      [--progress] [--sets N] [--threads N]
                             rerun a paper's experiment on the bundled datasets: tables
                             (Markdown, CSV) and figures (PNG) in DIR/PAPER
  convert --in FILE --out FILE [--to sglog|carmen] [--json]
                             rewrite a log as .sglog or CARMEN
  robot --world WORLD.json [--robot p3dx|amigobot] [--port N] [--bind ADDRESS]
      [--route in-motion|stop-and-scan|u-turn [--route-file FILE] [--stops N] | --teleop]
      [--seed N] [--drift on|off] [--duration S] [--time-scale K] [--log-out LOG.sglog]
                             serve a virtual robot over ARCOS (TCP), one client at a time
  record --connect tcp://HOST[:PORT]|serial://DEVICE[?baud=N] --out LOG.sglog
      [--duration S] [--wander] [--robot p3dx|amigobot] [--start-pose X,Y,THETA] [--json]
                             record a live robot's sonar to a log as it streams
  sweep --log FILE [--second-log FILE] [--reference REF] [map flags]
      --grid "P=FROM:STEP:TO" | --grid "P=V1,V2,..." ... [--tie "P=1-Q"]...
      --metric vsdns|derivative|entropy|two-run|iop|correlation|auc|... ...
      [--shard I/N] --csv OUT.csv [--json] [--progress]
                             one map per parameter set, rows streamed to a CSV that
                             resumes after Ctrl-C; shards for job arrays (docs/sweeps.md)
  sweep-merge SHARD.csv... --csv ALL.csv [--json]
                             join a sweep's shards, rows in set order
  optimize --log FILE [sweep's flags, no --grid] --range P=LO:HI ... [--tie ...]
      --metric M ... [--budget N] [--seed N] [--algorithm crs2+bobyqa|...]
      [--csv PATH.csv] [--json] [--progress]
                             search the ranges for the best set of the first --metric
                             with NLopt, reporting every evaluation (docs/sweeps.md)
  goodness-study --log FILE [--second-log FILE] --reference REF [map flags]
      --grid ... [--tie ...] [--bootstrap N] [--seed N] [--threads N] [--csv OUT.csv]
      [--json] [--progress]
                             Spearman's rho between each reference-free measure and each
                             reference metric over a sweep's sets, with bootstrap
                             intervals (docs/goodness-study.md)
  bench [--quick] [--json] [--threads N] [--progress]
                             time the standard workloads: office and 100k-reading
                             re-maps per pair, a 1M-reading load, bytes per cell
  help                       this text

log flags (every command that reads a log):
  --format auto|sglog|carmen|player|csv   --lenient   --robot PRESET|GEOMETRY_FILE
  --columns SPEC   --poses FILE           (docs/formats.md)
  --start-pose X,Y,THETA   the robot's pose at the first scan in the reference's frame
                           (metres, metres, degrees): the odometry is moved there

threads (map, score --log, compare, goodness, reproduce, sweep, bench): --threads N, else the
  environment variable SONARGRID_THREADS, else the CPUs the process may use (its affinity mask);
  results are the same for any N

See docs/cli.md for the full contract.
)";

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> raw(argv + 1, argv + argc);
  if (raw.empty()) {
    std::cerr << "sonargrid-cli: no command given (try sonargrid-cli help)\n";
    return 2;
  }
  const std::string command = raw.front();
  sg::cli::Arguments args(std::vector<std::string>(raw.begin() + 1, raw.end()));
  try {
    if (command == "help" || command == "--help" || command == "-h") {
      std::cout << kUsage;
      return 0;
    }
    if (command == "models") return sg::cli::runModels(args);
    if (command == "map") return sg::cli::runMap(args);
    if (command == "score") return sg::cli::runScore(args);
    if (command == "compare") return sg::cli::runCompare(args);
    if (command == "goodness") return sg::cli::runGoodness(args);
    if (command == "simulate") return sg::cli::runSimulate(args);
    if (command == "reproduce") return sg::cli::runReproduce(args);
    if (command == "convert") return sg::cli::runConvert(args);
    if (command == "robot") return sg::cli::runRobot(args);
    if (command == "record") return sg::cli::runRecord(args);
    if (command == "sweep") return sg::cli::runSweepCommand(args);
    if (command == "sweep-merge") return sg::cli::runSweepMerge(args);
    if (command == "optimize") return sg::cli::runOptimize(args);
    if (command == "goodness-study") return sg::cli::runGoodnessStudy(args);
    if (command == "bench") return sg::cli::runBench(args);
    throw sg::cli::UsageError("unknown command '" + command + "' (try sonargrid-cli help)");
  } catch (const sg::cli::UsageError& e) {
    std::cerr << "sonargrid-cli: " << e.what() << '\n';
    return 2;
  } catch (const sg::cli::InputError& e) {
    std::cerr << "sonargrid-cli: " << e.what() << '\n';
    return 2;
  } catch (const sg::GridLimitError& e) {
    // A log whose grid cannot be made (a pose at 1e12 m, a cell far too small): input to fix.
    std::cerr << "sonargrid-cli: " << e.what() << '\n';
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "sonargrid-cli: " << e.what() << '\n';
    return 1;
  }
}
