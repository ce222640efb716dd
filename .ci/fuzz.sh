#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Fuzz smoke test: builds every libFuzzer target of tests/fuzz with clang (ASan + UBSan) into
# build-fuzz/ and runs each over its seed corpus for FUZZ_SECONDS (default 30). A crash, a
# sanitizer report or a leak fails the job; the input that caused it is kept in build-fuzz/findings.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${FUZZ_SECONDS:-30}"
source .ci/ccache.sh
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "${ccache_flags[@]}" -DSONARGRID_BUILD_PYTHON=OFF -DCMAKE_CXX_COMPILER=clang++ \
  -DSONARGRID_BUILD_FUZZERS=ON -DSONARGRID_BUILD_TESTS=OFF -DSONARGRID_BUILD_BENCHMARKS=OFF -DSONARGRID_BUILD_GUI=OFF
cmake --build build-fuzz -j "$(nproc)" --target fuzzers
mkdir -p build-fuzz/findings
for target in build-fuzz/tests/fuzz/fuzz_*; do
  name="$(basename "$target")"
  seeds="tests/fuzz/corpus/${name#fuzz_}"
  # New inputs go to a scratch corpus, so the committed seeds stay as they are.
  work="build-fuzz/corpus/${name#fuzz_}"
  mkdir -p "$work"
  echo "== $name: ${seconds} s over $seeds"
  log="build-fuzz/${name}.log"
  status=0
  "$target" -max_total_time="$seconds" -max_len=65536 -timeout=10 -rss_limit_mb=2048 \
    -artifact_prefix="build-fuzz/findings/${name}-" -print_final_stats=1 "$work" "$seeds" \
    >"$log" 2>&1 || status=$?
  grep -E "^(#[0-9]+ +DONE|stat::number_of_executed_units)" "$log" || true
  if [ "$status" -ne 0 ]; then
    tail -n 60 "$log" >&2
    echo "$name failed (status $status); the input is in build-fuzz/findings/" >&2
    exit 1
  fi
done
