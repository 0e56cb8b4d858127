#!/bin/sh
# pipeline -o never deletes a folder sysid did not write, nor its input (issue #14).
# Usage: pipeline_output.sh SYSID SOURCE_DIR
set -u
sysid=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
cp -r "$src/datasets/virtual" in
mkdir thesis && echo keep > thesis/thesis.tex
expect1() {  # expect1 MESSAGE-PART ARGS...
  part=$1; shift
  "$sysid" "$@" 2>err.txt; rc=$?
  [ "$rc" -eq 1 ] || { echo "FAIL: $* exited $rc, expected 1" >&2; cat err.txt >&2; exit 1; }
  grep -q "$part" err.txt || { echo "FAIL: $*: message lacks '$part'" >&2; cat err.txt >&2; exit 1; }
}
expect1 "not written by sysid" pipeline in -o thesis
expect1 "not written by sysid" pipeline in -o thesis/
expect1 "contains the input" pipeline in -o in
expect1 "contains the input" pipeline in/ -o .
[ -f thesis/thesis.tex ] || { echo "FAIL: thesis deleted" >&2; exit 1; }
[ "$(ls in | wc -l)" -eq "$(ls "$src/datasets/virtual" | wc -l)" ] || { echo "FAIL: input touched" >&2; exit 1; }
echo "ok: refused, nothing deleted"
