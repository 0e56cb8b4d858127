#!/bin/sh
# A number that overflows a double in a model file is bad data (exit 2, FILE:LINE:COL), not an
# internal error (issue #14).
set -u
sysid=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
sed 's/"a3": *[0-9.e+-]*/"a3": 1e400/' "$src/experiments/paper_model.json" > "$work/big.json"
"$sysid" compare --model "$work/big.json" "$src/datasets/virtual/test.csv" 2>"$work/err.txt" >/dev/null
rc=$?
[ "$rc" -eq 2 ] || { echo "FAIL: exit $rc, expected 2" >&2; cat "$work/err.txt" >&2; exit 1; }
grep -q "big.json:1:[0-9]*: expected a finite number, found 1e400" "$work/err.txt" ||
  { echo "FAIL: message" >&2; cat "$work/err.txt" >&2; exit 1; }
echo ok
