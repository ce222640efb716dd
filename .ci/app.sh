#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Quick start, first command: installs what is missing, builds, maps the bundled room log with the
# CLI, and opens the desktop app on a bundled log of paper 000's test room (raschke-multi, run 1 in
# motion, with the room's reference walls), already mapped. Without a display it saves a screenshot
# of the app instead (offscreen platform).
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/build.sh
mkdir -p build/out
build/app/cli/sonargrid-cli map --log datasets/room/room.sglog --pose truth \
  --model himm --rule himm --cell 0.05 --png build/out/room-himm.png --legend --scale 4
app=(build/app/gui/sonargrid datasets/raschke-multi/in-motion-01.sglog
  --reference datasets/raschke-multi/world.json --pose truth --model parameterized --rule bayes)
if [ -n "${DISPLAY:-}" ] || [ -n "${WAYLAND_DISPLAY:-}" ]; then
  exec "${app[@]}"
fi
QT_QPA_PLATFORM=offscreen "${app[@]}" --screenshot build/out/sonargrid-window.png
echo "No display: the app's window is in build/out/sonargrid-window.png, the map in build/out/room-himm.png."
