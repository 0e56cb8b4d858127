#!/usr/bin/env bash
# The hysteresis models scored on outside data (docs/hysteresis.md), one table per data set:
#  1. Real piezo (datasets/piezo_aye_ang/piezo.csv, Aye & Ang): every model is fitted on the
#     first 40 % of the recording and scored on the rest. Forward: simulate the whole
#     recording from u alone (the state runs through the training part), e_RMS [m] and NRMSE
#     (RMS / std of x) over the rest. Inverse: invert the model on the measured x of the whole
#     recording, e_RMS [V] and NRMSE of u over the rest.
#  2. Bouc–Wen benchmark (datasets/boucwen): experiments/boucwen_benchmark.sh when present.
#
#   experiments/hysteresis_benchmark.sh [OUT_DIR] [BUILD_DIR]     (default: out/hysteresis, build)
# PIEZO_CSV overrides the piezo recording (columns t, u, x).
set -euo pipefail
cd "$(dirname "$0")/.."
OUT="${1:-out/hysteresis}"
BUILD="${2:-build}"
SYSID="$BUILD/apps/sysid"
PIEZO="${PIEZO_CSV:-datasets/piezo_aye_ang/piezo.csv}"
SCORE="python3 experiments/hysteresis_score.py"
FRACTION=0.4
if [ ! -x "$SYSID" ]; then
  echo "hysteresis_benchmark: $SYSID not found; run scripts/setup.sh first" >&2
  exit 1
fi
if [ ! -f "$PIEZO" ]; then
  echo "hysteresis_benchmark: $PIEZO not found (datasets/piezo_aye_ang, see its README)" >&2
  exit 1
fi
mkdir -p "$OUT"
$SCORE split "$PIEZO" "$FRACTION" "$OUT/piezo_train.csv" "$OUT/piezo_reference.csv"

# name | kind | flags
MODELS=(
  "PI, 20 operators + offset|pi|--operators 20"
  "asymmetric PI (cubic input function), 20 operators + offset|gpi|--operators 20 --degree 3"
  "rate-dependent PI, 20 operators + offset|rdpi|--operators 20"
  "dominant-variable network (static, H = 10)|nn-operators|--operators 0 --hidden 10"
  "operator-input network (4 play operators, H = 10)|nn-operators|--operators 4 --hidden 10"
)

echo "## Real piezo (Aye & Ang), fit on the first 40 %, scored on the remaining 60 %"
echo
echo "| model | parameters | fit time [s] | forward e_RMS [m] | forward NRMSE | inverse e_RMS [V] | inverse NRMSE |"
echo "|---|---|---|---|---|---|---|"
i=0
for entry in "${MODELS[@]}"; do
  IFS='|' read -r name kind flags <<<"$entry"
  i=$((i + 1))
  model="$OUT/piezo_model_$i.json"
  # shellcheck disable=SC2086
  "$SYSID" hysteresis fit --model "$kind" $flags --json "$OUT/piezo_train.csv" -o "$model" \
    >"$OUT/piezo_fit_$i.json"
  read -r params fit_time < <(python3 -c "import json,sys; s=json.load(open(sys.argv[1])); \
print(len(s['parameters']), '%.3g' % s['fit_time_s'])" "$OUT/piezo_fit_$i.json")
  "$SYSID" hysteresis simulate --model "$model" "$PIEZO" -o "$OUT/piezo_sim_$i.csv" >/dev/null
  rm -f "$OUT/piezo_inv_$i.csv"
  "$SYSID" hysteresis invert --model "$model" "$OUT/piezo_reference.csv" -o "$OUT/piezo_inv_$i.csv" \
    >/dev/null 2>"$OUT/piezo_inv_$i.err" || true
  read -r fe fn ie in < <($SCORE score "$PIEZO" "$FRACTION" "$OUT/piezo_sim_$i.csv" "$OUT/piezo_inv_$i.csv")
  fn_pct=$(python3 -c "import sys; print('%.2f %%' % (100 * float(sys.argv[1])))" "$fn")
  in_pct=$(python3 -c "import sys; v = float(sys.argv[1]); print('-' if v != v else '%.2f %%' % (100 * v))" "$in")
  # Not invertible: say why, in the library's words up to the first colon-separated detail.
  [ "$ie" = "nan" ] && ie="- ($(sed -e 's/^sysid: [a-z ]*: //' -e 's/ (an error.*//' "$OUT/piezo_inv_$i.err" | head -c 160))"
  echo "| $name | $params | $fit_time | $fe | $fn_pct | $ie | $in_pct |"
done
echo "| Bouc–Wen, piezo form | (filled once bouc-wen-piezo lands) | | | | | |"
echo
echo "Prototype (issue #25 notes, same split): a straight line 20.9 %, PI 10 operators +"
echo "offset 3.0 %, PI 20 operators + offset 2.9 %, PI 20 + u, u², u³ + offset 2.6 % (forward NRMSE)."
echo

echo "## Bouc–Wen benchmark (multisine test set, simulation mode)"
echo
if [ -x experiments/boucwen_benchmark.sh ]; then
  experiments/boucwen_benchmark.sh "$OUT/boucwen" "$BUILD"
else
  echo "(experiments/boucwen_benchmark.sh not present in this version: the Bouc–Wen table is"
  echo "filled by it once the Bouc–Wen models land.)"
fi
