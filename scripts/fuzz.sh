#!/bin/sh
# Longer fuzzing of the CSV and JSON readers with libFuzzer (clang from Debian), under
# ASan/UBSan, seeded with the bundled files (issue #14). CI runs the short deterministic
# mutation step instead (ctest -L fuzz).
#   scripts/fuzz.sh [SECONDS_PER_TARGET]     (default 150: ten minutes for the four readers)
set -eu
seconds=${1:-150}
root=$(cd "$(dirname "$0")/.." && pwd)
build="$root/build-fuzz"
flags="-fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer"
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DSYSID_FUZZ=ON -DSYSID_BUILD_BENCH=OFF -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
cmake --build "$build" -j"${SYSID_JOBS:-2}" --target fuzz_csv fuzz_model fuzz_network fuzz_stage
d="$root/datasets"
for target in csv model network stage; do
  corpus="$build/corpus_$target"
  mkdir -p "$corpus"
  case $target in
    csv) cp "$d/virtual/waveform_square.csv" "$d/paper/pulse_table.csv" "$root/fuzz/corpus/small.csv" "$corpus/" ;;
    model) cp "$root/fuzz/corpus/model.json" "$corpus/" ;;
    network) cp "$d/paper/nn24.json" "$corpus/" ;;
    stage) cp "$d/virtual/stage.json" "$corpus/" ;;
  esac
  echo "fuzz.sh: $target for $seconds s"
  (cd "$build" && "./fuzz/fuzz_$target" -max_total_time="$seconds" -max_len=65536 "$corpus")
done
