#!/usr/bin/env bash
# Quick start, first command: installs what is missing, builds, and maps the bundled room log.
# (The desktop app arrives with issue 5; until then the CLI builds the map and writes a PNG.)
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/build.sh
mkdir -p build/out
build/app/cli/sonargrid-cli map --log datasets/room/room.sglog --pose truth \
  --model himm --rule himm --cell 0.05 --png build/out/room-himm.png --legend --scale 4
echo "Open build/out/room-himm.png to see the map."
