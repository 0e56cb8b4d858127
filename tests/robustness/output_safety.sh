#!/bin/sh
# Never lose or clobber a file (issue #29, item 1): generate refuses a user's own recording,
# -o onto a FIFO or a device writes through it and onto a link writes the file it names (never
# replacing the node), two runs at once never publish a mixed folder, Ctrl-C leaves no staging
# folder, and a write error (stdout included) is exit 2. Usage: output_safety.sh SYSID SOURCE_DIR
set -u
. "$(dirname "$0")/common.sh"
v="$src/datasets/virtual"

# generate -o DIR replaces only the files sysid wrote (the generator mark, first line).
mkdir mylab && printf 't,u,x\n0,0,0\n0.001,1,0\n' > mylab/pulses.csv
cp mylab/pulses.csv mine.csv
expect 1 "mylab/pulses.csv exists and was not written by sysid" generate pulses -o mylab
cmp -s mylab/pulses.csv mine.csv || fail "generate replaced the user's mylab/pulses.csv"
expect 1 "was not written by sysid" generate all --seed 1 -o mylab
cmp -s mylab/pulses.csv mine.csv || fail "generate all replaced the user's mylab/pulses.csv"
expect 0 "" generate pulses -o mylab --force
head -1 mylab/pulses.csv | grep -q '^# generator: sysid ' || fail "generate --force did not write"
expect 0 "" generate pulses --seed 2 -o mylab   # its own file: replaced without --force
echo "my notes" > plain
expect 1 "-o plain: exists and is not a folder" generate pulses -o plain
expect 1 "-o plain: exists and is not a folder" generate pulses -o plain --force
[ "$(cat plain)" = "my notes" ] || fail "generate -o plain changed the file"

# -o FILE replaces only a file sysid wrote (its generator mark), others with --force.
printf 't,u,x\n0,0,0\n0.001,1,0\n' > notes.csv
expect 1 "-o notes.csv: exists and was not written by sysid" excite pulses -o notes.csv
cmp -s notes.csv mine.csv || fail "excite replaced the user's notes.csv"
expect 1 "not written by sysid" derive notes.csv -o notes.csv
expect 0 "" excite pulses -o notes.csv --force
expect 0 "" excite pulses -o notes.csv   # now sysid's: replaced without --force
printf '{"a1p": 104.0154, "a1n": 117.1441, "a2p": 3.1023, "a2n": 6.8216, "a3": 6.0, "tau": 0}\n' \
  > hand.json
cp hand.json hand0.json
expect 1 "-o hand.json: exists and was not written by sysid" \
  tune-delay --model hand.json "$v/pulses.csv" -o hand.json
cmp -s hand.json hand0.json || fail "tune-delay replaced a hand-written model"
echo "my events" > ev.csv
expect 1 "--events ev.csv: exists and was not written by sysid" \
  simulate --paper-model --pulses 1 --events ev.csv -o s1.csv
[ ! -e s1.csv ] || fail "simulate wrote -o although --events was refused"
# The hysteresis writers too (they replaced any file before): a user's notes stay.
pz="$src/datasets/piezo_aye_ang/piezo.csv"
expect 0 "" hysteresis fit --model pi "$pz" -o hy.json
echo "my notes" > notes.json
cp notes.json notes0.json
expect 1 "-o notes.json: exists and was not written by sysid" \
  hysteresis fit --model pi "$pz" -o notes.json
expect 1 "-o notes.json: exists and was not written by sysid" \
  hysteresis simulate --model hy.json "$pz" -o notes.json
expect 1 "-o notes.json: exists and was not written by sysid" \
  hysteresis invert --model hy.json "$pz" -o notes.json
cmp -s notes.json notes0.json || fail "a hysteresis command replaced the user's notes.json"
expect 0 "" hysteresis fit --model pi "$pz" -o notes.json --force
# Each writer's own files are replaced without --force (their marks are recognised).
for i in 1 2; do
  expect 0 "" hysteresis fit --model pi "$pz" -o hy.json
  expect 0 "" hysteresis simulate --model hy.json "$pz" -o hy_sim.csv
  expect 0 "" identify --a3 6 "$v/pulses.csv" -o id.json
  expect 0 "" dominance --model id.json -o dom.csv "$v/test.csv"
  expect 0 "" simulate --model id.json --pulses 1 --events ev2.csv -o sim.csv
  expect 0 "" derive "$v/test.csv" -o d.csv
  expect 0 "" excite tracking --set test -o tr.csv
done

# -o onto a FIFO: written through (a reader gets the CSV), the FIFO stays a FIFO.
mkfifo f
cat f > from_fifo.txt &
reader=$!
expect 0 "" excite pulses -o f
wait $reader
[ -p f ] || fail "excite pulses -o f replaced the FIFO"
grep -q '^t,u' from_fifo.txt || fail "nothing came through the FIFO"
# Character devices: written through, never replaced (as root, -o /dev/full used to replace it).
expect 0 "" excite pulses -o /dev/null
[ -c /dev/null ] || fail "/dev/null is no longer a character device"
expect 2 "/dev/full: cannot write: No space left on device" excite pulses -o /dev/full
[ -c /dev/full ] || fail "/dev/full is no longer a character device"
# /dev/stdout writes into the shell's redirection, appending where it appends.
echo "first line" > so.txt
"$sysid" excite pulses -o /dev/stdout >> so.txt 2>err.txt || fail "-o /dev/stdout failed"
[ "$(head -1 so.txt)" = "first line" ] || fail "-o /dev/stdout clobbered an appended file"
grep -q '^t,u' so.txt || fail "-o /dev/stdout wrote nothing"
# Symbolic links are followed: the file they name is replaced, the link stays a link.
expect 0 "" excite pulses -o target.csv
ln -s target.csv link.csv
expect 0 "" excite pulses --rate 500 -o link.csv
[ -L link.csv ] || fail "the link was replaced"
grep -q '^# sample_rate_hz: 500' target.csv || fail "the linked file was not written"
ln -s missing.csv dangling.csv
expect 1 "a symbolic link to a missing file" excite pulses -o dangling.csv
[ -L dangling.csv ] && [ ! -e missing.csv ] || fail "the dangling link changed"
ln -s loop.csv loop.csv
expect 1 "in a loop" excite pulses -o loop.csv
mkdir adir
expect 1 "exists and is a folder" excite pulses -o adir

# Write errors on standard output: exit 2 with the reason, not 0.
"$sysid" derive "$v/pulses.csv" > /dev/full 2>err.txt; rc=$?
[ "$rc" -eq 2 ] || fail "derive > /dev/full exited $rc, expected 2"
grep -q "cannot write to standard output: No space left on device" err.txt ||
  fail "derive > /dev/full: no reason given"
"$sysid" excite pulses > /dev/full 2>err.txt; rc=$?
[ "$rc" -eq 2 ] || fail "excite pulses > /dev/full exited $rc, expected 2"

# Two runs at once into one new folder: one publishes, the other refuses (exit 2, or exit 1 when
# it started after the first had published); the folder holds one run's files only.
concurrent() {  # concurrent DIR ARGS-A -- ARGS-B
  dir=$1; shift
  a=""; while [ "$1" != "--" ]; do a="$a $1"; shift; done; shift
  # shellcheck disable=SC2086
  "$sysid" $a >a.out 2>a.err & pa=$!
  "$sysid" "$@" >b.out 2>b.err & pb=$!
  wait $pa; ra=$?; wait $pb; rb=$?
  [ "$ra" -eq 0 ] || [ "$rb" -eq 0 ] || { cat a.err b.err >&2; fail "$dir: neither run published"; }
  for r in "$ra:a" "$rb:b"; do
    case "${r%%:*}" in
      0) ;;
      2) grep -q "changed while this run worked" "${r#*:}.err" || fail "$dir: no reason on exit 2" ;;
      # A fast run may publish before the other starts: that one then finds sysid's folder.
      1) grep -q "pass --force to replace it" "${r#*:}.err" || fail "$dir: exit 1 without reason" ;;
      *) cat "${r#*:}.err" >&2; fail "$dir: a run exited ${r%%:*}" ;;
    esac
  done
  ls -a | grep -q "^\.$dir\.tmp" && fail "$dir: a staging folder was left"
  return 0
}
mkdir D && cp "$v/pulses.csv" "$v/training.csv" "$v/test.csv" D/
concurrent rep pipeline D -o rep --a3 5 --hidden 2 --max-epochs 3 --no-typical --no-track \
  --no-delay -- pipeline D -o rep --a3 6 --hidden 3 --max-epochs 3 --no-typical --no-track \
  --no-delay
a3=$(sed -n 's/.*"a3": *\([0-9.e+-]*\).*/\1/p' rep/model.json | head -1)
hidden=$(sed -n 's/.*"hidden": *\([0-9]*\).*/\1/p' rep/nn.json | head -1)
case "$a3:$hidden" in
  5*:2|6*:3) ;;
  *) fail "rep mixes two runs: model.json a3 = $a3, nn.json hidden = $hidden" ;;
esac
# Both replacing the folder an earlier run wrote (--force): still one run's files.
concurrent rep pipeline D -o rep --force --a3 5 --hidden 2 --max-epochs 3 --no-typical \
  --no-track --no-delay -- pipeline D -o rep --force --a3 6 --hidden 3 --max-epochs 3 \
  --no-typical --no-track --no-delay
a3=$(sed -n 's/.*"a3": *\([0-9.e+-]*\).*/\1/p' rep/model.json | head -1)
hidden=$(sed -n 's/.*"hidden": *\([0-9]*\).*/\1/p' rep/nn.json | head -1)
case "$a3:$hidden" in
  5*:2|6*:3) ;;
  *) fail "rep (replaced) mixes two runs: model.json a3 = $a3, nn.json hidden = $hidden" ;;
esac
ls -a | grep -q '\.old$' && fail "a moved-aside folder was left"
concurrent T excite tracking --set training -o T -- excite tracking --set test -o T
if ls T | grep -q training; then ls T | grep -q test && fail "T mixes the training and test sets"; fi

# Ctrl-C (and SIGTERM, SIGHUP) removes the staging folder.
for sig in INT TERM HUP; do
  for t in 0.02 0.05 0.1 0.2 0.4; do
    rm -rf T2
    timeout --preserve-status -s $sig $t "$sysid" excite tracking -o T2 >/dev/null 2>&1
    ls -a | grep -q '^\.T2\.tmp' && fail "SIG$sig after $t s left a staging folder"
  done
done
rm -rf rep2
timeout --preserve-status -s INT 1 "$sysid" pipeline D -o rep2 --hidden 2 --max-epochs 3 \
  >/dev/null 2>&1
ls -a | grep -q '^\.rep2\.tmp' && fail "an interrupted pipeline left a staging folder"
echo "ok: no file lost or clobbered"
