#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The core's folders include downward only (docs/architecture.md): the sensor models and the
# update rules both build on the interfaces in engine/ and the lanes in simd/, neither names the
# other's folder, and those two name neither.
set -euo pipefail
cd "$(dirname "$0")/.."
bad=0
check() {  # folder, forbidden folder
  [[ -d "core/sonargrid/$1" ]] || { echo "no folder core/sonargrid/$1" >&2; exit 1; }
  local hits status=0
  # Any spelling of an include of the folder: "sonargrid/X/…", <sonargrid/X/…>, "../X/…".
  hits=$(git grep --untracked -nE "^[[:space:]]*#[[:space:]]*include[[:space:]]*[<\"](\.\./|sonargrid/)$2/" \
    -- "core/sonargrid/$1/") || status=$?
  if ((status > 1)); then exit "$status"; fi  # 1: no match; anything else: git failed
  if [[ -n "$hits" ]]; then
    echo "core/sonargrid/$1 includes $2/:" >&2
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
# Test hooks (testing/) are implemented by the registries' .cpp files; no header of the library
# names them, so nothing built on the library sees them.
status=0
hits=$(git grep --untracked -nE "^[[:space:]]*#[[:space:]]*include[[:space:]]*[<\"](\.\./|sonargrid/)testing/" \
  -- 'core/sonargrid/*.h' ':!core/sonargrid/testing/') || status=$?
if ((status > 1)); then exit "$status"; fi
if [[ -n "$hits" ]]; then
  echo "library headers include testing/:" >&2
  echo "$hits" >&2
  bad=1
fi
# Every file of the core lives in a folder of one concern (docs/architecture.md).
loose=$(git ls-files --cached --others --exclude-standard -- 'core/sonargrid/*' | grep -E '^core/sonargrid/[^/]+$' || true)
if [[ -n "$loose" ]]; then
  echo "files at the root of core/sonargrid/ (put each in its folder):" >&2
  echo "$loose" >&2
  bad=1
fi
if ((bad)); then exit 1; fi
echo "Layers: models/ and rules/ include neither each other; engine/ and simd/ include neither;"
echo "no library header includes testing/; no file at the root of core/sonargrid/"
