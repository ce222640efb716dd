#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Installs what is missing, then configures and builds SonarGrid into build/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/deps.sh
source .ci/ccache.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "${ccache_flags[@]}"
cmake --build build -j "$(nproc)"
