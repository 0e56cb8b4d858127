#!/usr/bin/env bash
# The README's first command: set-up (scripts/setup.sh), then the project's main job on the
# bundled data. Results go to out/ (override with SYSID_OUT).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh build
SYSID=build/apps/sysid
OUT="${SYSID_OUT:-out}"
mkdir -p "$OUT"
echo "== sysid info: the EMPS estimation recording (real measured data) =="
"$SYSID" info datasets/emps/emps_estimation.csv
