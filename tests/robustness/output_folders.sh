#!/bin/sh
# Every "-o DIR" (excite, compare, validate, track, pipeline, export) follows one rule: a new or empty folder, or
# one sysid wrote (with --force); a user's folder is refused with exit 1 and nothing is deleted
# (issue #14). Usage: output_folders.sh SYSID SOURCE_DIR
set -u
. "$(dirname "$0")/common.sh"
mkdir thesis && echo keep > thesis/thesis.tex
# excite waveforms -o DIR: one CSV per waveform (the tutorial's next step globs them).
expect 0 "" excite waveforms -o refs
[ "$(ls refs/waveform_*.csv | wc -l)" -eq 6 ] || fail "excite waveforms -o refs: expected 6 CSVs"
[ -f refs/.sysid-output ] || fail "no marker in refs"
expect 1 "pass --force" excite waveforms -o refs
expect 0 "" excite waveforms -o refs/ --force
expect 0 "" excite tracking --set test -o test_refs/
[ -d test_refs ] && [ "$(ls test_refs/*.csv | wc -l)" -ge 2 ] || fail "excite tracking -o test_refs/"
expect 0 "" excite tracking -o one.csv
[ -f one.csv ] || fail "excite tracking -o one.csv wrote no file"
expect 1 "not written by sysid" excite waveforms -o thesis
expect 1 "not written by sysid" excite waveforms -o thesis --force
expect 1 "is not a folder" excite waveforms -o thesis/thesis.tex
cat > model.json <<'JSON'
{"a1p": 104.0154, "a1n": 117.1441, "a2p": 3.1023, "a2n": 6.8216, "a3": 6.0, "tau": 0.0035}
JSON
data="$src/datasets/virtual/waveform_square.csv"
expect 1 "not written by sysid" compare --model model.json --no-plots -o thesis "$data"
expect 1 "not written by sysid" track --freq 0.5 --no-plots -o thesis
expect 1 "contains the input" compare --model model.json --no-plots -o . "$data" model.json
expect 0 "" compare --model model.json --no-plots -o cmp "$data"
[ -f cmp/summary.json ] && [ -f cmp/.sysid-output ] || fail "compare -o cmp wrote no summary"
expect 1 "pass --force" compare --model model.json --no-plots -o cmp "$data"
expect 1 "not written by sysid" validate --model model.json --no-plots -o thesis "$data"
expect 1 "contains the input" validate --model model.json --no-plots -o . "$data" model.json
expect 0 "" validate --model model.json --no-plots -o val "$data"
[ -f val/summary.json ] && [ -f val/.sysid-output ] || fail "validate -o val wrote no summary"
expect 1 "pass --force" validate --model model.json --no-plots -o val "$data"
expect 1 "not written by sysid" export --model model.json --dt 1e-3 -o thesis
expect 0 "" export --model model.json --dt 1e-3 -o c_export
[ -f c_export/sysid_inverse.c ] && [ -f c_export/.sysid-output ] || fail "export -o c_export"
expect 1 "pass --force" export --model model.json --dt 1e-3 -o c_export
expect 1 "contains the input" export --model model.json --dt 1e-3 -o .
[ -f thesis/thesis.tex ] && [ "$(ls -A thesis | wc -l)" -eq 1 ] || fail "thesis folder changed"
ls -a | grep -q "^\.\(thesis\|refs\|cmp\|val\)\.tmp" && fail "temporary folder left"
echo "ok: every -o DIR follows the folder rule"
