#!/bin/sh
# `sysid stage facts` prints, byte for byte, the text kept in stage_facts_reduced.expected.txt
# (captured before the facts moved into their own module; the reduced networks and the facts
# without a network, F1-F4, F6, F8, keep it to a few seconds). A difference is shown as a diff.
#   stage_facts_golden.sh SYSID SOURCE_DIR
set -eu
SYSID="$1"
EXPECTED="$2/tests/paper/stage_facts_reduced.expected.txt"
OUT="$(mktemp)"
trap 'rm -f "$OUT"' EXIT
"$SYSID" stage facts --reduced --facts F1,F2,F3,F4,F6,F8 >"$OUT"
if ! cmp -s "$EXPECTED" "$OUT"; then
  echo "sysid stage facts: the text differs from $EXPECTED:" >&2
  diff "$EXPECTED" "$OUT" >&2 || true
  exit 1
fi
echo "sysid stage facts: the same text as $EXPECTED"
