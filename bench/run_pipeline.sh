#!/usr/bin/env bash
# The main job end to end: `sysid pipeline datasets/virtual` by this build and, in the same run,
# by a baseline binary (SYSID_BASELINE, e.g. a build of the commit before the speed work),
# alternated N times. Per binary: the median wall and CPU time (user + system, children
# included: gnuplot) and the median of each step's wall time from --json; the load average
# before and after (the machine may be shared: CPU-s says more than wall then). Then whether the
# outputs agree: every file but the PNG plots and the folder's marker byte for byte (report.md
# but its line naming the steps), and the --json summaries but their step times.
#   bench/run_pipeline.sh [BUILD_DIR] [THREADS] [N]   (THREADS: 0 = all cores; N: 5)
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD="${1:-build}"
THREADS="${2:-0}"
N="${3:-5}"
BASELINE="${SYSID_BASELINE:-}"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
run() {  # run NAME I BINARY [extra args]
  local name="$1" i="$2" bin="$3"
  shift 3
  local out="$TMP/report_${name}_$i"
  /usr/bin/time -f "%e %U %S" -o "$TMP/${name}_$i.time" \
    "$bin" pipeline datasets/virtual -o "$out" --json "$@" > "$TMP/${name}_$i.json" \
    2> "$TMP/${name}_$i.log"
}
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)  ($(nproc) cores)"
for i in $(seq 1 "$N"); do
  if [ -n "$BASELINE" ]; then run baseline "$i" "$BASELINE"; fi
  run ours "$i" "$BUILD/apps/sysid" --threads "$THREADS"
done
echo "load after:  $(cut -d' ' -f1-3 /proc/loadavg)"
/usr/bin/python3 - "$TMP" "$BASELINE" "$N" <<'PY'
import filecmp, json, os, statistics, sys
tmp, baseline, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
def runs(name):
    out = []
    for i in range(1, n + 1):
        wall, user, sys_ = map(float, open(os.path.join(tmp, "%s_%d.time" % (name, i))).read().split())
        j = json.load(open(os.path.join(tmp, "%s_%d.json" % (name, i))))
        steps = j.get("steps", [])
        # steps: [{"name", "wall_time_s"}] in run order; older builds wrote {name: seconds}.
        steps = steps if isinstance(steps, dict) else {s["name"]: s["wall_time_s"] for s in steps}
        out.append((wall, user + sys_, steps, j))
    return out
def med(xs):
    return statistics.median(xs)
def summary(label, rs):
    wall, cpu = med([r[0] for r in rs]), med([r[1] for r in rs])
    print("%s: median of %d: %.2f s wall, %.2f CPU-s  (walls %s)" % (
        label, len(rs), wall, cpu, " ".join("%.1f" % r[0] for r in rs)))
    for k in rs[0][2]:
        print("  %-52s %7.2f s" % (k, med([r[2].get(k, float("nan")) for r in rs])))
    # Per run, then the median: medians of the steps need not add up to the median wall.
    print("  %-52s %7.2f s" % ("outside the steps", med([r[0] - sum(r[2].values()) for r in rs])))
    return wall, cpu
ours = runs("ours")
wall, cpu = summary("sysid pipeline datasets/virtual", ours)
print("TARGET < 10 s wall: %s" % ("met" if wall < 10 else "not met (state the load)"))
if baseline:
    base = runs("baseline")
    bwall, bcpu = summary("baseline " + baseline, base)
    print("ratio baseline / ours: wall %.2fx, CPU %.2fx" % (bwall / wall, bcpu / cpu))
    a, b = os.path.join(tmp, "report_baseline_1"), os.path.join(tmp, "report_ours_1")
    files = sorted(f for f in os.listdir(a) if not f.endswith(".png") and not f.startswith("."))
    _, mismatch, errors = filecmp.cmpfiles(a, b, files, shallow=False)
    # report.md names the steps run; a step added or renamed is not a changed number.
    unsteps = lambda p: [l for l in open(p) if not l.startswith("Steps:")]
    mismatch = [f for f in mismatch
                if not (f == "report.md" and unsteps(os.path.join(a, f)) == unsteps(os.path.join(b, f)))]
    strip = lambda j: {k: v for k, v in j.items() if k not in ("steps", "report")}
    same_json = strip(base[0][3]) == strip(ours[0][3])
    print("outputs (every file but *.png): %s; --json but steps: %s" % (
        "identical" if not mismatch and not errors else "DIFFER: " + " ".join(mismatch + errors),
        "identical" if same_json else "DIFFERENT"))
PY
