#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The paths a CPU without AVX2 takes, chosen at run time: the "default" clones of the rule kernels
# (core/sonargrid/rules/run_kernels.cpp) and of the batch evaluation
# (core/sonargrid/sweep/batch_evaluation.cpp), and the cone rows in four lanes rather than eight
# (core/sonargrid/models/cone_model.h). On a CPU with AVX2 nothing runs them, so the suites that
# pin their bits (the footprint path's for the runs, the per-set engine's for the batches) run
# again here on an emulated Nehalem (QEMU user mode: SSE4.2, no AVX). Uses the build of
# .ci/test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/deps.sh
cmake --build build -j "$(nproc)" --target tst_fused_runs tst_batch_evaluation
for suite in build/tests/core/tst_fused_runs build/tests/core/tst_batch_evaluation; do
  echo "== $(basename "$suite") on an emulated Nehalem"
  qemu-x86_64 -cpu Nehalem "$suite"
done
