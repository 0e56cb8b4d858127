#!/usr/bin/env bash
# Each hysteresis model's inverse as feedforward to the PI loop of the virtual piezo stack
# (docs/piezo_stack.md, "Worked example"): generate -> fit -> track.
#  1. Training recordings: PI alone tracking 22 um sines at 2, 10 and 40 Hz on the stack
#     (sysid track -o writes t, x_ref, x, e, u, u_ff: the columns t, u, x are a recording).
#  2. Fit each model kind on the three recordings (sysid hysteresis fit).
#  3. Track 20 um sines and triangles at 1, 10 and 50 Hz (another seed: other sensor noise)
#     with PI alone and PI + each model's inverse; print RMS e [um] and RMS e / stroke.
#
#   experiments/piezo_stack_feedforward.sh [OUT_DIR] [BUILD_DIR]   (default: out/piezo_stack, build)
# PLANT overrides the stack (a stack file or the preset piezo-stack).
set -euo pipefail
cd "$(dirname "$0")/.."
OUT="${1:-out/piezo_stack}"
BUILD="${2:-build}"
SYSID="$BUILD/apps/sysid"
PLANT="${PLANT:-datasets/piezo_stack/stack.json}"
if [ ! -x "$SYSID" ]; then
  echo "piezo_stack_feedforward: $SYSID not found; run scripts/setup.sh first" >&2
  exit 1
fi
mkdir -p "$OUT"
for f in 2 10 40; do
  rm -rf "$OUT/train_$f"
  "$SYSID" track --plant "$PLANT" --ff none --freq "$f" --amplitude 22e-6 --seed 2 --no-plots \
    -o "$OUT/train_$f" > /dev/null
done
TRAIN=("$OUT"/train_2/track_none.csv "$OUT"/train_10/track_none.csv "$OUT"/train_40/track_none.csv)

# kind | flags
MODELS=("pi|--operators 10" "gpi|--operators 10 --degree 3" "rdpi|--operators 10" "bouc-wen-piezo|")
echo "## Fits on the stack's PI-alone traces (2, 10, 40 Hz sines, 22 um)"
echo
echo "| model | fit time [s] | training RMS [um] |"
echo "|---|---|---|"
for entry in "${MODELS[@]}"; do
  kind="${entry%%|*}"; flags="${entry#*|}"
  # shellcheck disable=SC2086
  "$SYSID" hysteresis fit --model "$kind" $flags "${TRAIN[@]}" -o "$OUT/$kind.json" --json \
    > "$OUT/$kind.fit.json"
  python3 -c 'import json,sys; s=json.load(open(sys.argv[1])); print("| %s | %.3g | %.4g |" % (sys.argv[2], s["fit_time_s"], 1e6*s["training_rms_m"]))' \
    "$OUT/$kind.fit.json" "$kind"
done
echo
echo "## Tracking 20 um references (seed 3): RMS e [um] (RMS e / stroke)"
echo
printf '| reference | PI alone |'
for entry in "${MODELS[@]}"; do printf ' PI + %s |' "${entry%%|*}"; done
printf '\n|---|---|'
for entry in "${MODELS[@]}"; do printf -- '---|'; done
printf '\n'
cell() {  # the JSON summary of one track run -> "RMS (percent)"
  python3 -c 'import json,sys; s=json.load(sys.stdin)["schemes"][-1]; print("%.4g (%.3g %%)" % (1e6*s["rms_error_m"], 100*s["rms_error_m"]/20e-6))'
}
for wave in sine triangle; do
  for f in 1 10 50; do
    row="| $wave $f Hz | $("$SYSID" track --plant "$PLANT" --ff none --waveform "$wave" --freq "$f" --seed 3 --json | cell) |"
    for entry in "${MODELS[@]}"; do
      kind="${entry%%|*}"
      if res=$("$SYSID" track --plant "$PLANT" --ff hysteresis --hysteresis "$OUT/$kind.json" \
                 --waveform "$wave" --freq "$f" --seed 3 --json 2> "$OUT/$kind.err"); then
        row="$row $(echo "$res" | cell) |"
      else
        row="$row refused (exit $?) |"
      fi
    done
    echo "$row"
  done
done
for entry in "${MODELS[@]}"; do
  kind="${entry%%|*}"
  if [ -s "$OUT/$kind.err" ]; then echo; echo "$kind: $(tail -1 "$OUT/$kind.err")"; fi
done
