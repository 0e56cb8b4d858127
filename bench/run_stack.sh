#!/usr/bin/env bash
# The virtual piezo stack's speed (docs/piezo_stack.md, "Speed"): bench_stack (both integrators
# against the stage, same process) and the NumPy/SciPy peer of the same plant on the same drive
# (bench/stack_numpy_peer.py, the exact zero-order-hold step), same run.
#   bench/run_stack.sh [BUILD_DIR] [SAMPLES]
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD="${1:-build}"
SAMPLES="${2:-50000}"
OURS="$("$BUILD/bench/bench_stack" --samples "$SAMPLES" --repeats 2)"
echo "$OURS"
PEER="$(/usr/bin/python3 bench/stack_numpy_peer.py datasets/piezo_stack/stack.json --samples "$SAMPLES" --repeats 2)"
echo "$PEER"
printf '%s\n%s\n' "$OURS" "$PEER" | awk '
  /^stack exact/ { exact = $3 } /^stack cvode/ { cvode = $3 }
  /^x_end exact/ { ours_x = $3 }
  /^peer/ { for (i = 2; i <= NF; ++i) { split($i, kv, "="); v[kv[1]] = kv[2] } }
  END {
    printf "ratio stack exact / NumPy peer (same exact step): %.0fx\n", exact / v["samples_per_s"]
    printf "ratio stack cvode / NumPy peer: %.2fx\n", cvode / v["samples_per_s"]
    printf "x_end ours %s m, peer %s m\n", ours_x, v["x_end"]
  }'
