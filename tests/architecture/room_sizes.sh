#!/bin/sh
# Small rooms (docs/architecture.md): the size check passes on the tree, and on seeded trees it
# fails, naming file and line, exactly at the limits (a file of 501 lines, a function of 101)
# and passes one line below them or where the room says why.
# Usage: room_sizes.sh SOURCE_DIR
set -eu
src=$1
check="$src/scripts/check_sizes.py"
python3 "$check" --root "$src"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# A tree holding the one file $2 with the text on stdin; runs the check on it into $tmp/out.
seed() {
  rm -rf "$tmp/tree" && mkdir -p "$tmp/tree/libsysid/src/m" "$tmp/tree/apps" "$tmp/tree/python/src"
  cat > "$tmp/tree/$1"
  python3 "$check" --root "$tmp/tree" > "$tmp/out" 2>&1
}
lines() { i=0; while [ $i -lt "$1" ]; do echo "int v$i = $i;"; i=$((i + 1)); done; }
# A function whose body (opening to closing brace) spans $1 lines; `}` in a string and a
# comment inside it must not end it.
function_of() {
  echo "int F(int a) {"
  echo "  const char* s = \"}\";  // }"
  i=3; while [ $i -lt "$1" ]; do echo "  a += $i;"; i=$((i + 1)); done
  echo "}"
}
pass() { seed "$1" || { echo "FAIL: $2 was refused:"; cat "$tmp/out"; exit 1; }; }
fail() {
  if seed "$1"; then echo "FAIL: $2 passed the check"; cat "$tmp/out"; exit 1; fi
  grep -q "^$1:$3: $4" "$tmp/out" || { echo "FAIL: $2 is not named as $1:$3:"; cat "$tmp/out"; exit 1; }
}

lines 500 | pass libsysid/src/m/a.cpp "a file of 500 lines"
lines 501 | fail libsysid/src/m/a.cpp "a file of 501 lines" 1 "file of 501 lines, over 500"
{ echo "// A table read top to bottom."; echo "// Long file: one table"; lines 600; } |
  pass apps/a.cpp "a long file with its reason"
{ lines 10; echo "// Long file: too late, below the code"; lines 600; } |
  fail apps/a.cpp "a reason below the file's top comment" 1 "file of 611 lines"
function_of 100 | pass python/src/f.cpp "a function of 100 lines"
{ echo "// F."; function_of 101; } |
  fail python/src/f.cpp "a function of 101 lines" 2 "function of 101 lines, over 100"
{ echo "// Long function: emitted in reading order"; echo "// F."; function_of 101; } |
  pass libsysid/src/m/f.hpp "a long function with its reason"
echo "ok: rooms over the limit are named, rooms at it or with a reason pass"
