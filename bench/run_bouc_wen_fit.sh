#!/usr/bin/env bash
# The Bouc–Wen benchmark fit through the CLI (`sysid hysteresis fit --model bouc-wen
# --integrator benchmark-chain` on the 40960 training samples) by this build and, in the same
# run, by a baseline binary (SYSID_BASELINE, e.g. a build of the commit before the exact
# Jacobian): wall and CPU time (user + system, /usr/bin/time) and their ratios, the parameters'
# differences in standard errors, and each model's e_RMS on the multisine test set
# (`simulate --periodic` by this build). Prints the load before and after: the machine is shared.
#   SYSID_BASELINE=/path/to/old/sysid bench/run_bouc_wen_fit.sh [BUILD_DIR] [THREADS] [EXTRA...]
# EXTRA goes to this build's fit only (e.g. --jacobian central-differences).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD="${1:-build}"
THREADS="${2:-2}"
shift $(($# < 2 ? $# : 2))
BASELINE="${SYSID_BASELINE:-}"
TRAIN=datasets/boucwen/train.csv
TEST=datasets/boucwen/test_multisine.csv
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
fit() {  # fit NAME BINARY [extra args]
  local name="$1" bin="$2"
  shift 2
  /usr/bin/time -f "%e %U %S" -o "$TMP/$name.time" "$bin" hysteresis fit --model bouc-wen \
    --integrator benchmark-chain --threads "$THREADS" "$TRAIN" -o "$TMP/$name.json" "$@" \
    > "$TMP/$name.log"
  "$BUILD/apps/sysid" hysteresis simulate --model "$TMP/$name.json" --periodic "$TEST" \
    -o "$TMP/$name.test.csv" > /dev/null
}
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
if [ -n "$BASELINE" ]; then fit baseline "$BASELINE"; fi
fit ours "$BUILD/apps/sysid" "$@"
echo "load after:  $(cut -d' ' -f1-3 /proc/loadavg)"
/usr/bin/python3 - "$TMP" "$TEST" "$BASELINE" <<'PY'
import json, math, os, sys
tmp, test, baseline = sys.argv[1], sys.argv[2], sys.argv[3]
def columns(path):
    lines = [l for l in open(path) if not l.startswith("#")]
    names = lines[0].strip().split(",")
    cols = {n: [] for n in names}
    for l in lines[1:]:
        for n, v in zip(names, l.strip().split(",")):
            cols[n].append(float(v))
    return cols
x = columns(test)["x"]
def load(name):
    wall, user, system = map(float, open(os.path.join(tmp, name + ".time")).read().split()[-3:])
    model = json.load(open(os.path.join(tmp, name + ".json")))
    y = columns(os.path.join(tmp, name + ".test.csv"))["x_model"]
    erms = math.sqrt(sum((a - b) ** 2 for a, b in zip(y, x)) / len(x))
    return wall, user + system, model, erms
names = ["ours"] + (["baseline"] if baseline else [])
runs = {n: load(n) for n in names}
for n in names:
    wall, cpu, model, erms = runs[n]
    print(f"fit {n} wall_s={wall:.2f} cpu_s={cpu:.2f} test_e_rms_m={erms:.5g} "
          f"message={model['fit']['message']!r}")
if baseline:
    (w1, c1, m1, e1), (w0, c0, m0, e0) = runs["ours"], runs["baseline"]
    print(f"ratio baseline/ours wall {w0 / w1:.2f}x cpu {c0 / c1:.2f}x")
    worst = 0.0
    for k, v0 in m0["parameters"].items():
        se = m0["std_errors"].get(k)
        if se:
            d = abs(m1["parameters"][k] - v0) / se
            worst = max(worst, d)
            print(f"parameter {k} baseline={v0:.10g} ours={m1['parameters'][k]:.10g} "
                  f"diff_in_se={d:.2e} se_baseline={se:.4g} se_ours={m1['std_errors'][k]:.4g}")
    print(f"largest parameter difference: {worst:.2e} standard errors (target <= 1)")
PY
