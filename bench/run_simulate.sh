#!/usr/bin/env bash
# Simulator speed, side by side: libsysid (bench_simulate) and the SciPy peer (solve_ivp LSODA
# with a method-of-steps wrapper, ../shared/bench/peers/ivp_mos.py) on the paper's 10 s pulse
# train, both scored against the same h = 1e-6 s reference trajectory (p1_reference_1ms.csv).
#   bench/run_simulate.sh [BUILD_DIR] [REPEATS]
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD="${1:-build}"
REPEATS="${2:-5}"
PEERS="${SYSID_PEERS:-$(cd .. && pwd)/shared/bench/peers}"
REF="tests/data/simulate/p1_reference_1ms.csv"

OURS="$("$BUILD/bench/bench_simulate" --reference "$REF" --repeats "$REPEATS")"
echo "$OURS" | grep -v '^sysid_'

if [ -f "$PEERS/ivp_mos.py" ] && /usr/bin/python3 -c "import scipy" 2>/dev/null; then
  echo "$OURS" | grep '^sysid_case' | /usr/bin/python3 -c '
import statistics, sys, time
peers, ref_path, repeats = sys.argv[1], sys.argv[2], int(sys.argv[3])
ours = []
for line in sys.stdin:
    kv = dict(f.split("=") for f in line.split()[1:])
    ours.append(dict(method=kv["method"], rtol=float(kv["rtol"]), wall=float(kv["wall"]),
                     cpu=float(kv["cpu"]), dv=float(kv["dv"])))
sys.path.insert(0, peers)
import numpy as np
from fricdde import PAPER, pulse_train
from ivp_mos import IvpMoS
segs, t_end = pulse_train()
ref = np.loadtxt(ref_path, delimiter=",", comments="#", skiprows=2)
print("\nSciPy peer (same script, same reference), median of %d; ratios against the fastest "
      "libsysid case with equal or smaller max|dv|:" % repeats)
for rtol in (1e-9, 1e-6):
    walls, cpus = [], []
    for _ in range(repeats):
        w0, c0 = time.perf_counter(), time.process_time()
        s = IvpMoS(PAPER, segs, t_end, "LSODA", rtol, warm=True).run()
        walls.append(time.perf_counter() - w0)
        cpus.append(time.process_time() - c0)
    xs, vs = s.sample(ref[:, 0])
    dv = abs(vs - ref[:, 3]).max()
    wall, cpu = statistics.median(walls), statistics.median(cpus)
    print("  solve_ivp LSODA MoS rtol %g: wall %.4f s, cpu %.4f s, rhs %d, events %d, "
          "max|dv| %.2e, max|dx| %.2e" % (rtol, wall, cpu, s.nrhs, len(s.events), dv,
                                          abs(xs - ref[:, 2]).max()))
    better = [o for o in ours if o["dv"] <= dv]
    if better:
        b = min(better, key=lambda o: o["wall"])
        print("    vs libsysid %s rtol %g (max|dv| %.2e): %.0fx faster by wall time, %.0fx by "
              "cpu time" % (b["method"], b["rtol"], b["dv"], wall / b["wall"], cpu / b["cpu"]))
' "$PEERS" "$REF" "$REPEATS"
else
  echo "SciPy peer skipped: $PEERS/ivp_mos.py or python3-scipy not available"
fi
