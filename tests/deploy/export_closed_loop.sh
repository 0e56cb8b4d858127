#!/bin/sh
# The exported analytic inverse, built as a shared object by the system cc, inside the twin's
# PI loop (tests/deploy/closed_loop/closed_loop_main.cpp): its tracking errors must equal those
# with the library's stepper to 1e-12 m; the same with τ one sample late must not.
# Usage: export_closed_loop.sh SYSID DRIVER
set -u
SYSID=$1
DRIVER=$2
CC=${CC:-cc}
command -v "$CC" >/dev/null 2>&1 || { echo "no C compiler ($CC): skipped"; exit 77; }
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
cd "$WORK" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
# The paper's coefficients at the default virtual stage's 10 kHz control rate.
printf '{"a1p":104.0154,"a1n":117.1441,"a2p":3.1023,"a2n":6.8216,"a3":6,"tau":0.00379}' > model.json
"$SYSID" export --model model.json --dt 1e-4 --prefix ff -o ff >/dev/null || fail "sysid export"
# The state's size for the loader: the struct is the header's, a compile-time constant.
printf '#include <stddef.h>\n#include "ff.h"\nunsigned long ff_state_size(void) { return sizeof(ff_state); }\n' \
  > size.c
FLAGS="-std=c99 -O2 -ffp-contract=off -fPIC -shared -Iff"
# shellcheck disable=SC2086
"$CC" $FLAGS ff/ff.c size.c -o libff.so || fail "shared object does not build"
"$DRIVER" model.json "$PWD/libff.so" ff 1e-4 || fail "the exported C's loop differs from the stepper's"
sed 's/_kWhole = \([0-9]*\);/_kWhole = \1 + 1;/' ff/ff.c > late.c
# shellcheck disable=SC2086
"$CC" $FLAGS late.c size.c -o liblate.so || fail "mutant does not build"
"$DRIVER" model.json "$PWD/liblate.so" ff 1e-4 > /dev/null
[ $? -eq 1 ] || fail "tau one sample late gave the stepper's tracking errors"
echo "tau one sample late: detected"
