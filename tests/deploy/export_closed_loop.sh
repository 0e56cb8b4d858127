#!/bin/sh
# The exported inverses, built as shared objects by the system cc, inside the twins' PI loops
# (tests/deploy/closed_loop/closed_loop_main.cpp): the analytic inverse in the virtual stage's,
# the stack's hysteresis as a PI inverse in the piezo stack's. Their tracking errors must equal
# those with the library's steppers to 1e-12 m; with τ one sample late, or two PI operators
# in another order, they must not.
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
"$DRIVER" stage model.json "$PWD/libff.so" ff 1e-4 || fail "the exported C's loop differs from the stepper's"
sed 's/_kWhole = \([0-9]*\);/_kWhole = \1 + 1;/' ff/ff.c > late.c
# shellcheck disable=SC2086
"$CC" $FLAGS late.c size.c -o liblate.so || fail "mutant does not build"
"$DRIVER" stage model.json "$PWD/liblate.so" ff 1e-4 > /dev/null
[ $? -eq 1 ] || fail "tau one sample late gave the stepper's tracking errors"
echo "tau one sample late: detected"

"$DRIVER" stack-model pi.json || fail "stack-model"
"$SYSID" export --hysteresis pi.json --dt 1e-4 --prefix ff -o ffpi >/dev/null || fail "sysid export (stack)"
printf '#include <stddef.h>\n#include "ff.h"\nunsigned long ff_state_size(void) { return sizeof(ff_state); }\n' \
  > size_pi.c
# shellcheck disable=SC2086
"$CC" -std=c99 -O2 -ffp-contract=off -fPIC -shared -Iffpi ffpi/ff.c size_pi.c -o libpi.so \
  || fail "PI shared object does not build"
"$DRIVER" stack pi.json "$PWD/libpi.so" ff 1e-4 || fail "the exported PI inverse's stack loop differs"
sed 's/_kR\[\([0-9]*\)\] = {\([^,]*\), \([^,]*\),/_kR[\1] = {\3, \2,/' ffpi/ff.c > swapped.c
cmp -s swapped.c ffpi/ff.c && fail "the operator swap matched nothing"
"$CC" -std=c99 -O2 -ffp-contract=off -fPIC -shared -Iffpi swapped.c size_pi.c -o libswapped.so \
  || fail "PI mutant does not build"
"$DRIVER" stack pi.json "$PWD/libswapped.so" ff 1e-4 > /dev/null
[ $? -eq 1 ] || fail "two PI operators in another order gave the stepper's tracking errors"
echo "PI operators in another order: detected"
