#!/bin/sh
# The module graph check passes on the tree (sources and docs/architecture.md) and fails, naming
# file and line, on a seeded cycle (a copy of the tree where signal includes identification,
# which includes signal).
# Usage: module_graph.sh SOURCE_DIR
set -eu
src=$1
python3 "$src/scripts/check_modules.py" --root "$src"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/libsysid"
cp -R "$src/libsysid/src" "$src/libsysid/include" "$tmp/libsysid/"
printf '#include "sysid/identify.hpp"\n' >> "$tmp/libsysid/src/signal/checks.cpp"
if python3 "$src/scripts/check_modules.py" --root "$tmp" 2> "$tmp/err"; then
  echo "FAIL: a seeded cycle signal -> identify -> signal passed the check"; exit 1
fi
grep -q "libsysid/src/signal/checks.cpp:[0-9]*: module 'signal' includes sysid/identify.hpp of module 'identify', which is above it" "$tmp/err" \
  || { echo "FAIL: the violation does not name file, line and modules:"; cat "$tmp/err"; exit 1; }
echo "ok: the seeded cycle is reported"

# The architecture doc is checked against the sources: a graph row edited by hand fails, naming
# the doc's line.
rm -rf "$tmp/libsysid" && mkdir -p "$tmp/libsysid" "$tmp/docs"
cp -R "$src/libsysid/src" "$src/libsysid/include" "$tmp/libsysid/"
sed 's/^| nn | \(.*\) |$/| nn | \1, stage |/' "$src/docs/architecture.md" > "$tmp/docs/architecture.md"
if python3 "$src/scripts/check_modules.py" --root "$tmp" 2> "$tmp/err"; then
  echo "FAIL: a graph table that differs from the sources passed the check"; exit 1
fi
grep -q "docs/architecture.md:[0-9]*: the graph table reads '| nn | .*, stage |'" "$tmp/err" \
  || { echo "FAIL: the doc drift is not named with its line:"; cat "$tmp/err"; exit 1; }
echo "ok: a drifted architecture doc is reported"

# The report formats what the pipeline computed: a read or a simulation planted in report/
# fails, naming file, line and call.
rm -rf "$tmp/libsysid" "$tmp/docs" && mkdir -p "$tmp/libsysid"
cp -R "$src/libsysid/src" "$src/libsysid/include" "$tmp/libsysid/"
printf 'static auto planted = [](const sysid::FrictionModel& m, const sysid::Recording& r) {\n  return sysid::SimulateRecording(m, r);\n};\n' \
  >> "$tmp/libsysid/src/report/stack_report.cpp"
if python3 "$src/scripts/check_modules.py" --root "$tmp" 2> "$tmp/err"; then
  echo "FAIL: a simulation planted in report/ passed the check"; exit 1
fi
grep -q "libsysid/src/report/stack_report.cpp:[0-9]*: report/ calls SimulateRecording" "$tmp/err" \
  || { echo "FAIL: the planted call is not named with its line:"; cat "$tmp/err"; exit 1; }
echo "ok: a simulation in report/ is reported"
