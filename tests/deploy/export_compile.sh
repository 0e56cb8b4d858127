#!/bin/sh
# The exported C of one kind, in double and in float: sysid export; the generated sources
# compiled by the system cc with the strict flags of docs/deploy.md; NAME_check over the
# vectors (exit 0: every output within the header's bound), and again (double) built by clang
# -O3 -march=native where clang is installed; no allocator and no stdio in the
# model's object; the network's own tanh within its error bound of tanhl (tanh_accuracy.c); and
# a planted bug in the generated code that the check must catch.
# Usage: export_compile.sh SYSID SOURCE_DIR KIND   (KIND: friction, nn, pi, gpi, rdpi,
# nn-operators, bouc-wen; an rdpi whose rate feedback leaves float no bound must be refused in float)
set -u
SYSID=$1
SRC=$2
KIND=$3
CC=${CC:-cc}
command -v "$CC" >/dev/null 2>&1 || { echo "no C compiler ($CC): skipped"; exit 77; }
command -v nm >/dev/null 2>&1 || { echo "no nm: skipped"; exit 77; }
HERE=$(cd "$(dirname "$0")" && pwd)
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
cd "$WORK" || exit 1
FLAGS="-std=c99 -Wall -Wextra -Wpedantic -Wconversion -Wshadow -Werror -O2 -ffp-contract=off"
fail() { echo "FAIL: $*"; exit 1; }

. "$HERE/export_models.sh"

if [ -n "$FLOAT_REFUSED" ]; then
  # shellcheck disable=SC2086
  "$SYSID" export $FLOAT_REFUSED --precision float -o refused >/dev/null 2>&1
  [ $? -eq 1 ] && [ ! -e refused ] || fail "float export of $KIND: expected exit 1, nothing written"
  # shellcheck disable=SC2086
  "$SYSID" export $FLOAT_REFUSED --precision double -o accepted >/dev/null 2>&1 \
    || fail "the model refused in float must export in double"
fi
for PREC in $PRECS; do
  EXTRA=""
  [ "$PREC" = float ] && EXTRA="-Wdouble-promotion"
  OUT=out_$PREC
  N=ff_$(printf '%s' "$KIND" | tr - _)
  # shellcheck disable=SC2086
  "$SYSID" export $MODEL --precision "$PREC" --prefix "$N" -o "$OUT" >/dev/null \
    || fail "$PREC: sysid export"
  for f in "$N.h" "$N.c" "${N}_check.c" "${N}_vectors.csv" "${N}_README.md"; do
    [ -f "$OUT/$f" ] || fail "$PREC: $f not written"
  done
  # shellcheck disable=SC2086
  "$CC" $FLAGS $EXTRA -c "$OUT/$N.c" -o model.o || fail "$PREC: $N.c does not compile clean"
  # shellcheck disable=SC2086
  "$CC" $FLAGS $EXTRA "$OUT/${N}_check.c" model.o -o check || fail "$PREC: check does not build"
  ./check "$OUT/${N}_vectors.csv" > outputs.txt || fail "$PREC: outputs beyond the bound"
  # Another compiler and flags (double: the bit-identical case), where clang is installed.
  if [ "$PREC" = double ] && command -v clang >/dev/null 2>&1; then
    # shellcheck disable=SC2086
    clang $FLAGS $EXTRA -O3 -march=native "$OUT/${N}_check.c" "$OUT/$N.c" -o check_clang \
      || fail "$PREC: clang -O3 -march=native does not compile it clean"
    ./check_clang "$OUT/${N}_vectors.csv" > /dev/null 2>&1 || fail "$PREC: clang build beyond the bound"
  fi
  ROWS=$(grep -vc '^#' "$OUT/${N}_vectors.csv")
  [ "$(wc -l < outputs.txt)" -eq $((ROWS - 1)) ] || fail "$PREC: one output per row expected"
  if nm model.o | grep -Eq ' U (malloc|calloc|realloc|free|printf|puts|fprintf|tanh|exp|expm1|log)f?$'; then
    nm model.o | grep ' U '
    fail "$PREC: the model's object calls the allocator, stdio or libm"
  fi
  grep -q "SHA-256 [0-9a-f]\{64\}" "$OUT/$N.h" || fail "$PREC: no SHA-256 in the header"
  # The network's own tanh against long double tanhl, within its first-order bound.
  if [ "$KIND" = nn ]; then
    "$CC" -std=c99 -O2 -ffp-contract=off -DT="$PREC" -DNAME="${N}_tanh" -DLIMIT=6.6 -I"$OUT" \
      -include "$OUT/$N.c" "$HERE/tanh_accuracy.c" -o tanh_accuracy -lm \
      || fail "$PREC: tanh_accuracy does not build"
    ./tanh_accuracy || fail "$PREC: the exported tanh beyond its bound"
  fi
  # The planted bug must be caught by the check (in double, where the bound is tight).
  if [ "$PREC" = double ]; then
    sed "$MUTANT" "$OUT/$N.c" > mutant.c
    cmp -s mutant.c "$OUT/$N.c" && fail "the planted bug's edit matched nothing"
    cp "$OUT/$N.h" .
    # shellcheck disable=SC2086
    "$CC" -std=c99 -O2 -ffp-contract=off -I"$OUT" "$OUT/${N}_check.c" mutant.c -o mutant \
      || fail "mutant does not build"
    ./mutant "$OUT/${N}_vectors.csv" > /dev/null 2>&1
    [ $? -eq 1 ] || fail "the check passed a planted bug ($MUTANT)"
  fi
  echo "$KIND $PREC: ok ($(tail -c 200 outputs.txt | tail -1))"
done
