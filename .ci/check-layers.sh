#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The core's folders include downward only: the sensor models and the update rules both build on
# the interfaces in engine/ and the lanes in simd/, neither names the other's folder, and those
# two name neither.
set -euo pipefail
cd "$(dirname "$0")/.."
bad=0
check() {  # folder, forbidden include prefix
  local hits
  hits=$(git grep -n "#include \"sonargrid/$2/" -- "core/sonargrid/$1/" || true)
  if [[ -n "$hits" ]]; then
    echo "core/sonargrid/$1 includes sonargrid/$2/:" >&2
    echo "$hits" >&2
    bad=1
  fi
}
check rules models
check models rules
check engine models
check engine rules
check simd models
check simd rules
if ((bad)); then exit 1; fi
echo "Layers: rules/ and models/ include neither each other nor upward"
