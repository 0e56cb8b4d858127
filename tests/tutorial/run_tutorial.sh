#!/bin/sh
# Runs docs/tutorial.md as a new user would (issue #14): every fenced ```sh or ```bash block, in
# order, in a fresh empty folder with the built sysid first on PATH; the first failing command
# fails the test (set -e, each command echoed). Plain ``` blocks (file contents) are not run.
#   sh tests/tutorial/run_tutorial.sh SYSID_EXECUTABLE SOURCE_DIR [TUTORIAL.md]
# CTest: label "tutorial" (about 6 s in Release, 40 s under ASan).
set -eu
sysid=$1
src=$2
doc=${3:-"$src/docs/tutorial.md"}
[ -x "$sysid" ] || { echo "run_tutorial: no executable '$sysid'" >&2; exit 1; }
[ -f "$doc" ] || { echo "run_tutorial: no tutorial '$doc'" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
bin="$work/bin"
mkdir "$bin"
ln -s "$(cd "$(dirname "$sysid")" && pwd)/$(basename "$sysid")" "$bin/sysid"
# The blocks, concatenated; a block's lines keep their backslash continuations.
awk '
  /^```(sh|bash)[[:space:]]*$/ { inside = 1; blocks++; print "# --- block " blocks; next }
  /^```/ { inside = 0; next }
  inside { print }
  END { if (blocks == 0) exit 1 }
' "$doc" > "$work/tutorial.sh" || { echo "run_tutorial: no sh blocks in $doc" >&2; exit 1; }
mkdir "$work/run"
cd "$work/run"
echo "run_tutorial: $(grep -c '^# --- block' "$work/tutorial.sh") blocks from $doc in $work/run"
PATH="$bin:$PATH" sh -e -x "$work/tutorial.sh" >"$work/out.txt" 2>&1 || {
  rc=$?
  tail -n 40 "$work/out.txt" >&2
  echo "run_tutorial: FAILED (exit $rc) at the last command above" >&2
  exit 1
}
# The files the tutorial says it makes.
for f in data/pulses.csv pulses_cmd.csv waveforms_ref/waveform_square.csv training_va.csv \
         test_va.csv training_va_4.csv model.json model_refined.json sim.csv table.csv nn.json nn_typical.json \
         compare/summary.csv report/report.md report/model.json report/nn.json; do
  [ -s "$f" ] || { echo "run_tutorial: the tutorial did not make $f" >&2; exit 1; }
done
echo "run_tutorial: passed"
