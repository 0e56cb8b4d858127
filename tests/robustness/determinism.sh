#!/bin/sh
# Same inputs and seed -> byte-identical output files, whatever the thread count (issue #14):
# model files carry no wall time, the pipeline report keeps timing on stderr.
# Usage: determinism.sh SYSID SOURCE_DIR
set -u
. "$(dirname "$0")/common.sh"
run() { "$sysid" "$@" >/dev/null 2>err.txt || { cat err.txt >&2; fail "$* exited $?"; }; }
v="$src/datasets/virtual"
for k in 1 2; do
  threads=$k  # 1 then 2 threads: results must not depend on it
  run train --train "$v/test.csv" --inputs v,a --hidden 3 --max-epochs 5 --seed 7 \
      --threads "$threads" -o "train$k.json"
  run sweep --train "$v/test.csv" --inputs v --hidden 2,3 --max-epochs 4 --seed 7 \
      --threads "$threads" -o "sweep$k.json"
  run generate pulses --seed 3 -o "gen$k"
  run pipeline "$v" -o "report$k" --hidden 3 --max-epochs 3 --no-typical --no-track \
      --threads "$threads"
done
cmp train1.json train2.json || fail "train model files differ"
cmp sweep1.json sweep2.json || fail "sweep model files differ"
grep -q wall_time train1.json sweep1.json && fail "wall time inside a model file"
diff -r gen1 gen2 >/dev/null || fail "generate outputs differ"
# The marker names each run (cli/output_folder.hpp): all else must be identical.
diff -r -x .sysid-output report1 report2 || fail "pipeline report folders differ"
echo "ok: byte-identical outputs"
