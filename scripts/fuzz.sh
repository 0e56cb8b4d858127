#!/bin/sh
# Fuzzing of the CSV and JSON readers with libFuzzer (Debian's clang), under ASan/UBSan, seeded
# with the bundled files. CI's third stage runs `scripts/fuzz.sh 15 build-asan` (a minute for
# the four readers); the default is the longer run (150 s per target: ten minutes in all).
#   scripts/fuzz.sh [SECONDS_PER_TARGET] [BUILD_DIR]     (BUILD_DIR default: build-fuzz)
# Exits non-zero when a target crashes, leaks, hits undefined behaviour or hangs (> 10 s on one
# input); libFuzzer then writes the input as crash-*/leak-*/timeout-* in BUILD_DIR.
set -eu
seconds=${1:-150}
root=$(cd "$(dirname "$0")/.." && pwd)
build=${2:-"$root/build-fuzz"}
case $seconds in ''|*[!0-9]*) echo "fuzz.sh: SECONDS must be a whole number, got '$seconds'" >&2; exit 1 ;; esac
command -v clang++ >/dev/null || { echo "fuzz.sh: needs clang++ (scripts/setup.sh installs it)" >&2; exit 1; }
# -fno-sanitize-recover: undefined behaviour aborts (and so fails the run) instead of printing.
flags="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
# A build folder already configured for fuzzing (CI's sanitizer pass, `scripts/test.sh
# --sanitize`: clang, ASan + UBSan, libFuzzer's coverage hooks) is used as it is: one build
# serves both.
if ! grep -q '^SYSID_FUZZ:BOOL=ON' "$build/CMakeCache.txt" 2>/dev/null; then
  CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DSYSID_FUZZ=ON -DSYSID_BUILD_BENCH=OFF -DCMAKE_CXX_FLAGS="$flags" \
    -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
fi
# The MAT and HDF5 targets are not in the default list: libhdf5 (behind HDF5 and MAT v7.3 files)
# allocates and fills sizes a file declares before sysid can bound them (4 GB of RSS from a 64 KB
# input, inside H5C_protect), so libFuzzer's RSS limit stops a run there at random. Their
# deterministic mutation runs are CTest tests ("fuzz: mat|hdf5 reader") in both CI passes; run
# these targets by hand with SYSID_FUZZ_TARGETS="mat hdf5" scripts/fuzz.sh.
targets=${SYSID_FUZZ_TARGETS:-csv model network stage}
# shellcheck disable=SC2086
cmake --build "$build" -j"${SYSID_JOBS:-2}" --target $(printf 'fuzz_%s ' $targets)
d="$root/datasets"
for target in $targets; do
  corpus="$build/corpus_$target"
  mkdir -p "$corpus"
  case $target in
    csv) cp "$d/virtual/waveform_square.csv" "$d/paper/pulse_table.csv" "$root/fuzz/corpus/small.csv" "$corpus/" ;;
    model) cp "$root/fuzz/corpus/model.json" "$corpus/" ;;
    network) cp "$d/paper/nn24.json" "$corpus/" ;;
    stage) cp "$d/virtual/stage.json" "$corpus/" ;;
    mat) cp "$root"/fuzz/corpus/*.mat "$corpus/" ;;
    hdf5) cp "$root"/fuzz/corpus/*.h5 "$corpus/" ;;
  esac
  echo "fuzz.sh: $target for $seconds s (log: $build/fuzz_$target.log)"
  # A crash, leak, UB report, hang or memory blow-up makes libFuzzer exit non-zero: the log's
  # end (the report and the input's file name) is shown and the script fails. SYSID_FUZZ_FLAGS
  # adds libFuzzer flags (e.g. -jobs=2, -dict=...).
  # shellcheck disable=SC2086
  # libmatio allocates what a MAT file declares (a variable's size, a name's length) before
  # sysid sees the variable: under the fuzzer a declared 8 GB is a "malloc limit" report in
  # matio, not a bug of ours. With allocator_may_return_null matio gets NULL, as malloc gives a
  # real program for an impossible size, and the reader reports the file as malformed; the RSS
  # limit still catches memory that is really used.
  # libhdf5 (behind HDF5 and MAT v7.3 files) may keep allocations of a file it failed to
  # open: suppressed for that library only (fuzz/third_party_leaks.supp).
  extra_asan="" extra_flags=""
  if [ "$target" = mat ] || [ "$target" = hdf5 ]; then
    extra_asan=":allocator_may_return_null=1"
    extra_flags="-malloc_limit_mb=1048576"
  fi
  # shellcheck disable=SC2086
  if ! (cd "$build" && ASAN_OPTIONS="detect_leaks=1$extra_asan" \
          LSAN_OPTIONS="suppressions=$root/fuzz/third_party_leaks.supp" "./fuzz/fuzz_$target" $extra_flags \
          -max_total_time="$seconds" -max_len=65536 -timeout=10 -rss_limit_mb=4096 \
          -print_final_stats=1 ${SYSID_FUZZ_FLAGS:-} "$corpus" >"fuzz_$target.log" 2>&1); then
    tail -n 60 "$build/fuzz_$target.log" >&2
    echo "fuzz.sh: FAILED: fuzz_$target found a crash (see above; inputs in $build)" >&2
    exit 1
  fi
  grep -E '^stat::(number_of_executed_units|peak_rss_mb)' "$build/fuzz_$target.log" || true
done
echo "fuzz.sh: no crash in $seconds s per reader"
