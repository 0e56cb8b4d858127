#!/usr/bin/env bash
# The README's second command: set-up (scripts/setup.sh), then the whole test suite (CTest over
# Catch2). Extra arguments go to cmake, e.g. -DSYSID_SANITIZE=ON.
#   scripts/test.sh [BUILD_DIR] [cmake args...]
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR="${1:-build}"
scripts/setup.sh "$@"
ctest --test-dir "$BUILD_DIR" --output-on-failure -j "${SYSID_JOBS:-$(nproc)}"
