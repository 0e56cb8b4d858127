#!/usr/bin/env bash
# Identification benchmark: pulse-identification throughput (ours only; target >= 1000
# recordings/s) and delay tuning on p4_measured.csv beside the SciPy peer
# (../shared/bench/peers/p4_delay_tune.py: minimize_scalar(bounded) + solve_ivp LSODA, method
# of steps), same data, same script; prints the speed ratio at the reported tau accuracy, with
# and without our re-use of identical pulses (the peer simulates every pulse).
#   bench/run_identify.sh [BUILD_DIR]        (SYSID_PEERS overrides the peers' folder)
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD="${1:-build}"
PEERS="${SYSID_PEERS:-$(cd .. && pwd)/shared/bench/peers}"
[ -f "$PEERS/p4_delay_tune.py" ] || { echo "run_identify.sh: no peers in $PEERS (set SYSID_PEERS)" >&2; exit 1; }
OURS="$("$BUILD/bench/bench_identify" --p4 "$PEERS/p4_measured.csv" --repeats 5)"
echo "$OURS" | grep -v '^SYSID_DELAY'
OUR_WALL="$(echo "$OURS" | sed -n 's/^SYSID_DELAY_WALL_S=//p')"
OUR_WALL_NOREUSE="$(echo "$OURS" | sed -n 's/^SYSID_DELAY_NOREUSE_WALL_S=//p')"
OUT="$(mktemp --suffix=.json)"
trap 'rm -f "$OUT"' EXIT
PEER="$(/usr/bin/python3 "$PEERS/p4_delay_tune.py" --repeats 1 --methods LSODA --out "$OUT" 2>/dev/null)"
/usr/bin/python3 - "$PEER" "$OUR_WALL" "$OUR_WALL_NOREUSE" <<'PY'
import json, sys
peer = json.loads(sys.argv[1].splitlines()[0])
ours = float(sys.argv[2])
print("delay tuning (peer):  tau = %.4f ms (error %.2f us), %d simulations, wall %.3f s  [%s]"
      % (1e3 * peer["tau_hat"], 1e6 * peer["tau_err"], peer["n_simulations"],
         peer["wall_median_s"], peer["peer"]))
print("speed-up sysid vs peer, like for like (every pulse simulated): %.0fx"
      % (peer["wall_median_s"] / float(sys.argv[3])))
print("speed-up sysid vs peer, ours re-using identical pulses: %.0fx"
      % (peer["wall_median_s"] / ours))
PY
