#!/usr/bin/env bash
# The README's first command: set-up (scripts/setup.sh), then the project's main job on the
# bundled data: the whole pipeline on the virtual stage's recordings (identify -> delay ->
# dominance -> NN sweep -> compare -> PI tracking -> report), plus the paper's pulse table and
# a look at the real EMPS recording; it ends with the paper's measured facts checked on the bundled
# stage (sysid stage facts: paper vs stage, tolerance, met). Results go to out/ (override with
# SYSID_OUT).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh build
SYSID=build/apps/sysid
OUT="${SYSID_OUT:-out}"
mkdir -p "$OUT"
echo "== the paper's pulse table -> a1p, a1n, a2p, a2n (a3 = 6) =="
"$SYSID" identify --table datasets/paper/pulse_table.csv --a3 6
echo
echo "== real measured data: the EMPS estimation recording =="
"$SYSID" info datasets/emps/emps_estimation.csv
echo
echo "== the pipeline on the bundled virtual-stage recordings (datasets/virtual) =="
"$SYSID" --progress pipeline datasets/virtual -o "$OUT/pipeline"
echo
echo "== the paper's facts on the bundled stage: paper vs stage (sysid stage facts) =="
"$SYSID" --progress stage facts --stage datasets/virtual/stage.json | tee "$OUT/facts.txt"
