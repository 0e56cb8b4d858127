#!/usr/bin/env bash
# The README's second command: set-up (scripts/setup.sh), then the whole test suite (CTest over
# Catch2). Extra arguments go to cmake, e.g. -DSYSID_WERROR=ON. The set-up also installs the
# packages only tests use (setup.sh --test-tools: the Cortex-M cross toolchain and QEMU).
#   scripts/test.sh [--sanitize] [BUILD_DIR] [cmake args...]
# --sanitize is CI's second pass (docs/testing.md, "CI budget"): a clang build under
# AddressSanitizer + UndefinedBehaviorSanitizer with libFuzzer's coverage hooks (so that
# scripts/fuzz.sh runs from the same build), and the suite less the long numerical runs that
# the sanitizers add nothing to; it installs nothing.
set -euo pipefail
cd "$(dirname "$0")/.."
sanitize=0
if [ "${1:-}" = --sanitize ]; then
  sanitize=1
  shift
fi
BUILD_DIR="${1:-build}"
shift || true
exclude=()
if ((sanitize)); then
  # clang and the sanitizer runtimes come with setup.sh's package list.
  export CC=clang CXX=clang++
  # Line tables are all a sanitizer report needs for FILE:LINE, at a fraction of -g's cost.
  # With debug information ccache would also key on the build folder's absolute path; without
  # it another clone reuses these objects too (their line tables name files relative to it).
  export CCACHE_NOHASHDIR=1
  set -- -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -gline-tables-only -DNDEBUG" \
    -DSYSID_SANITIZE=ON -DSYSID_FUZZ=ON -DSYSID_BUILD_BENCH=OFF \
    "-DCMAKE_CXX_FLAGS=-fsanitize=fuzzer-no-link" "$@"
  # Labels: the Monte-Carlo check, the docs' and tutorial's command runs, the paper's facts
  # (long simulations and trainings through code the module tests already run under ASan) and
  # the few single tests labelled long (tests/CMakeLists.txt says which and why).
  exclude=(-LE '^(slow|docs|tutorial|paper|long)$')
fi
scripts/setup.sh --test-tools "$BUILD_DIR" "$@"
ctest --test-dir "$BUILD_DIR" --output-on-failure -j "${SYSID_JOBS:-$(nproc)}" ${exclude[@]+"${exclude[@]}"}
