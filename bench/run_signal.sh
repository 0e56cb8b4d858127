#!/usr/bin/env bash
# Derivative throughput: bench_signal (ours beside a plain central-difference loop, same
# process), then SciPy's equivalents on the same signal (same script) where installed:
# numpy.gradient, sosfiltfilt + gradient, savgol_filter (x, v, a), scipy.signal.decimate.
#   bench/run_signal.sh [BUILD_DIR] [SAMPLES]
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD="${1:-build}"
N="${2:-2000000}"
"$BUILD/bench/bench_signal" --samples "$N" --repeats 5
if /usr/bin/python3 -c "import scipy.signal" 2>/dev/null; then
  /usr/bin/python3 - "$N" <<'PY'
import sys, time
import numpy as np, scipy.signal as ss
n = int(sys.argv[1]); dt = 1e-3; q = 1e-6
t = np.arange(n) * dt
x = q * np.round((0.1 * t + 5e-3 * np.sin(2 * np.pi * 2 * t)) / q)
def best(f, r=5):
    b = 1e300
    for _ in range(r):
        t0 = time.perf_counter(); f(); b = min(b, time.perf_counter() - t0)
    return b
sos = ss.butter(4, 50 * dt * 2, output="sos")
cases = [
    ("numpy.gradient (v, a)", lambda: np.gradient(np.gradient(x, dt), dt)),
    ("sosfiltfilt order 4 + gradient (x, v, a)",
     lambda: np.gradient(np.gradient(ss.sosfiltfilt(sos, x), dt), dt)),
    ("savgol_filter 21/3 (x, v, a)",
     lambda: [ss.savgol_filter(x, 21, 3, deriv=d, delta=dt, mode="interp") for d in (0, 1, 2)]),
    ("savgol_filter 51/3 (x, v, a)",
     lambda: [ss.savgol_filter(x, 51, 3, deriv=d, delta=dt, mode="interp") for d in (0, 1, 2)]),
    ("scipy.signal.decimate 10 (iir, zero_phase)", lambda: ss.decimate(x, 10, ftype="iir")),
]
print("SciPy %s (same signal, same script)" % __import__("scipy").__version__)
for name, f in cases:
    s = best(f)
    print("%-46s %10.4f %14.3e" % (name, s, n / s))
PY
else
  echo "SciPy peer: skipped (python3-scipy not installed)"
fi
