"""Compares the golden outputs value by value: tests/golden/golden.sh calls it.

"The same" means: every key of the expected file is present (new keys are allowed), arrays
have the same length, strings and booleans are equal, and numbers agree to a relative
tolerance (GOLDEN_RTOL, default 1e-9: the redesign moves code, not arithmetic; a sanitizer
build's different instruction selection stays well inside it). Keys in VOLATILE (the version
stamp) and wall times (keys ending in "time_s") are not compared. Every difference is printed with its file and key path.
"""
import json
import math
import os
import sys

VOLATILE = {"_generator"}


def compare(expected, actual, path, out):
    if isinstance(expected, dict):
        if not isinstance(actual, dict):
            out.append("%s: expected an object, found %s" % (path, type(actual).__name__))
            return
        for key, value in expected.items():
            if key in VOLATILE or key.endswith("time_s"):
                continue
            if key not in actual:
                out.append("%s.%s: missing" % (path, key))
                continue
            compare(value, actual[key], "%s.%s" % (path, key), out)
    elif isinstance(expected, list):
        if not isinstance(actual, list) or len(actual) != len(expected):
            out.append("%s: expected an array of %d, found %s" % (
                path, len(expected),
                "%d" % len(actual) if isinstance(actual, list) else type(actual).__name__))
            return
        for i, (e, a) in enumerate(zip(expected, actual)):
            compare(e, a, "%s[%d]" % (path, i), out)
    elif isinstance(expected, bool) or expected is None or isinstance(expected, str):
        if actual != expected:
            out.append("%s: expected %r, found %r" % (path, expected, actual))
    else:
        if isinstance(actual, bool) or not isinstance(actual, (int, float)):
            out.append("%s: expected the number %r, found %r" % (path, expected, actual))
            return
        rtol = float(os.environ.get("GOLDEN_RTOL", "1e-9"))
        if not math.isclose(actual, expected, rel_tol=rtol, abs_tol=0.0):
            out.append("%s: expected %r, found %r" % (path, expected, actual))


def main(expected_dir, actual_dir):
    names = sorted(n for n in os.listdir(expected_dir) if n.endswith(".json"))
    if not names:
        sys.exit("golden: no expected files in %s" % expected_dir)
    failures = []
    for name in names:
        actual_path = os.path.join(actual_dir, name)
        if not os.path.exists(actual_path):
            failures.append("%s: not written" % name)
            continue
        with open(os.path.join(expected_dir, name)) as f:
            expected = json.load(f)
        with open(actual_path) as f:
            actual = json.load(f)
        compare(expected, actual, name, failures)
    for line in failures:
        print("golden: " + line)
    print("golden: %d files, %d differences" % (len(names), len(failures)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
