#!/usr/bin/env bash
# CSV throughput: sysid::ReadRecording vs getline/strtod baselines (same process), and
# numpy.loadtxt on the same file (same script) where python3-numpy is installed.
#   bench/run_csv.sh [BUILD_DIR] [MB]
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD="${1:-build}"
MB="${2:-100}"
FILE="$(mktemp --suffix=.csv)"
trap 'rm -f "$FILE"' EXIT
/usr/bin/env python3 - "$FILE" "$MB" <<'PY'
import math, sys
path, mb = sys.argv[1], float(sys.argv[2])
rows = int(mb * 1e6 / 95)
with open(path, "w") as f:
    f.write("t,u,x,v,a\n")
    for k in range(rows):
        t = k * 1e-3
        f.write("%r,%r,%r,%r,%r\n" % (t, 1.6 * math.sin(3.1 * t), 0.01 * math.sin(0.7 * t) + 1e-7 * (k % 7),
                                      0.007 * math.cos(0.7 * t), -0.0049 * math.sin(0.7 * t)))
PY
"$BUILD/bench/bench_csv" "$FILE" --repeats 3
if /usr/bin/python3 -c "import numpy" 2>/dev/null; then
  /usr/bin/python3 - "$FILE" <<'PY'
import os, sys, time
import numpy as np
path = sys.argv[1]
mb = os.path.getsize(path) / 1e6
t0 = time.perf_counter()
d = np.loadtxt(path, delimiter=",", skiprows=1)
t = time.perf_counter() - t0
print("%-42s %10.3f %10.0f   (rows %d)" % ("numpy.loadtxt (same file, same script)", t, mb / t, d.shape[0]))
PY
else
  echo "numpy.loadtxt: skipped (python3-numpy not installed)"
fi
