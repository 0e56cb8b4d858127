#!/bin/sh
# Reports for the user (issue #14): excite --json describes what it wrote, train and sweep show
# per-epoch / per-network progress on stderr (with --progress, as on a terminal), and refine
# warns when it moves a given parameter far from its prior. Each run takes well under a second.
. "$(dirname "$0")/common.sh"
v="$src/datasets/virtual"
# excite --json: files, samples, durations, units.
"$sysid" excite pulses -o p.csv --json >p.json 2>err.txt || fail "excite pulses --json"
python3 - <<'PY' || fail "excite pulses --json content"
import json
j = json.load(open("p.json"))
f = j["files"]
assert j["what"] == "pulses" and j["sample_rate_hz"] == 1000 and len(f) == 1, j
rows = sum(1 for l in open("p.csv") if l[0].isdigit() or l[0] == "-")
assert f[0]["path"] == "p.csv" and f[0]["samples"] == rows == j["total_samples"], (f, rows)
assert abs(f[0]["duration_s"] - (rows - 1) / 1000) < 1e-9, f
assert f[0]["units"] == {"t": "s", "u": "V"}, f
PY
"$sysid" excite waveforms -o refs --json >w.json 2>err.txt || fail "excite waveforms --json"
python3 - <<'PY' || fail "excite waveforms --json content"
import json, os
j = json.load(open("w.json"))
assert len(j["files"]) == 6 == len([n for n in os.listdir("refs") if n.endswith(".csv")]), j
for f in j["files"]:
    assert os.path.isfile(f["path"]) and f["waveform"] in f["path"], f
    assert f["units"]["x_ref"] == "m" and f["units"]["v_ref"] == "m/s", f
assert j["total_samples"] == sum(f["samples"] for f in j["files"])
PY
# Without -o nothing is written: the summary alone, path null.
"$sysid" excite tracking --set test --json >t.json 2>err.txt || fail "excite tracking --json"
grep -q '"path": null' t.json || fail "excite --json without -o"
# Progress: one line per epoch (throttled) and per trained network, on stderr only.
"$sysid" --progress train --train "$v/training.csv" --hidden 3 --max-epochs 4 -o n.json \
  >out.txt 2>err.txt || fail "train --progress"
grep -q "epoch 1/4" err.txt && grep -q "epoch 4/4" err.txt || fail "train: no per-epoch progress"
grep -q "epoch 1/4" out.txt && fail "train: progress on stdout"
"$sysid" train --train "$v/training.csv" --hidden 3 --max-epochs 4 -o n.json >out.txt 2>err.txt ||
  fail "train"
grep -q "epoch 1/4" err.txt && fail "train: progress without --progress and no terminal"
"$sysid" --progress sweep --train "$v/training.csv" --hidden 2,3 --max-epochs 2 -o s.json \
  >out.txt 2>err.txt || fail "sweep --progress"
grep -q "trained 1/2 networks" err.txt && grep -q "trained 2/2 networks" err.txt ||
  fail "sweep: no per-network progress"
# refine: a3 given as 20 (the stage's is about 7.5) moves by more than 50 % and many standard
# errors: a warning on stderr and in --json; from the tuned model itself, none.
"$sysid" identify --a3 6 "$v/pulses.csv" -o m.json >/dev/null 2>&1 || fail "identify"
"$sysid" tune-delay --model m.json "$v/pulses.csv" -o m.json >/dev/null 2>&1 || fail "tune-delay"
sed 's/"a3": 6.0/"a3": 20.0/' m.json >m20.json
"$sysid" refine --model m20.json "$v/pulses.csv" --max-iterations 3 --json >r.json 2>err.txt ||
  fail "refine"
grep -q "sysid refine: warning: a3 moved from its given value 20 to" err.txt ||
  fail "refine: no far-from-prior warning"
python3 -c "
import json; w = json.load(open('r.json'))['diagnostics']['warnings']
assert len(w) == 1 and w[0].startswith('a3 moved'), w" || fail "refine --json warnings"
"$sysid" refine --model m.json "$v/pulses.csv" --max-iterations 3 --json >r.json 2>err.txt ||
  fail "refine from the tuned model"
grep -q "warning" err.txt && fail "refine warned without reason"
grep -q '"warnings": \[\]' r.json || fail "refine --json: warnings not empty"
exit 0
