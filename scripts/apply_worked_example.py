#!/usr/bin/env python3
"""Applies docs/architecture.md's worked example ("Adding a field is one edit plus its doc
line") to a copy of the header it edits, so a test can build against the edited struct and
check what the doc promises. Usage: apply_worked_example.py SOURCE_DIR OUT_DIR

Writes OUT_DIR/sysid/delay.hpp: libsysid/include/sysid/delay.hpp with the example's member line
placed after DelayTuningOptions' last field and its Visit line at the end of its Serialize.
Exits 1, naming the doc's line, when the example no longer applies."""
import pathlib
import sys

MARK = "Adding a field is one edit plus its doc line."


def fail(where, what):
    print(f"{where}: {what}", file=sys.stderr)
    sys.exit(1)


def example_lines(doc):
    lines = doc.read_text().splitlines()
    start = next((i for i, l in enumerate(lines) if l.startswith(MARK)), None)
    if start is None:
        fail(doc, f"no paragraph starting '{MARK}'")
    fence = next((i for i in range(start, len(lines)) if lines[i].startswith("```cpp")), None)
    end = next((i for i in range(fence + 1, len(lines)) if lines[i].startswith("```")), None)
    block = lines[fence + 1:end]
    member = block[0]
    visits = [l for l in block if "a->Visit(" in l]
    if "///<" not in member:
        fail(f"{doc}:{fence + 2}", "the example's first line is not a member with its doc")
    if len(visits) != 1:
        fail(f"{doc}:{fence + 1}", "the example needs exactly one a->Visit(...) line")
    return member, visits[0]


def main():
    src, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
    member, visit = example_lines(src / "docs/architecture.md")
    header = src / "libsysid/include/sysid/delay.hpp"
    lines = header.read_text().splitlines()
    try:
        first = lines.index("struct DelayTuningOptions {")
        serialize = next(i for i in range(first, len(lines))
                         if lines[i].strip() == "template <class Archive>")
        body = serialize + 2  # "void Serialize(Archive* a) {" is the next line
        close = next(i for i in range(body, len(lines)) if lines[i] == "  }")
    except (ValueError, StopIteration):
        fail(header, "DelayTuningOptions' Serialize is not where the worked example expects it")
    # The member goes before the fields' comment ("/// The fields, ...") that precedes Serialize.
    at = serialize - 1 if lines[serialize - 1].lstrip().startswith("///") else serialize
    edited = lines[:at] + [member] + lines[at:close] + [visit] + lines[close:]
    target = out / "sysid" / "delay.hpp"
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_text("\n".join(edited) + "\n")


if __name__ == "__main__":
    main()
