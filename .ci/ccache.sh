# SPDX-License-Identifier: GPL-3.0-or-later
# Sourced by the build scripts: compile through ccache (Debian's), with paths taken relative to
# the checkout, so that a fresh clone in another folder (as CI makes one) reuses what an earlier
# build of the same sources compiled. The cache lives in ccache's default folder (~/.cache/ccache).
export CCACHE_BASEDIR="$PWD"
export CCACHE_NOHASHDIR=true
ccache_flags=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
