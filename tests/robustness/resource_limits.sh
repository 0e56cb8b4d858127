#!/bin/sh
# Sizes typed by a user are bounded before allocation: each case exits with the documented code
# at once, naming the option or key and the limit, instead of running out of memory (issue #14).
# Usage: resource_limits.sh SYSID SOURCE_DIR
set -u
. "$(dirname "$0")/common.sh"
train="$src/datasets/virtual/training.csv"
expect 1 "at most 20000000 samples" excite pulses --rate 1e12
expect 1 "at most 20000000 samples" excite pulses --on 1e9
expect 1 "at most 20000000 samples" excite waveforms --cycles 1000000000
expect 1 "cycles / frequency_hz" track --cycles 1000000000
expect 1 "20 samples a period" track --freq 1e9
expect 1 "stage's travel" track --amplitude 1e9
expect 1 "2e7 output samples" simulate --paper-model --pulses 1 --t-end 1e5 -o sim.csv
expect 1 "20000000 table rows" simulate --paper-model --pulses 1 --pulse-repeats 2000000000 -o sim.csv
expect 1 "above the limit of 4 GB" train --hidden 100000 --train "$train" --inputs v,a
expect 1 "sizes must be <= 100000" sweep --hidden 1:2000000000 --train "$train"
expect 1 "more than 1000 sizes" sweep --hidden 1:5000 --train "$train"
expect 1 "seed" train --seed -1 --train "$train"
sed 's/"control_rate_hz": [0-9.e]*/"control_rate_hz": 1e12/' "$src/datasets/virtual/stage.json" > fast.json
expect 2 "fast.json:[0-9]*:[0-9]*: rig.control_rate_hz: expected a number in (0, 1e+06]" \
  generate pulses --stage fast.json -o g
[ ! -e sim.csv ] && [ ! -e g ] || fail "partial output left"
echo "ok: every oversized request refused before allocation"
