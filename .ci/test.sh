#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Quick start, second command: installs what is missing, builds, and runs every test: the offscreen
# suites first, then the OpenGL suites (ctest label gl) on a virtual X server.
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/build.sh
ctest --test-dir build --output-on-failure -j "$(nproc)" -LE gl
xvfb-run -a -s "-screen 0 1280x1024x24" ctest --test-dir build --output-on-failure -L gl
