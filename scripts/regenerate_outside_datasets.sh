#!/usr/bin/env bash
# Regenerates the CSV recordings of the two outside data sets from their bundled originals, byte
# for byte, with `sysid import` (tests/io checks that a fresh import equals the committed files):
#
#   scripts/regenerate_outside_datasets.sh [BUILD_DIR]     (default BUILD_DIR: build)
#
#   datasets/boucwen/train.csv            t,u,x from train.h5 /multisine/u, /multisine/y (750 Hz)
#   datasets/boucwen/test_multisine.csv   t,u,x from uval_multisine.mat, yval_multisine.mat
#   datasets/piezo_aye_ang/piezo.csv      t,u,x from Model_Vi_Do.dat columns 1 [V] and 5 [um]
#
# Paths are relative to the repository root, as recorded in each file's `source.*` metadata.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${1:-build}
SYSID="$BUILD_DIR/apps/sysid"
if [ ! -x "$SYSID" ]; then
  echo "regenerate_outside_datasets: $SYSID not found; build first (scripts/setup.sh $BUILD_DIR)" >&2
  exit 1
fi
B=datasets/boucwen
P=datasets/piezo_aye_ang
"$SYSID" import --column u=$B/train.h5:/multisine/u --column x=$B/train.h5:/multisine/y \
  --rate 750 --unit u=N -o $B/train.csv
"$SYSID" import --column u=$B/uval_multisine.mat:uval_multisine \
  --column x=$B/yval_multisine.mat:yval_multisine --rate 750 --unit u=N -o $B/test_multisine.csv
"$SYSID" import --column u=$P/Model_Vi_Do.dat:1 --column x=$P/Model_Vi_Do.dat:5 \
  --scale x=1e-6 --rate 200 -o $P/piezo.csv
