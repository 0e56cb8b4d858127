#!/usr/bin/env bash
# Mutation check (issue #30): applies each hand-picked mutant of a core formula listed in
# scripts/mutants.txt to a scratch copy of the tree, rebuilds (ccache) only the test targets
# that should catch it, runs the named tests and prints a table (mutant, killed by which test,
# seconds). Fails when a mutant survives, does not build, or the unmutated tree fails its tests.
#
#   scripts/mutants.sh [--subset ci|all] [--only ID[,ID...]] [--list FILE] [--keep] [--markdown]
#
#   --subset ci   the fixed fast subset (mutants marked "ci"); default: all
#   --only        just these mutant ids
#   --list FILE   another mutant list (default scripts/mutants.txt)
#   --keep        keep the scratch folder (printed) instead of removing it
#   --markdown    print the table as Markdown (docs/testing.md's table)
#
# Environment: SYSID_JOBS (build and test jobs, default: number of cores); SYSID_MUTANT_DIR
# (parent of the scratch folder, default $TMPDIR or /tmp); SYSID_MUTANT_CMAKE_ARGS (extra
# configure arguments; the default configuration is the README's Release build without Python
# and benchmarks, with SYSID_WERROR as in the user's build/ so that ccache finds its
# objects). The user's tree and build folders are never written: everything happens in the
# scratch copy (tracked and untracked, non-ignored files, so uncommitted work is included).
set -euo pipefail
# The whole script is one block: bash reads it completely before running, so editing this file
# during a run cannot change the running one.
{
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
LIST="$ROOT/scripts/mutants.txt"
SUBSET=all
ONLY=""
KEEP=0
MARKDOWN=0
while (($#)); do
  case "$1" in
    --subset) SUBSET="${2:?--subset needs ci or all}"; shift 2 ;;
    --only) ONLY="${2:?--only needs mutant ids}"; shift 2 ;;
    --list) LIST="${2:?--list needs a file}"; shift 2 ;;
    --keep) KEEP=1; shift ;;
    --markdown) MARKDOWN=1; shift ;;
    -h|--help) sed -n '2,20p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "mutants.sh: unknown argument '$1' (see --help)" >&2; exit 1 ;;
  esac
done
case "$SUBSET" in ci|all) ;; *) echo "mutants.sh: --subset must be ci or all, got '$SUBSET'" >&2; exit 1 ;; esac
[ -f "$LIST" ] || { echo "mutants.sh: no mutant list $LIST" >&2; exit 1; }
JOBS="${SYSID_JOBS:-$(nproc)}"

# One scratch folder per clone, at a fixed path: the tests' objects carry the source path
# (SYSID_SOURCE_DIR), so only a repeated path lets ccache find them on the next run.
SCRATCH="${SYSID_MUTANT_DIR:-${TMPDIR:-/tmp}}/sysid-mutants-$(printf '%s' "$ROOT" | md5sum | cut -c1-8)"
if ! mkdir "$SCRATCH" 2>/dev/null; then
  echo "mutants.sh: $SCRATCH exists: another run of this clone, or a kept one (remove it)" >&2
  exit 1
fi
cleanup() { if [ "$KEEP" = 1 ]; then echo "scratch kept: $SCRATCH" >&2; else rm -rf "$SCRATCH"; fi; }
trap cleanup EXIT
SRC="$SCRATCH/src"
BUILD="$SRC/build"
LOGS="$SCRATCH/logs"
mkdir -p "$SRC" "$LOGS"

# The selected mutants, checked (seven fields, unique ids, original text found exactly once),
# as one TSV file the loop below reads.
SELECTED="$SCRATCH/selected.tsv"
python3 - "$LIST" "$ROOT" "$SUBSET" "$ONLY" "$SELECTED" <<'PY'
import sys
path, root, subset, only, out = sys.argv[1:6]
wanted = set(filter(None, only.split(",")))
rows, ids, errors = [], set(), []
for no, line in enumerate(open(path, encoding="utf-8"), 1):
    line = line.rstrip("\n")
    if not line.strip() or line.startswith("#"):
        continue
    f = line.split("\t")
    if len(f) != 7:
        errors.append(f"{path}:{no}: expected 7 tab-separated fields, found {len(f)}")
        continue
    mid, sub, file, orig, repl = f[:5]
    if mid in ids:
        errors.append(f"{path}:{no}: duplicate mutant id '{mid}'")
    ids.add(mid)
    if sub not in ("ci", "all"):
        errors.append(f"{path}:{no}: subset must be ci or all, found '{sub}'")
    try:
        count = open(f"{root}/{file}", encoding="utf-8").read().count(orig)
    except OSError as e:
        errors.append(f"{path}:{no}: {file}: {e.strerror}")
        continue
    if count != 1:
        errors.append(f"{path}:{no}: mutant '{mid}': the original text occurs {count} times in "
                      f"{file}, expected exactly once")
    if orig == repl:
        errors.append(f"{path}:{no}: mutant '{mid}': replacement equals the original")
    if (subset == "all" or sub == "ci") and (not wanted or mid in wanted):
        rows.append(line)
for w in wanted - ids:
    errors.append(f"--only: no mutant '{w}' in {path}")
if errors:
    sys.exit("\n".join(errors))
if not rows:
    sys.exit("mutants.sh: no mutant selected")
open(out, "w", encoding="utf-8").write("\n".join(rows) + "\n")
PY
COUNT=$(wc -l < "$SELECTED")

# Scratch copy of the working tree (what git would see: tracked and untracked, not ignored).
if git -C "$ROOT" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  (cd "$ROOT" && git ls-files -z --cached --others --exclude-standard |
    python3 -c 'import os,sys; sys.stdout.buffer.write(b"\0".join(p for p in sys.stdin.buffer.read().split(b"\0") if p and os.path.isfile(p)))' |
    tar --null -T - -cf -) | tar -C "$SRC" -xf -
else
  (cd "$ROOT" && tar --exclude='./build*' -cf - .) | tar -C "$SRC" -xf -
fi

# ccache: with the base directory at the scratch folder, compile commands use paths relative to
# it, as the user's build (base_dir above the tree) does, so unchanged objects are cache hits.
export CCACHE_BASEDIR="$SCRATCH"
TARGETS=$(cut -f6 "$SELECTED" | tr ',' '\n' | sort -u | tr '\n' ' ')
# The tests' regexes joined into as few ctest -R runs as CMake's regular expressions allow (at
# most 9 groups each: more fail to compile and would select no test).
REGEX_CHUNKS=$(cut -f7 "$SELECTED" | sort -u | awk '{
  n = gsub(/\(/, "(")
  if (cur != "" && groups + n > 9) { print cur; cur = ""; groups = 0 }
  cur = (cur == "" ? $0 : cur "|" $0); groups += n
} END { if (cur != "") print cur }')
start_all=$(date +%s)
echo "mutants.sh: $COUNT mutants ($SUBSET), scratch $SCRATCH; building $TARGETS" >&2
# Warnings as errors as in the user's build/ (read, never written), so its objects are hits.
WERROR=OFF
if grep -q '^SYSID_WERROR:BOOL=ON' "$ROOT/build/CMakeCache.txt" 2>/dev/null; then WERROR=ON; fi
# The Python bindings only for a mutant of theirs (target _sysid, killed by a python: test).
PYTHON=OFF
case " $TARGETS " in *" _sysid "*) PYTHON=ON ;; esac
# shellcheck disable=SC2086
cmake -S "$SRC" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DSYSID_PYTHON=$PYTHON \
  -DSYSID_BUILD_BENCH=OFF -DSYSID_WERROR=$WERROR ${SYSID_MUTANT_CMAKE_ARGS:-} \
  >"$LOGS/configure.log" 2>&1 ||
  { cat "$LOGS/configure.log" >&2; echo "mutants.sh: configure failed" >&2; exit 2; }
build() {  # build the given targets, log to $1
  local log="$1"; shift
  local args=()
  for t in "$@"; do args+=(--target "$t"); done
  cmake --build "$BUILD" -j "$JOBS" "${args[@]}" >"$log" 2>&1
}
# shellcheck disable=SC2086
build "$LOGS/baseline-build.log" $TARGETS ||
  { tail -40 "$LOGS/baseline-build.log" >&2; echo "mutants.sh: the unmutated tree does not build" >&2; exit 2; }
# The unmutated tree must pass every test named, or a "kill" would mean nothing.
baseline_failed=0
: >"$LOGS/baseline-tests.log"
while IFS= read -r chunk; do
  ctest --test-dir "$BUILD" -R "$chunk" -j "$JOBS" --no-tests=error >>"$LOGS/baseline-tests.log" 2>&1 ||
    { baseline_failed=1; break; }
done <<<"$REGEX_CHUNKS"
if [ "$baseline_failed" = 1 ]; then
  tail -30 "$LOGS/baseline-tests.log" >&2
  echo "mutants.sh: the unmutated tree fails the listed tests" >&2
  exit 2
fi
baseline_tests=$(grep -c "Test *#" "$LOGS/baseline-tests.log" || true)
echo "mutants.sh: baseline builds and passes $baseline_tests tests in $(( $(date +%s) - start_all )) s" >&2

RESULTS="$SCRATCH/results.tsv"
: >"$RESULTS"
failed=0
i=0
while IFS=$'\t' read -r -u 3 id subset file original replacement targets regex; do
  i=$((i + 1))
  t0=$(date +%s)
  cp "$SRC/$file" "$SCRATCH/original"
  python3 - "$SRC/$file" "$original" "$replacement" <<'PY'
import sys
path, orig, repl = sys.argv[1:4]
text = open(path, encoding="utf-8").read()
assert text.count(orig) == 1, f"{path}: original text not found exactly once"
open(path, "w", encoding="utf-8").write(text.replace(orig, repl))
PY
  status=killed
  killer=""
  # shellcheck disable=SC2046
  if ! build "$LOGS/$id-build.log" $(echo "$targets" | tr ',' ' '); then
    status="does not build"
  else
    rm -f "$BUILD/Testing/Temporary/LastTestsFailed.log"
    if ctest --test-dir "$BUILD" -R "$regex" -j "$JOBS" --stop-on-failure --no-tests=error \
        >"$LOGS/$id-tests.log" 2>&1; then
      status=SURVIVED
    else
      killer=$(sed -n '1s/^[0-9]*://p' "$BUILD/Testing/Temporary/LastTestsFailed.log" 2>/dev/null || true)
      [ -n "$killer" ] || killer="(ctest failed: see $id-tests.log)"
    fi
  fi
  # Restore with a fresh time stamp, so the next build recompiles the original (a cache hit).
  cat "$SCRATCH/original" >"$SRC/$file"
  secs=$(( $(date +%s) - t0 ))
  [ "$status" = killed ] || failed=1
  printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$id" "$subset" "$file" "$status" "${killer:--}" "$secs" >>"$RESULTS"
  printf 'mutants.sh: [%d/%d] %s: %s %s (%d s)\n' "$i" "$COUNT" "$id" "$status" "$killer" "$secs" >&2
done 3<"$SELECTED"
total=$(( $(date +%s) - start_all ))

if [ "$MARKDOWN" = 1 ]; then
  echo "| mutant | subset | file | result | killed by | s |"
  echo "|---|---|---|---|---|---|"
  awk -F'\t' '{gsub(/\|/, "\\|", $5); printf "| %s | %s | `%s` | %s | %s | %s |\n", $1, $2, $3, $4, $5, $6}' "$RESULTS"
else
  awk -F'\t' 'BEGIN {printf "%-28s %-4s %-10s %5s  %s\n", "mutant", "set", "result", "s", "killed by"}
              {printf "%-28s %-4s %-10s %5s  %s\n", $1, $2, $4, $6, $5}' "$RESULTS"
fi
killed=$(awk -F'\t' '$4 == "killed"' "$RESULTS" | wc -l)
echo "mutants.sh: $killed of $COUNT mutants killed; total $total s (baseline build and tests included)"
if [ "$failed" != 0 ]; then
  echo "mutants.sh: FAILED: a mutant survived or did not build (logs: --keep)" >&2
  exit 1
fi
exit 0
}
