#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# A fuzzing campaign (tests/fuzz/README.md, "Campaigns"): runs TARGET (a name such as `carmen`, or
# `all`) for SECONDS each with libFuzzer's -fork on the cores the thread policy grants
# (SONARGRID_THREADS, else the CPUs this process may use), merges the new inputs that add coverage
# into the committed corpus (tests/fuzz/corpus/<name>/, with -merge=1), and prints executions, coverage and
# findings per target. Findings (crash-, leak-, timeout- and oom- inputs) are kept in
# build-fuzz/findings/; the script exits 1 when there is one.
#
#   tests/fuzz/campaign.sh all 600
#   tests/fuzz/campaign.sh ros1_bag 3600
set -euo pipefail
cd "$(dirname "$0")/../.."
if (($# != 2)) || ! [[ "$2" =~ ^[0-9]+$ ]]; then
  echo "usage: tests/fuzz/campaign.sh TARGET|all SECONDS" >&2
  exit 2
fi
which="$1"
seconds="$2"
jobs="${SONARGRID_THREADS:-$(nproc)}"
if ! [[ "$jobs" =~ ^[0-9]+$ ]] || ((jobs < 1)); then
  echo "SONARGRID_THREADS must be a whole number >= 1, got '$jobs'" >&2
  exit 2
fi

source .ci/ccache.sh
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "${ccache_flags[@]}" \
  -DSONARGRID_BUILD_PYTHON=OFF -DCMAKE_CXX_COMPILER=clang++ -DSONARGRID_BUILD_FUZZERS=ON \
  -DSONARGRID_BUILD_TESTS=OFF -DSONARGRID_BUILD_BENCHMARKS=OFF -DSONARGRID_BUILD_GUI=OFF >/dev/null
cmake --build build-fuzz -j "$jobs" --target fuzzers >/dev/null

if [ "$which" = all ]; then
  targets=(build-fuzz/tests/fuzz/fuzz_*)
else
  targets=("build-fuzz/tests/fuzz/fuzz_$which")
  [ -x "${targets[0]}" ] || { echo "no fuzz target '$which' (see tests/fuzz/README.md)" >&2; exit 2; }
fi

mkdir -p build-fuzz/findings build-fuzz/campaign
printf '%-22s %14s %8s %8s %8s %s\n' target executions cov ft corpus findings
found=0
for target in "${targets[@]}"; do
  name="$(basename "$target")"
  short="${name#fuzz_}"
  seeds="tests/fuzz/corpus/$short"
  work="build-fuzz/campaign/$short"
  log="build-fuzz/campaign/$short.log"
  rm -rf "$work" && mkdir -p "$work"
  before=$(ls build-fuzz/findings | grep -c "^$name-" || true)
  # -fork runs `jobs` workers; new inputs land in $work, the seeds stay as they are until the merge.
  "$target" -fork="$jobs" -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 \
    -max_total_time="$seconds" -max_len=65536 -timeout=10 -rss_limit_mb=2048 \
    -artifact_prefix="build-fuzz/findings/$name-" "$work" "$seeds" >"$log" 2>&1 || true
  # The last progress line of the fork mode: "#EXECS: cov: C ft: F corp: N exec/s ...".
  last=$(grep -E "^#[0-9]+: cov:" "$log" | tail -n 1 || true)
  execs=$(sed -E 's/^#([0-9]+):.*/\1/' <<<"$last")
  cov=$(sed -E 's/.* cov: ([0-9]+).*/\1/' <<<"$last")
  ft=$(sed -E 's/.* ft: ([0-9]+).*/\1/' <<<"$last")
  # Into the committed corpus go the fewest new inputs that add coverage to it (-merge=1 keeps
  # the seeds, the hand-written and the loggers' files, as they are).
  "$target" -merge=1 -max_len=65536 -timeout=10 -rss_limit_mb=2048 "$seeds" "$work" >>"$log" 2>&1
  after=$(ls build-fuzz/findings | grep -c "^$name-" || true)
  new=$((after - before))
  found=$((found + new))
  printf '%-22s %14s %8s %8s %8s %s\n' "$name" "${execs:-?}" "${cov:-?}" "${ft:-?}" \
    "$(ls "$seeds" | wc -l)" "$new"
done
echo "$(date -u +%Y-%m-%d) tests/fuzz/campaign.sh $which $seconds, $jobs workers; logs in build-fuzz/campaign/"
if ((found > 0)); then
  echo "findings in build-fuzz/findings/: reproduce with build-fuzz/tests/fuzz/fuzz_NAME FILE" >&2
  exit 1
fi
