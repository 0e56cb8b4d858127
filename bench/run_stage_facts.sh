#!/usr/bin/env bash
# Issue #28's speed figure: `sysid stage facts --seeds A-B --threads 1` on the default stage
# (drive hysteresis and creep) against, in the same run, the stage it replaced (the preset
# velocity-source) and the default when issue #28 was filed (virtual-1khz), as CPU time (user +
# sys of the child: the measure on a loaded machine) and wall time. Target: the default within
# 2x of each. Prints met_count per fact of every run too.
#   bench/run_stage_facts.sh [BUILD_DIR] [SEEDS]     (SEEDS default 1-12: about 13 min of CPU)
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD="${1:-build}"
SEEDS="${2:-1-12}"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
for stage in virtual-1khz velocity-source virtual; do
  /usr/bin/time -f "%e %U %S" -o "$TMP/$stage.time" \
    "$BUILD/apps/sysid" stage facts --stage "$stage" --seeds "$SEEDS" --json --threads 1 \
    > "$TMP/$stage.json" 2> "$TMP/$stage.log"
done
echo "load after:  $(cut -d' ' -f1-3 /proc/loadavg)"
/usr/bin/python3 - "$TMP" "$SEEDS" <<'PY'
import json, os, sys
tmp, seeds = sys.argv[1], sys.argv[2]
cpu = {}
for stage in ("virtual-1khz", "velocity-source", "virtual"):
    wall, user, sys_ = map(float, open(os.path.join(tmp, stage + ".time")).read().split())
    cpu[stage] = user + sys_
    facts = json.load(open(os.path.join(tmp, stage + ".json")))["facts"]
    counts = ", ".join(f"{f['id']} {f['met_count']}" for f in facts)
    print(f"stage facts --stage {stage} --seeds {seeds}: {wall:.1f} s wall, {cpu[stage]:.1f} s CPU;"
          f" met at: {counts} of {facts[0]['runs']}")
for base in ("velocity-source", "virtual-1khz"):
    ratio = cpu["virtual"] / cpu[base]
    print(f"TARGET default (virtual) within 2x of {base}: {ratio:.2f}x CPU: "
          f"{'met' if ratio <= 2 else 'not met'}")
PY
