#!/bin/sh
# Every size bounded before allocation, every loop bounded in work (issue #29, item 3): each
# big request runs under `ulimit -v` (1 GiB of address space) and ends with exit 1 or 2 naming
# its limit, never bad_alloc (exit 4) or a kill. Usage: bounded_memory.sh SYSID SOURCE_DIR
set -u
. "$(dirname "$0")/common.sh"
v="$src/datasets/virtual"
# Sanitizer builds reserve terabytes of address space and cannot start under ulimit -v: skip.
(ulimit -v 1048576 && "$sysid" --version) >/dev/null 2>&1 || { echo "skip: ulimit -v"; exit 77; }
ulimit -v 1048576

# derive --resample: rate x duration against kMaxSignalSamples (2e7).
expect 1 "--resample: Resample::rate_hz = 1e+12" derive "$v/pulses.csv" --resample 1e12
expect 1 "rate_hz x duration <= kMaxSignalSamples = 2e7" derive "$v/pulses.csv" --resample 5e6
# A recording with a 1e6 s gap: 1e9 samples at 1 kHz.
printf 't,u,x\n0,0,0\n0.001,0,0\n0.002,0,0\n1000000,0,0\n1000000.001,0,0\n' > gap.csv
expect 1 "(1e+09 samples over the 1e+06 s of gap.csv)" derive gap.csv --resample 1000
# Savitzky-Golay: the window is bounded (work per sample) and memory is linear in it.
expect 1 "--window: DerivativeOptions::savgol_window = 20001. Violated constraint: savgol_window <= 10001" \
  derive "$v/training.csv" --method savgol --window 20001 --order 5
expect 1 "savgol_window <= 10001" derive "$v/training.csv" --method savgol --window 100001
expect 1 "savgol_order <= 20" derive "$v/training.csv" --method savgol --window 101 --order 50
# The largest window runs (its weights used to be a window x window matrix: 800 MB here).
expect 0 "" derive "$v/training.csv" --method savgol --window 10001 --order 5 -o sg.csv
[ -s sg.csv ] || fail "derive --window 10001 wrote nothing"
# info on an endless or huge input: a device is refused, a file past 4 GiB is refused unread.
expect 2 "/dev/zero: cannot open: is a character device, not a file" info /dev/zero
truncate -s 5G big.csv 2>/dev/null && expect 2 "past the 4 GiB a file may have" info big.csv
rm -f big.csv
# A recording of more than 2e7 rows (kMaxSignalSamples) is refused while it is read: its values
# would take 4 bytes for each 1 of a short row's text.
awk 'BEGIN { print "t,u,x"; for (i = 0; i <= 20000000; i++) printf "%d,0,0\n", i }' > rows.csv
expect 2 "rows.csv:20000002: more than 20000000 rows" info rows.csv
rm -f rows.csv
# tune-delay --curve: at most 1000 points.
printf '{"a1p": 104.0154, "a1n": 117.1441, "a2p": 3.1023, "a2n": 6.8216, "a3": 6.0, "tau": 0}\n' \
  > model.json
expect 1 "--curve" tune-delay --model model.json --curve 10000 "$v/pulses.csv"
echo "ok: every big request refused before allocation, under ulimit -v"
