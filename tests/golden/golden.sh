#!/usr/bin/env bash
# Behaviour fixed before the house's redesign (issue #37): the --json outputs and the model
# files of the commands a user runs on the bundled data, compared value by value with the files
# in tests/golden/expected/ (golden_compare.py says what "the same" means). New keys are
# allowed; a key or value that changes fails, naming the file and the key's path.
#   tests/golden/golden.sh SYSID SOURCE_DIR            compare
#   tests/golden/golden.sh SYSID SOURCE_DIR --update   rewrite expected/ (a behaviour change
#                                                      the commit message explains)
set -euo pipefail
SYSID="$(realpath "$1")"
SRC="$(realpath "$2")"
MODE="${3:-}"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
cd "$WORK"
# Relative paths, so the file names the outputs record do not depend on where the test runs.
ln -s "$SRC/datasets" datasets
OUT=out
mkdir "$OUT"
run() {  # run NAME ARGS...: stdout (--json) to out/NAME.json
  local name=$1
  shift
  if ! "$SYSID" "$@" --json > "$OUT/$name.json" 2> "$WORK/$name.err"; then
    echo "golden: '$name' failed: sysid $*" >&2
    cat "$WORK/$name.err" >&2
    exit 1
  fi
}
V=datasets/virtual
P=datasets/piezo_aye_ang/piezo.csv
"$SYSID" derive $V/training.csv --method butterworth --cutoff 50 --decimate 4 -o train_va.csv > /dev/null 2>&1
"$SYSID" derive $V/test.csv --method butterworth --cutoff 50 -o test_va.csv > /dev/null 2>&1
run identify_pulse identify --a3 6 $V/pulses.csv -o "$OUT/model_pulse.json"
run identify_trajectory identify --method trajectory train_va.csv -o "$OUT/model_trajectory.json"
run tune_delay tune-delay --model "$OUT/model_pulse.json" $V/pulses.csv -o "$OUT/model.json"
run dominance dominance --model "$OUT/model.json" train_va.csv test_va.csv
run train train --train train_va.csv --test test_va.csv --inputs v,a --output u --hidden 8 \
  --max-epochs 20 --seed 1 --threads 1 -o "$OUT/nn.json"
run compare compare --model "$OUT/model.json" --nn "$OUT/nn.json" test_va.csv
run track track --ff none,analytic,nn --model "$OUT/model.json" --nn "$OUT/nn.json" --freq 0.5
run irreducible irreducible test_va.csv --inputs v --inputs v,a
run loop loop $V/loop_triangle.csv
run margins margins --model "$OUT/model.json"
run hysteresis_fit_pi hysteresis fit --model pi $P -o "$OUT/hysteresis_pi.json"
run hysteresis_fit_bouc_wen hysteresis fit --model bouc-wen-piezo $P -o "$OUT/hysteresis_bouc_wen.json"
run hysteresis_dominance hysteresis dominance $P

EXPECTED="$SRC/tests/golden/expected"
if [ "$MODE" = "--update" ]; then
  rm -rf "$EXPECTED"
  mkdir -p "$EXPECTED"
  cp "$OUT"/*.json "$EXPECTED/"
  echo "golden: wrote $(ls "$EXPECTED" | wc -l) files to $EXPECTED"
  exit 0
fi
python3 "$SRC/tests/golden/golden_compare.py" "$EXPECTED" "$OUT"
# The comparison can fail: a1p moved by one part in 1e7 must be reported.
python3 - "$OUT/model.json" <<'PY'
import json, sys
path = sys.argv[1]
model = json.load(open(path))
model["a1p"] *= 1 + 1e-7
json.dump(model, open(path, "w"))
PY
if python3 "$SRC/tests/golden/golden_compare.py" "$EXPECTED" "$OUT" > "$WORK/planted.txt"; then
  echo "golden: a planted change of a1p was not reported" >&2
  exit 1
fi
grep -q "model.json.a1p" "$WORK/planted.txt"
