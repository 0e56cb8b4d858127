#!/usr/bin/env bash
# Regenerates datasets/virtual/ (the virtual stage's recordings) byte for byte:
#
#   scripts/regenerate_datasets.sh [BUILD_DIR]     (default BUILD_DIR: build)
#
# The files are deterministic: seed 1, the built-in calibrated stage (written beside them as
# stage.json). tests/stage checks that a regeneration matches the committed files.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${1:-build}
SYSID="$BUILD_DIR/apps/sysid"
if [ ! -x "$SYSID" ]; then
  echo "regenerate_datasets: $SYSID not found; build first (scripts/setup.sh $BUILD_DIR)" >&2
  exit 1
fi
"$SYSID" generate all --seed 1 -o datasets/virtual
