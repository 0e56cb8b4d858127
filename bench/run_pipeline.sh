#!/usr/bin/env bash
# The main job end to end: `sysid pipeline datasets/virtual` by this build and, in the same run,
# by a baseline binary (SYSID_BASELINE, e.g. a build of the commit before the speed work), with
# wall time per step from --json. Prints the whole job's wall time against the 10 s target and
# the typical (v, a) 120-unit network's time against the baseline's (target >= 3x).
#   bench/run_pipeline.sh [BUILD_DIR] [THREADS]     (THREADS: 0 = all cores, the default)
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD="${1:-build}"
THREADS="${2:-0}"
BASELINE="${SYSID_BASELINE:-}"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
run() {  # run NAME BINARY [extra args]
  local name="$1" bin="$2"
  shift 2
  local t0 t1
  t0=$(date +%s.%N)
  "$bin" pipeline datasets/virtual -o "$TMP/report_$name" --json "$@" > "$TMP/$name.json" 2> "$TMP/$name.log"
  t1=$(date +%s.%N)
  echo "$t0 $t1" > "$TMP/$name.wall"
}
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
if [ -n "$BASELINE" ]; then run baseline "$BASELINE"; fi
run ours "$BUILD/apps/sysid" --threads "$THREADS"
echo "load after:  $(cut -d' ' -f1-3 /proc/loadavg)"
/usr/bin/python3 - "$TMP" "$BASELINE" <<'PY'
import json, os, sys
tmp, baseline = sys.argv[1], sys.argv[2]
def load(name):
    t0, t1 = map(float, open(os.path.join(tmp, name + ".wall")).read().split())
    return t1 - t0, json.load(open(os.path.join(tmp, name + ".json")))
def step_times(summary):
    # steps: [{"name", "wall_time_s"}] in run order; older builds wrote {name: seconds}.
    steps = summary.get("steps", [])
    if isinstance(steps, dict):
        return steps
    return {s["name"]: s["wall_time_s"] for s in steps}
wall, ours = load("ours")
steps = step_times(ours)
print("sysid pipeline datasets/virtual: %.2f s wall  (TARGET < 10 s: %s)" % (wall, "met" if wall < 10 else "not met"))
for k, v in steps.items():
    print("  %-40s %7.2f s" % (k, v))
if baseline:
    bwall, base = load("baseline")
    bsteps = step_times(base)
    print("baseline %s: %.2f s wall; ratio %.2fx" % (baseline, bwall, bwall / wall))
    key = next((k for k in steps if k.startswith("typical")), None)
    if key and key in bsteps:
        print("TARGET typical (v, a) network: %.2f s vs baseline %.2f s: %.2fx faster"
              % (steps[key], bsteps[key], bsteps[key] / steps[key]))
PY
