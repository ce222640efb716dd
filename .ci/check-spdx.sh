#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Every tracked source, header, CMake and shell file names its licence in an SPDX line near its
# top (LICENSE says which part of the tree is under which licence).
set -euo pipefail
cd "$(dirname "$0")/.."
missing=0
while IFS= read -r f; do
  case "$f" in
    tests/fuzz/corpus/*) continue ;;
  esac
  if ! head -n 3 "$f" | grep -q "SPDX-License-Identifier: \(BSD-3-Clause\|GPL-3.0-or-later\)"; then
    echo "no SPDX line: $f" >&2
    missing=$((missing + 1))
  fi
done < <(git ls-files '*.cpp' '*.h' '*.cmake' '*.sh' 'CMakeLists.txt' '*/CMakeLists.txt' .ci/run)
if ((missing > 0)); then
  echo "$missing file(s) lack an SPDX-License-Identifier line" >&2
  exit 1
fi
echo "SPDX: every source file names its licence"
