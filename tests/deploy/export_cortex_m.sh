#!/bin/sh
# The float export of one kind on an emulated Cortex-M4F (QEMU's MPS2 AN386): NAME.c compiled
# by arm-none-eabi-gcc with the strict flags of docs/deploy.md, NAME_check linked against
# newlib with semihosting (rdimon: the check reads the vectors file from the host and prints
# to QEMU's standard output), run by qemu-system-arm. Passes when the Cortex-M check exits 0
# (every output within NAME_BOUND_V of the library's double stepper) and its outputs are within
# NAME_BOUND_V of the x86 float build's; prints the largest difference, arm-none-eabi-size's
# text/data/bss of NAME.o and -fstack-usage's frames. Exit 77 (skipped) when the cross
# toolchain, newlib or QEMU is missing (scripts/test.sh installs them).
# Usage: export_cortex_m.sh SYSID SOURCE_DIR KIND   (KIND as in export_models.sh)
set -u
SYSID=$1
SRC=$2  # export_models.sh reads it
export SRC
KIND=$3
CC=${CC:-cc}
HERE=$(cd "$(dirname "$0")" && pwd)
for tool in arm-none-eabi-gcc arm-none-eabi-size qemu-system-arm "$CC"; do
  command -v "$tool" >/dev/null 2>&1 || {
    echo "no $tool: skipped (scripts/test.sh installs gcc-arm-none-eabi, qemu-system-arm)"
    exit 77
  }
done
ARMFLAGS="-mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16"
# shellcheck disable=SC2086
[ -f "$(arm-none-eabi-gcc $ARMFLAGS -print-file-name=rdimon-crt0.o)" ] || {
  echo "no newlib rdimon start-up: skipped (scripts/test.sh installs libnewlib-arm-none-eabi)"
  exit 77
}
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
cd "$WORK" || exit 1
FLAGS="-std=c99 -Wall -Wextra -Wpedantic -Wconversion -Wshadow -Wdouble-promotion -Werror -O2 -ffp-contract=off"
fail() { echo "FAIL: $*"; exit 1; }

# shellcheck source=export_models.sh
. "$HERE/export_models.sh"

N=ff_$(printf '%s' "$KIND" | tr - _)
# shellcheck disable=SC2086
"$SYSID" export $MODEL --precision float --prefix "$N" -o out >/dev/null || fail "sysid export"
# shellcheck disable=SC2086
"$CC" $FLAGS "out/${N}_check.c" "out/$N.c" -o check_x86 || fail "x86 build"
./check_x86 "out/${N}_vectors.csv" > x86.txt 2>/dev/null || fail "x86 float check"

# shellcheck disable=SC2086
arm-none-eabi-gcc $ARMFLAGS $FLAGS -fstack-usage -c "out/$N.c" -o model.o \
  || fail "$N.c does not compile clean for the Cortex-M4F"
# shellcheck disable=SC2086
arm-none-eabi-gcc $ARMFLAGS -std=c99 -O2 -ffp-contract=off -Iout --specs=rdimon.specs \
  -T "$HERE/cortex_m/mps2_an386.ld" "$HERE/cortex_m/start.c" "out/${N}_check.c" model.o \
  -o check.elf || fail "Cortex-M check does not link"
# The vectors by a relative name: semihosting opens it in QEMU's working folder.
cp "out/${N}_vectors.csv" vectors.csv
timeout 60 qemu-system-arm -M mps2-an386 -nographic -monitor none -serial none \
  -semihosting-config enable=on,target=native,arg=check,arg=vectors.csv -kernel check.elf \
  > arm.txt 2> arm_err.txt
RC=$?
cat arm_err.txt
[ $RC -eq 0 ] || fail "the Cortex-M check exited $RC (1: beyond the bound; 124: timed out)"
[ "$(wc -l < arm.txt)" -eq "$(wc -l < x86.txt)" ] || fail "not one Cortex-M output per row"

BOUND=$(sed -n "s/^#define ${N}_BOUND_V //p" "out/$N.h")
paste -d' ' arm.txt x86.txt | awk -v bound="$BOUND" -v kind="$KIND" '
  { d = $1 - $2; if (d < 0) d = -d; if (d > worst) worst = d; if ($1 != $2) differ++ }
  END {
    printf "%s float, Cortex-M4F against x86: max |du| = %.3g V over %d rows (%d differ), bound %s V\n",
           kind, worst, NR, differ, bound
    exit !(worst <= bound)
  }' || fail "Cortex-M outputs beyond the bound from the x86 float export"
# The planted bug of export_models.sh: QEMU must pass the check's verdict (its exit status, by
# semihosting) through as the x86 build gives it. The first 1000 rows suffice (and keep QEMU's
# run short).
grep -v '^#' vectors.csv | head -n 1001 > head.csv
sed "$MUTANT" "out/$N.c" > mutant.c
cp "out/$N.h" .
"$CC" -std=c99 -O2 -ffp-contract=off -Iout "out/${N}_check.c" mutant.c -o mutant_x86 \
  || fail "x86 mutant does not build"
./mutant_x86 head.csv > /dev/null 2>&1
X86_RC=$?
# shellcheck disable=SC2086
arm-none-eabi-gcc $ARMFLAGS -std=c99 -O2 -ffp-contract=off -Iout --specs=rdimon.specs \
  -T "$HERE/cortex_m/mps2_an386.ld" "$HERE/cortex_m/start.c" "out/${N}_check.c" mutant.c \
  -o mutant.elf || fail "Cortex-M mutant does not link"
timeout 60 qemu-system-arm -M mps2-an386 -nographic -monitor none -serial none \
  -semihosting-config enable=on,target=native,arg=check,arg=head.csv -kernel mutant.elf \
  > /dev/null 2>&1
ARM_RC=$?
[ $X86_RC -eq 1 ] || fail "planted bug: the x86 check exited $X86_RC over the first 1000 rows, not 1"
[ $ARM_RC -eq $X86_RC ] || fail "planted bug: the Cortex-M check exited $ARM_RC, x86's $X86_RC"
echo "$KIND float, planted bug: both checks exit $ARM_RC"
arm-none-eabi-size model.o | awk -v kind="$KIND" \
  'NR == 2 { printf "%s float, Cortex-M4F %s: text %d B, data %d B, bss %d B\n", kind, "'"$N"'.o", $1, $2, $3 }'
# Frames of every function in NAME.c: none recurses, so their sum bounds the stack depth.
awk -v kind="$KIND" '{ n = split($1, a, ":"); sum += $2; list = list sprintf(" %s %d", a[n], $2) }
  END { printf "%s float, Cortex-M4F stack: at most %d B (frames:%s)\n", kind, sum, list }' model.su
