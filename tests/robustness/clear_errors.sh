#!/bin/sh
# Errors that were internal or vague (issue #29, item 4): a symbolic link loop in a pipeline
# folder, the file line of a sampling error, duplicate JSON keys, bytes after the JSON text,
# and a bad manifest value: each exit 2 with FILE:LINE(:COL). Usage: clear_errors.sh SYSID SRC
set -u
. "$(dirname "$0")/common.sh"
v="$src/datasets/virtual"

# A link loop among a pipeline folder's recordings: exit 2 naming it (was exit 4).
mkdir D && cp "$v/pulses.csv" "$v/training.csv" "$v/test.csv" D/
ln -s pulses_2.csv D/pulses_2.csv
expect 2 "D/pulses_2.csv: cannot read: Too many levels of symbolic links (a symbolic link loop)" \
  pipeline D -o rep
# The pipeline's input itself a link loop: a usage error naming it (CLI11's path check).
ln -s loopdir loopdir
expect 1 "loopdir" pipeline loopdir -o rep
[ ! -e rep ] || fail "a refused pipeline wrote rep"

# Irregular sampling names the file line (the generator mark, 12 metadata lines, control_rate_hz
# among them, and the header come first): a 1 s jump after data row 3000 (0-based) is the
# interval ending at line 3015.
awk -F, 'BEGIN{OFS=","} /^[0-9-]/{n++; if (n > 3000) $1 = $1 + 1} {print}' "$v/pulses.csv" \
  > r_gap.csv
expect 2 "r_gap.csv:3015: irregular sampling" derive r_gap.csv
"$sysid" info r_gap.csv > info.txt 2>&1
grep -q "interval ending at r_gap.csv:3015" info.txt || fail "info: no file line in the warning"

# Duplicate keys: an error naming both positions (nlohmann keeps the last one silently).
printf '{"a1p": 104, "a1n": 117, "a2p": 3.1, "a2n": 6.8, "a3": 6,\n "a1p": 1, "tau": 0}\n' > dup.json
expect 2 "dup.json:2:2: duplicate key 'a1p' (first at 1:2)" simulate --model dup.json -o s.csv
# Bytes after the JSON text, a NUL first (nlohmann stops reading at a NUL).
printf '{"a1p": 104, "a1n": 117, "a2p": 3.1, "a2n": 6.8, "a3": 6, "tau": 0}\0{"a3": 60}' > nul.json
expect 2 "nul.json:1:68: unexpected a NUL byte after the JSON text" simulate --model nul.json -o s.csv
printf '{"a1p": 104, "a1n": 117, "a2p": 3.1, "a2n": 6.8, "a3": 6, "tau": 0}\n\n}' > extra.json
expect 2 "extra.json:3:1" simulate --model extra.json -o s.csv
[ ! -e s.csv ] || fail "a refused model file gave output"

# Manifest values: FILE:LINE:COL and exit 2 (a bad a3 used to exit 1 with no position).
mkdir M && cp "$v/pulses.csv" "$v/training.csv" "$v/test.csv" M/
printf '{"pulses": ["pulses.csv"], "training": "training.csv", "test": "test.csv",\n "a3": -5}\n' \
  > M/manifest.json
expect 2 "M/manifest.json:2:2: a3: expected a number > 0, found -5" pipeline M -o rep
printf '{"pulses": "pulses.csv", "training": "training.csv", "test": "test.csv"}\n' \
  > M/manifest.json
expect 2 "M/manifest.json:1:2: pulses: expected an array" pipeline M -o rep
printf '{"pulses": ["pulses.csv"], "training": "training.csv", "test": "test.csv", "tset": 1}\n' \
  > M/manifest.json
expect 2 "M/manifest.json:1:76: unknown key 'tset'" pipeline M -o rep
echo "ok: every error positioned, none internal"
