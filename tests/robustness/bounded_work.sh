#!/bin/sh
# Issue #38 (items 2 and 3): every model's work bounded before it starts, -o onto a device never
# read, a user's file never replaced because of keys it happens to hold, and the last exit-4 and
# silent-garbage paths. Each command runs under `timeout` (a hang fails the test) and, where the
# case was an allocation, `ulimit -v`. Usage: bounded_work.sh SYSID SOURCE_DIR
set -u
. "$(dirname "$0")/common.sh"
# timed SECONDS CODE MESSAGE-PART ARGS...: expect, within SECONDS (exit 124 is a hang).
timed() {
  secs=$1; code=$2; part=$3; shift 3
  timeout "$secs" "$sysid" "$@" >out.txt 2>err.txt; rc=$?
  [ "$rc" -ne 124 ] || fail "$* ran past ${secs} s"
  [ "$rc" -eq "$code" ] || fail "$* exited $rc, expected $code"
  [ -z "$part" ] || grep -q -- "$part" err.txt || fail "$*: message lacks '$part'"
  grep -q "internal error" err.txt && fail "$*: internal error"
  return 0
}
rows() {  # rows N FILE: t,u over N samples at 750 Hz
  awk -v n="$1" 'BEGIN { print "t,u"; for (k = 0; k < n; k++) printf "%.17g,%.17g\n", k / 750, sin(k * 0.01) }' > "$2"
}

# Bouc-Wen: rows x upsampling and the FFT's work, refused before allocation (were > 120 s and
# exit 4 std::bad_alloc).
bw='"m": 2, "c": 10, "k": 5e4, "alpha": 5e4, "beta": 1e3, "gamma": 0.8, "delta": -1.1, "nu": 1'
printf '{"kind": "bouc-wen", "parameters": {%s}, "simulation": {"integrator": "benchmark-chain", "upsampling": 997}}\n' "$bw" > bw997.json
printf '{"kind": "bouc-wen", "parameters": {%s}, "simulation": {"integrator": "benchmark-chain", "upsampling": 1000}}\n' "$bw" > bw1000.json
rows 20000 r20k.csv
rows 200000 r200k.csv
timed 10 2 "bw997.json: on r20k.csv: bouc-wen: .*more than the 2e+09 allowed (kMaxFftWork)" \
  hysteresis simulate --model bw997.json r20k.csv -o o.csv
[ ! -e o.csv ] || fail "hysteresis simulate wrote o.csv after refusing the work"
# Under ulimit -v where the build can start under it (sanitizer builds reserve terabytes).
limit=""
(ulimit -v 1048576 && "$sysid" --version) >/dev/null 2>&1 && limit="ulimit -v 1048576;"
(eval "$limit"; "$sysid" hysteresis simulate --model bw1000.json r200k.csv -o o.csv \
  >out.txt 2>err.txt; echo $? > rc.txt)
[ "$(cat rc.txt)" = 2 ] || fail "upsampling 1000 on 200k rows exited $(cat rc.txt), expected 2"
grep -q "bw1000.json: on r200k.csv: bouc-wen: the benchmark chain on 200000 samples x upsampling 1000 = 2e+08 fine samples, more than the 2e+07" err.txt ||
  fail "upsampling 1000 on 200k rows: message"

# A band-limited input with many lines is tabulated once (summing every line at each of
# CVODE's evaluations ran for minutes on a rough 8000-sample input): that input now simulates
# in seconds, and a table too large to hold is refused before it is allocated.
printf '{"kind": "bouc-wen-piezo", "parameters": {"d": 1e-6, "alpha": 0.2, "beta": 0.05, "gamma": 0.01, "offset": 0}, "simulation": {"integrator": "cvode", "input": "band-limited"}}\n' > bwp.json
awk 'BEGIN { srand(1); print "t,u"; for (k = 0; k < 8000; k++) printf "%g,%.17g\n", k / 1000, 10 * rand() }' > rnd.csv
timed 20 0 "" hysteresis simulate --model bwp.json rnd.csv -o o.csv
rm -f o.csv
awk 'BEGIN { srand(2); print "t,u"; for (k = 0; k < 300000; k++) printf "%g,%.9g\n", k / 1000, 10 * rand() }' > rnd300k.csv
timed 20 2 "bwp.json: on rnd300k.csv: bouc-wen: the band-limited input of 300000 samples (.* spectral lines) would be tabulated at .* points a sample: 3 values (u, u', u'') at .* points, more than the 2e+07" \
  hysteresis simulate --model bwp.json rnd300k.csv -o o.csv
[ ! -e o.csv ] || fail "hysteresis simulate wrote o.csv after refusing the table"
rm -f rnd300k.csv
# A CVODE fit builds each recording's table once, before its first simulation: the same refusal,
# naming the recording (was: every evaluation failing, "bouc-wen fit failed", exit 3).
awk 'BEGIN { srand(2); print "t,u,x"; for (k = 0; k < 300000; k++) printf "%g,%.9g,%.9g\n", k / 1000, 10 * rand(), 1e-6 * rand() }' > rnd300kx.csv
timed 20 2 "rnd300kx.csv: bouc-wen: the band-limited input of 300000 samples (.* spectral lines) would be tabulated at .* points a sample" \
  hysteresis fit --model bouc-wen --integrator cvode --input band-limited --starts 1 rnd300kx.csv -o fit.json
[ ! -e fit.json ] || fail "hysteresis fit wrote fit.json after refusing the table"
rm -f rnd300kx.csv

# The periodic search's work: the undamped (c = 0) CVODE form never settles; it now stops at a
# bounded number of samples (was > 120 s), and a period too long for two runs is refused.
printf '{"kind": "bouc-wen", "parameters": {%s}, "simulation": {"integrator": "cvode"}}\n' \
  "$(echo "$bw" | sed 's/"c": 10/"c": 0/')" > bwc0.json
awk 'BEGIN { print "t,u"; for (k = 0; k < 200; k++) printf "%.17g,%.17g\n", k / 750, 10 * sin(2 * 3.141592653589793 * k / 200) }' > period.csv
timed 60 3 "bwc0.json: on period.csv: bouc-wen: no periodic steady state within .* at most 1e+06" \
  hysteresis simulate --periodic --model bwc0.json period.csv -o o.csv
rows 500001 long.csv
timed 10 2 "bwc0.json: on long.csv: bouc-wen: a periodic simulation of 2 periods of 500001 samples exceeds" \
  hysteresis simulate --periodic --model bwc0.json long.csv -o o.csv
rm -f r200k.csv long.csv

# import -o onto a device or a FIFO writes through it, never reads it (read /dev/zero forever).
printf '1\n2\n3\n' > u.txt
timed 10 0 "" import --column u=u.txt:1 --rate 10 -o /dev/zero
timed 10 2 "/dev/full: cannot write: No space left on device" import --column u=u.txt:1 --rate 10 -o /dev/full
mkfifo fifo
(cat fifo > from_fifo.txt) &
timed 10 0 "" import --column u=u.txt:1 --rate 10 -o fifo
wait
grep -q '^# generator: sysid ' from_fifo.txt || fail "import -o FIFO: nothing came through"

# Values near the largest double: info prints them (was exit 4, json type_error 302).
printf 't,u,x\n0,1e308,0\n1,1.7e308,1e-6\n2,1e308,2e-6\n' > b.csv
timed 10 0 "" info b.csv
grep -q "1.23333e+308" out.txt || fail "info b.csv: the mean of u"
printf 't,u,x\n0,1,0\n1,1,1e-6\n2,1,2e-6\n' > c.csv
timed 10 2 "c.csv: column 't'\[2\]: t = 1e-320 after 0: expected a step of at least" info c.csv --scale t=1e-320
printf 'u,x\n1,0\n1,1e-6\n1,2e-6\n' > d.csv
timed 10 1 "rate 1e-320: t = k / rate over 3 samples reaches inf" info d.csv --rate 1e-320
printf 't,u,x\n0,1,0\n1e-320,1,1e-6\n' > e.csv
timed 10 2 "e.csv:3:1: column 't': a step of 1e-320 s" info e.csv

# A user's file is not replaced because it holds keys sysid writes: only sysid's generator
# mark, the first line or key, says sysid wrote it.
pz="$src/datasets/piezo_aye_ang/piezo.csv"
printf '{"note":"lab log","fit_time_s":3}\n' > n.json
cp n.json n0.json
timed 60 1 "-o n.json: exists and was not written by sysid" hysteresis fit --model pi "$pz" -o n.json
cmp -s n.json n0.json || fail "hysteresis fit replaced the user's n.json"
printf '# stage: my rig\nt,u,x\n0,0,0\n0.001,1,0\n0.002,1,1e-6\n0.003,1,2e-6\n0.004,1,3e-6\n' > st.csv
cp st.csv st0.csv
timed 10 1 "-o st.csv: exists and was not written by sysid" derive st.csv -o st.csv
cmp -s st.csv st0.csv || fail "derive replaced the user's CSV with a '# stage:' line"
timed 10 0 "" derive st.csv -o st_d.csv
head -1 st_d.csv | grep -q '^# generator: sysid ' || fail "derive: no generator mark"
timed 10 0 "" derive st.csv -o st_d.csv   # its own file: replaced without --force

# Two hysteresis models whose labels differ only in '-' / '_': both traces kept.
timed 60 0 "" hysteresis fit --model pi "$pz" -o a-b.json
cp a-b.json a_b.json
timed 60 0 "" compare --hysteresis a-b.json --hysteresis a_b.json --no-plots -o cmp "$pz"
head -20 cmp/piezo_traces.csv | grep -v '^#' | head -1 | grep -q 'u_pi_a_b,u_pi_a_b_2' ||
  fail "compare: a model's trace column was dropped ($(grep -v '^#' cmp/piezo_traces.csv | head -1))"

# An error while a -o DIR command writes names DIR, not its hidden staging folder (a label too
# long for a MATLAB variable name fails the MAT traces file inside the staging folder).
long_label=$(printf 'm%.0s' $(seq 1 70))
cp a-b.json "$long_label.json"
timed 60 2 "cmpm/piezo_traces.mat: column 'u_pi_mmm" \
  compare --hysteresis "$long_label.json" --traces mat --no-plots -o cmpm "$pz"
grep -q "\.cmpm\.tmp" err.txt && fail "compare -o: the error names the staging folder"
[ ! -e cmpm ] || fail "compare -o cmpm published a folder after failing"

# The stack's sensor and damping are bounded (were inf in the table, "gain nan").
timed 10 2 "rig.sensor_resolution_m: expected 1e-20 <= sensor_resolution_m <= 1e-3, found 1e-320" \
  track --plant "$(printf '{"plant": "piezo-stack", "rig": {"sensor_resolution_m": 1e-320}}' > s1.json; echo s1.json)" --cycles 1
timed 10 2 "rig.sensor_noise_m: expected 0 <= sensor_noise_m <= 1e-3, found 1e+300" \
  track --plant "$(printf '{"plant": "piezo-stack", "rig": {"sensor_noise_m": 1e300}}' > s2.json; echo s2.json)" --cycles 1
timed 10 2 "mechanics.damping_ratio: expected damping_ratio in \[1e-4, 2\], found 1e-300" \
  track --plant "$(printf '{"plant": "piezo-stack", "mechanics": {"damping_ratio": 1e-300}}' > s3.json; echo s3.json)" --cycles 1

# A stack folder whose u, x are near 1e150 (was exit 0, "inf %" and a Ceres dump in report.md).
mkdir sf
awk 'BEGIN { print "t,u,x"; for (k = 0; k < 2000; k++) printf "%g,%.17g,%.17g\n", k / 1000, 1e150 * sin(k * 0.01), 1e150 * sin(k * 0.01 - 0.3) }' > sf/stack.csv
timed 30 2 "sf/stack.csv: column 'x' spans 2e+150 m, more than the 10 m" pipeline sf -o sfo
[ ! -e sfo ] || fail "pipeline wrote sfo after refusing the recording"
awk 'BEGIN { print "t,u,x"; for (k = 0; k < 2000; k++) printf "%g,%.17g,%.17g\n", k / 1000, 1e150 * sin(k * 0.01), 1e-6 * sin(k * 0.01 - 0.3) }' > sf/stack.csv
timed 30 2 "sf/stack.csv: column 'u' reaches 1e+150 V, more than the 100000 V" pipeline sf -o sfo

# irreducible: one answer at every scale of an input (+-1.7e308 gave MSE 0, +-1 0.485).
awk 'BEGIN { print "t,u,v"; s = 1; for (k = 0; k < 400; k++) { printf "%g,%.17g,%g\n", k / 1000, sin(k * 0.37), s; s = -s } }' > one.csv
awk 'BEGIN { print "t,u,v"; s = 1.7e308; for (k = 0; k < 400; k++) { printf "%g,%.17g,%.17g\n", k / 1000, sin(k * 0.37), s; s = -s } }' > big.csv
timed 20 0 "" irreducible --json --inputs v one.csv
grep -o '"irreducible_mse[^,]*' out.txt > mse_one.txt
timed 20 0 "" irreducible --json --inputs v big.csv
grep -o '"irreducible_mse[^,]*' out.txt > mse_big.txt
[ -s mse_one.txt ] && cmp -s mse_one.txt mse_big.txt ||
  fail "irreducible: $(cat mse_one.txt) at +-1, $(cat mse_big.txt) at +-1.7e308"

# A malformed number in the first row of a text column is an error, not a header.
for cell in 1.2.3 1e400 0x10; do
  printf '0 %s\n1 2\n2 3\n' "$cell" > f.txt
  timed 10 2 "f.txt:1:3: column 2: expected a number, found \"$cell\"" import --column u=f.txt:2 --rate 10
done
printf 'time volt\n0 1\n1 2\n' > h.txt
timed 10 0 "" import --column u=h.txt:volt --rate 10   # a header of names is still a header

# Invert with weights near the largest double: the model file is named, exit 3 (was exit 1
# naming PiParameters::thresholds[1] = inf, a field of the computed inverse).
printf '{"kind": "pi", "thresholds": [0.5, 1, 2], "weights": [1e308, 1e308, 1e308], "polynomial": [1e-6], "offset_m": 0, "initial_input_v": 0, "initial_state": [0, 0, 0], "input_min_v": 0, "input_max_v": 3}\n' > w.json
printf 't,x\n0,0\n0.01,1e-7\n0.02,2e-7\n' > ref.csv
timed 10 3 "w.json: pi model not invertible: its inverse's thresholds\[2\] = inf overflows a double" \
  hysteresis invert --model w.json ref.csv -o inv.csv
[ ! -e inv.csv ] || fail "invert wrote inv.csv after failing"

# A pipe as the recording: format sniffing must not eat its first bytes.
cat "$src/datasets/virtual/pulses.csv" | timeout 20 "$sysid" derive /dev/stdin -o piped.csv 2>err.txt ||
  fail "derive /dev/stdin from a pipe: $(cat err.txt)"
grep -q '^# generator: sysid ' piped.csv || fail "derive /dev/stdin wrote nothing"

# A legal 240-byte name is written (the staging suffix made it 'File name too long').
long=$(printf '%0240d' 0).csv
long=$(echo "$long" | cut -c1-240)
timed 10 0 "" import --column u=u.txt:1 --rate 10 -o "$long"
[ -f "$long" ] || fail "the 240-byte name was not written"
exit 0
