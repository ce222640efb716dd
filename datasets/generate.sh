#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Regenerates the simulated datasets (datasets/README.md) with sonargrid-cli simulate and fixed
# seeds. Every log depends only on these commands, the world and route files and the program:
# tst_cli_simulate regenerates raschke-single and compares bytes.
#
#   datasets/generate.sh [CLI [OUT_DIR [DATASET...]]]
#
# CLI defaults to build/app/cli/sonargrid-cli, OUT_DIR to this folder (the bundled files), DATASET
# to all of raschke-multi raschke-single arafat-room office. World and route files are read from
# this folder whatever OUT_DIR is. PHYSICS (environment) picks the simulator's physics preset,
# `default` unless set (docs/simulator.md, "Presets"): the bundled logs are the default's;
# PHYSICS=harsh rewrites the logs bundled before issue 16, byte for byte.
set -eu

here=$(cd "$(dirname "$0")" && pwd)
cli=${1:-build/app/cli/sonargrid-cli}
out=${2:-$here}
[ $# -ge 2 ] && shift 2 || shift $#
datasets=${*:-raschke-multi raschke-single arafat-room office}
physics=${PHYSICS:-default}

sim() {
  name=$1
  shift
  mkdir -p "$out/$name"
  "$cli" simulate --world "$here/$name/world.json" --physics "$physics" "$@" >/dev/null
}

# Paper 000 §4: ten in-motion (HIMM) runs and ten 4-stop (HPF) runs per course, K2A, 24 sonars.
# The robot starts at S (world.json) each time; the runs differ by seed: range noise, misreadings
# (when the preset has them) and odometry drift.
raschke() {
  name=$1
  for run in 01 02 03 04 05 06 07 08 09 10; do
    seed=${run#0}
    sim "$name" --robot k2a --route in-motion --route-file "$here/$name/route.txt" \
      --seed "$seed" --drift on --out "$out/$name/in-motion-$run.sglog"
    sim "$name" --robot k2a --route stop-and-scan --route-file "$here/$name/route.txt" \
      --stops 4 --seed "$seed" --drift on --out "$out/$name/stop-and-scan-$run.sglog"
  done
}

for d in $datasets; do
  case $d in
    raschke-multi | raschke-single) raschke "$d" ;;
    arafat-room)
      # Paper 002 §4-5: an AmigoBot sweeping the room in U-turns, the same route twice.
      for run in 1 2; do
        sim arafat-room --robot amigobot --route u-turn --route-file "$here/arafat-room/route.txt" \
          --duration 240 --seed "$run" --drift on --out "$out/arafat-room/run-$run.sglog"
      done
      ;;
    office)
      # The performance workload: a Pioneer 3-DX, 700 s out and back, > 100 000 readings.
      sim office --robot p3dx --route in-motion --route-file "$here/office/route.txt" \
        --duration 700 --seed 1 --drift on --out "$out/office/office.sglog"
      ;;
    *)
      echo "generate.sh: unknown dataset '$d'" >&2
      exit 2
      ;;
  esac
done
