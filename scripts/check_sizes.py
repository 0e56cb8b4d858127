#!/usr/bin/env python3
"""Small rooms: no source file over 500 lines and no function over 100 lines in libsysid/src,
apps and python/src, unless the code says why (docs/architecture.md, "Small rooms").

  scripts/check_sizes.py             check; exit 1, naming FILE:LINE, on a room too large
  scripts/check_sizes.py --list      print every file and function over its limit, with or
                                     without a reason
  scripts/check_sizes.py --root DIR  check another tree (the check's own test)

The reason is one comment line:
  - for a file, `// Long file: WHY` in the comment block at its top;
  - for a function, `// Long function: WHY` among the 8 lines above its opening brace (where its
    signature and doc comment are).
A function is a brace block that follows a parameter list `)` (with const, override, noexcept or
a trailing return type) at namespace or class level; blocks inside it, lambdas included, count
towards it. Comments, string and character literals (raw strings too) are blanked first, so
braces in them do not count.
"""
import pathlib
import re
import sys

MAX_FILE_LINES = 500
MAX_FUNCTION_LINES = 100
FOLDERS = ["libsysid/src", "apps", "python/src"]
SUFFIXES = {".cpp", ".hpp", ".h", ".c", ".inc"}
FILE_REASON = re.compile(r"//\s*Long file:\s*\S")
FUNCTION_REASON = re.compile(r"//\s*Long function:\s*\S")
CONTROL = re.compile(r"\b(if|for|while|switch|catch)\s*\([^;{}]*\)\s*$")
AFTER_PARAMETERS = re.compile(
    r"\)\s*(?:const|override|noexcept|final|mutable|->\s*[\w:<>,\s&*]+?)*\s*$")


def blank(text):
    """Comments and literals replaced by blanks of the same line count."""
    keep_lines = lambda m: "\n" * m.group(0).count("\n")
    text = re.sub(r'R"([^(\s]*)\(.*?\)\1"', lambda m: '""' + keep_lines(m), text, flags=re.S)
    text = re.sub(r"/\*.*?\*/", keep_lines, text, flags=re.S)
    text = re.sub(r"//[^\n]*", "", text)
    text = re.sub(r'"(?:\\.|[^"\\\n])*"', '""', text)
    return re.sub(r"'(?:\\.|[^'\\\n])*'", "''", text)


def long_functions(text):
    """(first line of the body, lines) of every function body longer than the limit."""
    code = blank(text)
    stack, found, line = [], [], 1
    for i, c in enumerate(code):
        if c == "\n":
            line += 1
        elif c == "{":
            before = code[max(0, i - 400):i].rstrip()
            is_function = bool(AFTER_PARAMETERS.search(before)) and not CONTROL.search(before)
            stack.append((is_function and not any(f for f, _ in stack), line))
        elif c == "}" and stack:
            outermost_function, start = stack.pop()
            if outermost_function and line - start + 1 > MAX_FUNCTION_LINES:
                found.append((start, line - start + 1))
    return found


def rooms(root):
    """(path, line, what, has_reason) for every file and function over its limit."""
    out = []
    for folder in FOLDERS:
        for path in sorted((root / folder).rglob("*")):
            if path.suffix not in SUFFIXES or not path.is_file():
                continue
            text = path.read_text(encoding="utf-8", errors="replace")
            lines = text.split("\n")
            rel = path.relative_to(root)
            if len(lines) - 1 > MAX_FILE_LINES:
                top = 0
                while top < len(lines) and lines[top].startswith("//"):
                    top += 1
                reason = any(FILE_REASON.search(l) for l in lines[:top])
                out.append((rel, 1, f"file of {len(lines) - 1} lines", reason))
            for start, count in long_functions(text):
                above = lines[max(0, start - 9):start]
                reason = any(FUNCTION_REASON.search(l) for l in above)
                out.append((rel, start, f"function of {count} lines", reason))
    return out


def main(argv):
    root = pathlib.Path(__file__).resolve().parent.parent
    if "--root" in argv:
        root = pathlib.Path(argv[argv.index("--root") + 1]).resolve()
    found = rooms(root)
    if "--list" in argv:
        for rel, line, what, reason in found:
            print(f"{rel}:{line}: {what}{'' if reason else ' (no reason given)'}")
        return 0
    bad = [r for r in found if not r[3]]
    for rel, line, what, _ in bad:
        limit = MAX_FILE_LINES if what.startswith("file") else MAX_FUNCTION_LINES
        kind = "file" if what.startswith("file") else "function"
        print(f"{rel}:{line}: {what}, over {limit}: split it, or say why in a "
              f"'// Long {kind}: WHY' line (scripts/check_sizes.py)")
    print(f"check_sizes: {len(found)} rooms over their limit, {len(bad)} without a reason")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
