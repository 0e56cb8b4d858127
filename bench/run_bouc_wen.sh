#!/usr/bin/env bash
# Bouc–Wen speed: the benchmark fit on its 40960 training samples (target < 60 s on 2 cores) and
# the simulators' throughput against the NumPy/SciPy peer (bench/bouc_wen_numpy_peer.py) on the
# same input in the same run.
#   bench/run_bouc_wen.sh [BUILD_DIR] [THREADS]
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD="${1:-build}"
THREADS="${2:-2}"
TRAIN=datasets/boucwen/train.csv
TEST=datasets/boucwen/test_multisine.csv
uptime
# One chain simulation as the fit ran it before against now (CPU, same process), then the fit.
"$BUILD/bench/bench_bouc_wen" fit-speed "$TRAIN" --threads "$THREADS" | grep -E '^(simulation|fit)'
"$BUILD/bench/bench_bouc_wen" score "$TRAIN" "$TEST" --threads "$THREADS" | grep -E '^(fit|score)'
OURS="$("$BUILD/bench/bench_bouc_wen" throughput "$TEST" --repeats 3)"
echo "$OURS"
PEER="$(/usr/bin/python3 bench/bouc_wen_numpy_peer.py "$TEST")"
echo "$PEER"
printf '%s\n%s\n' "$OURS" "$PEER" | awk '
  { for (i = 2; i <= NF; ++i) { split($i, kv, "="); v[kv[1]] = kv[2] } rate[v["method"]] = v["samples_per_s"] }
  END {
    printf "ratio cvode-linear/solve_ivp-lsoda (rtol 1e-6, linear input): %.1fx\n", rate["cvode-linear-rtol1e-6"] / rate["solve_ivp-lsoda-linear-rtol1e-6"]
    printf "ratio chain C++/Python (same chain): %.0fx\n", rate["chain-newmark-x20"] / rate["chain-newmark-x20-python"]
  }'
uptime
