#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Builds the core, the CLI and their tests with ThreadSanitizer into build-tsan/ and runs the core
# and CLI suites under it with SONARGRID_THREADS=4: every parallel path (the mapper's bands and
# pipeline, snapshots, the cone tables, the sweep) then runs on four threads, whatever the runner's
# CPU count (tests that set their own count, tst_concurrency and tst_mapper's 1/2/3/8-thread rows,
# still do). Any report fails the job.
set -euo pipefail
cd "$(dirname "$0")/.."
flags="-fsanitize=thread -fno-omit-frame-pointer"
# -g1: line tables only, which the reports' stack traces need, for less compile time than -g's
# full debug information (a large test file: 11–13 s against 14–15 s).
source .ci/ccache.sh
cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "${ccache_flags[@]}" -DSONARGRID_BUILD_PYTHON=OFF -DSONARGRID_BUILD_BENCHMARKS=OFF \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" \
  -DSONARGRID_BUILD_GUI=OFF -DSONARGRID_TEST_TIMEOUT=900 \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=thread"
cmake --build build-tsan -j "$(nproc)"
export SONARGRID_THREADS=4
# tsan.supp: reports from inside Qt and GDAL, which are not built with ThreadSanitizer.
export TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1 suppressions=$PWD/.ci/tsan.supp"
# Not here, as they run only code that other suites run here on its threads (they run whole in the
# uninstrumented build, .ci/test.sh); without them, and with tst_fused_runs' subset below, the
# job's tests took 530 s instead of 1290 s on two processors (2026-11-29):
# tst_cli_bench (the bench command's timings: 8 minutes under TSan, excluded from ASan for the
# same reason), tst_reproduce and tst_cli_goodness_study (whose sweeps tst_sweep,
# tst_batch_evaluation, tst_rank_correlation and tst_cli_sweep run here), and tst_fused_runs,
# which runs below with a subset of its longest function's rows; and tst_bag_log (177 s under
# TSan on 2026-12-02, then with 140 maps of the room log, now 70: mapping whose threads tst_mapper
# checks here; its bag readers run on one thread, as tst_rosbag1, tst_rosbag2 and tst_ros_messages
# do here); and tst_precision, which runs below with a subset of its contract's rows.
ctest --test-dir build-tsan -L "core|cli" \
  -E '^(tst_cli_threads|tst_cli_bench|tst_reproduce|tst_cli_goodness_study|tst_fused_runs|tst_bag_log|tst_precision)$' \
  --output-on-failure -j "$(nproc)"
# tst_fused_runs: every function whole but runsGiveTheFootprintPathsBits (60 rows, each mapping the
# workload at 1, 2 and 3 threads in three lane widths: 145 s of its 205 s under TSan), of which one
# row runs per rule kernel, plus addition's arc applied at once, a no-echo row and a prior of 0.3.
fused=build-tsan/tests/core/tst_fused_runs
long=runsGiveTheFootprintPathsBits
rows=("hpf/addition" "hpf/bayes" "hpf/bayes-recursive" "hpf/log" "hpf/logodds" "hpf/dempster-shafer"
  "konolige/addition normalise=0" "murphy/bayes no_echo=1" "parameterized/logodds prior=0.3")
mapfile -t functions < <("$fused" -functions | sed 's/()$//' | grep -vx "$long")
# (a failure inside < <(…) escapes set -e: an empty list would run the named rows alone)
((${#functions[@]} > 0)) || { echo "$fused -functions listed nothing" >&2; exit 1; }
"$fused" "${functions[@]}" "${rows[@]/#/$long:}"
# tst_precision: every function whole but two. Its contract runs on the three short logs (every
# pair mapped exact and fast on each: the office and arafat-room rows take 16 of the function's 19
# s uninstrumented, and it passed Qt Test's five-minute limit for one function under TSan on
# 2026-12-03); its fast engine's threads, on the office log, for one rule of the two (each row
# maps the log fourteen times: about 120 s under TSan), bayes-recursive, whose cells the run
# kernels update in the same code as bayes's.
precision=build-tsan/tests/core/tst_precision
mapfile -t functions < <("$precision" -functions | sed 's/()$//' |
  grep -vxE 'everyPairKeepsTheContract|fastMapIsTheSameAtAnyThreadCountAndIncrementally')
((${#functions[@]} > 0)) || { echo "$precision -functions listed nothing" >&2; exit 1; }
"$precision" "${functions[@]}" everyPairKeepsTheContract:room \
  everyPairKeepsTheContract:raschke-single everyPairKeepsTheContract:raschke-multi \
  fastMapIsTheSameAtAnyThreadCountAndIncrementally:bayes-recursive
# tst_cli_threads runs the CLI 100 times (every pair at three thread counts), over five minutes
# under TSan. Here: one pair for each way of mapping (bands, bands in two passes for totals, the
# pipeline), then its other cases whole. The full suite runs in the uninstrumented build (.ci/test.sh).
build-tsan/tests/cli/tst_cli_threads "sameMapAnyThreadCount:hpf × bayes" \
  "sameMapAnyThreadCount:hpf × addition" "sameMapAnyThreadCount:himm × himm" \
  sameResultsOtherCommands badValues
