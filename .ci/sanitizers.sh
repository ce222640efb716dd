#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Builds the core, the CLI and their tests with AddressSanitizer + UndefinedBehaviorSanitizer into
# build-asan/ and runs the core, CLI and live-robot test suites under them (see below for the two
# long CLI suites). Any report fails the job.
set -euo pipefail
cd "$(dirname "$0")/.."
flags="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined"
# -g1: line tables only, which the reports' stack traces need, for less compile time than -g's
# full debug information (a large test file: 11–13 s against 14–15 s). -O1, as AddressSanitizer's
# own documentation suggests: on a clean clone (2026-11-29, two processors) the job took 691 s
# against 902 s at -O2, its compilers' CPU 1049 against 1442 s, and its ctest run 200 against 214 s.
source .ci/ccache.sh
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "${ccache_flags[@]}" -DSONARGRID_BUILD_PYTHON=OFF -DSONARGRID_BUILD_BENCHMARKS=OFF \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
  -DSONARGRID_BUILD_GUI=OFF \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined"
cmake --build build-asan -j "$(nproc)"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
# tst_cli_threads (about 100 CLI runs) and tst_cli_bench (timings) take many minutes under ASan
# and cover no code the other suites do not: tst_cli_threads runs here with the same subset as in
# .ci/tsan.sh, tst_cli_bench only in the uninstrumented build (.ci/test.sh).
ctest --test-dir build-asan -L "core|cli|live" -E '^(tst_cli_threads|tst_cli_bench)$' \
  --output-on-failure -j "$(nproc)"
build-asan/tests/cli/tst_cli_threads "sameMapAnyThreadCount:hpf × bayes" \
  "sameMapAnyThreadCount:hpf × addition" "sameMapAnyThreadCount:himm × himm" \
  sameResultsOtherCommands badValues
