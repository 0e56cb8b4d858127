#!/bin/sh
# Recording names holding back-quotes, $(), quotes and a newline must not run anything when plots
# are drawn (issue #14), and the plots must still be written. A single quote is kept (plain text
# inside gnuplot's double-quoted strings: x'' is the acceleration); the rest is dropped.
# Usage: plot_injection.sh SYSID SOURCE_DIR
set -eu
sysid=$1
src=$2
command -v gnuplot >/dev/null 2>&1 || exit 77
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
name='sq`touch MARKER1`$(touch MARKER2)"q'"'"'
n.csv'
cp "$src/datasets/virtual/test.csv" "$name"
"$sysid" compare --model "$src/experiments/paper_model.json" -o out ./sq*.csv >/dev/null
for m in MARKER1 MARKER2 out/MARKER1 out/MARKER2; do
  if [ -e "$m" ]; then echo "FAIL: $m was created: a command ran from a file name" >&2; exit 1; fi
done
n=$(find out -name '*.png' -exec printf x \; | wc -c)
# The traces, their errors and (test.csv has more than 1000 samples) the zoom; no loop without a
# hysteresis model.
if [ "$n" -ne 3 ]; then echo "FAIL: expected 3 plots, found $n" >&2; exit 1; fi
echo "ok: no command ran, plots written"
