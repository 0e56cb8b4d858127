#!/usr/bin/env python3
"""The module graph of libsysid: which module's files include which module's headers.

A module is a folder of libsysid/src/ together with its public header(s) in
libsysid/include/sysid/ (sysid/<module>.hpp or sysid/<module>_*.hpp; sysid/error.hpp, termination.hpp and serialize.hpp are core's).
Dependencies must run one way, down the layers below (docs/architecture.md): a file may include
headers of its own module and of modules in lower layers only. Any other include is reported
with the file and line, and the check fails: an include cycle between modules is always such
a violation.

  scripts/check_modules.py            check; exit 1 on a violation
  scripts/check_modules.py --graph    print the module graph as markdown (for the docs)
  scripts/check_modules.py --root DIR check another source tree (the check's own test)

The report module only formats what the pipeline computed (docs/architecture.md, "report"):
a call in libsysid/src/report/ to a function that reads, simulates, fits, trains or analyses
(REPORT_FORBIDDEN_CALL), or an include of such a module's header (REPORT_FORBIDDEN_INCLUDES), is
reported with file and line, and the check fails.

The check also reads docs/architecture.md: its layer line (the code block under "## Layers")
must list LAYERS in order, and its graph table must be the one --graph prints, so the
architecture doc cannot drift from the sources.
"""
import pathlib
import re
import sys

# Lowest first. Modules on one line share a layer and must not include each other.
LAYERS = [
    ["core"],
    ["numerics"],
    ["io"],
    ["signal"],
    ["motion"],
    ["model", "input"],
    ["simulate"],
    ["hysteresis"],
    ["identify"],
    ["delay"],
    ["dominance"],
    ["nn"],
    ["compare"],
    ["validate"],
    ["stage", "stack", "deploy"],
    ["control"],
    ["paper"],
    ["pipeline"],
    ["report"],
]
# What report/ may not call: the library's readers, simulators, fits, trainers and analyses
# (by their names' verbs), outside comments and string literals. RunGnuplot draws.
REPORT_FORBIDDEN_CALL = re.compile(
    r"\b((?:Read|Load|Parse|Simulate|Fit|Invert|Train|Identify|Tune|Estimate|Analyze|Rank|Refine"
    r"|Sweep|MotionRipple)\w*|(?:Track|Run|Compare|Validate)[A-Z]\w*)\s*\(")
REPORT_ALLOWED_CALLS = {"RunGnuplot"}
REPORT_FORBIDDEN_INCLUDES = {"sysid/simulate.hpp", "sysid/nn_irreducible.hpp", "sysid/delay.hpp",
                             "sysid/identify.hpp"}
HEADER_MODULE = {"error": "core", "termination": "core", "serialize": "core", "stage_facts": "paper"}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')


def module_of_header(name, modules):
    """sysid/<name>.hpp -> module, or None when unknown."""
    if name in HEADER_MODULE:
        return HEADER_MODULE[name]
    if name in modules:
        return name
    prefix = name.split("_")[0]
    return prefix if prefix in modules else None


def graph_table(edges, rank):
    """The module graph as markdown table lines, modules in layer order."""
    lines = ["| module | depends on |", "|---|---|"]
    for layer in LAYERS:
        for m in layer:
            deps = sorted({n for (a, n) in edges if a == m}, key=lambda n: (rank.get(n, 99), n))
            lines.append(f"| {m} | {', '.join(deps) or '—'} |")
    return lines


def doc_problems(doc, table, root):
    """Where docs/architecture.md's layer line or graph table differ from the sources."""
    if not doc.exists():
        return []
    where = doc.relative_to(root)
    text = doc.read_text(encoding="utf-8").splitlines()
    problems = []
    try:
        start = text.index("## Layers")
        fence = text.index("```", start)
        end = text.index("```", fence + 1)
    except ValueError:
        return [f"{where}: no '## Layers' section with the layer line in a code block"]
    line = " ".join(text[fence + 1:end])
    written = [[m.strip() for m in layer.split(",")] for layer in line.split("→")]
    if written != LAYERS:
        problems.append(
            f"{where}:{fence + 2}: the layer line reads {' → '.join(', '.join(l) for l in written)}; "
            f"the layers are {' → '.join(', '.join(l) for l in LAYERS)}")
    try:
        first = text.index(table[0])
    except ValueError:
        return problems + [f"{where}: no module graph table ('{table[0]}')"]
    for i, expected in enumerate(table):
        found = text[first + i] if first + i < len(text) else ""
        if found != expected:
            problems.append(f"{where}:{first + i + 1}: the graph table reads '{found}', "
                            f"the sources give '{expected}' (scripts/check_modules.py --graph)")
    after = first + len(table)
    if after < len(text) and text[after].startswith("|"):
        problems.append(f"{where}:{after + 1}: the graph table has a row no module has")
    return problems


def code_only(line):
    """`line` without string literals and // comments (block comments are not used in src/)."""
    line = re.sub(r'"(?:\\.|[^"\\])*"', '""', line)
    line = re.sub(r"'(?:\\.|[^'\\])*'", "''", line)
    return line.split("//", 1)[0]


def report_problems(src, root):
    """Calls and includes in report/ that would read, simulate or compute there."""
    problems = []
    for path in sorted((src / "report").rglob("*")):
        if path.suffix not in (".cpp", ".hpp"):
            continue
        for lineno, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            where = f"{path.relative_to(root)}:{lineno}"
            hit = INCLUDE.match(line)
            if hit and hit.group(1) in REPORT_FORBIDDEN_INCLUDES:
                problems.append(f"{where}: report/ includes {hit.group(1)}: the report formats what "
                                f"the pipeline computed (put the computation in pipeline/)")
                continue
            for call in REPORT_FORBIDDEN_CALL.finditer(code_only(line)):
                if call.group(1) not in REPORT_ALLOWED_CALLS:
                    problems.append(f"{where}: report/ calls {call.group(1)}: the report reads, "
                                    f"simulates and computes nothing (put it in pipeline/, its "
                                    f"result in PipelineResult)")
    return problems


def main():
    root = pathlib.Path(__file__).resolve().parent.parent
    if "--root" in sys.argv:
        root = pathlib.Path(sys.argv[sys.argv.index("--root") + 1]).resolve()
    src = root / "libsysid" / "src"
    public = root / "libsysid" / "include" / "sysid"
    rank = {m: i for i, layer in enumerate(LAYERS) for m in layer}
    modules = {p.name for p in src.iterdir() if p.is_dir() and any(p.iterdir())}
    problems = []
    for m in sorted(modules - rank.keys()):
        problems.append(f"libsysid/src/{m}/: module not placed in a layer (LAYERS in {__file__})")

    files = []  # (module, path)
    for m in sorted(modules):
        files += [(m, p) for p in sorted((src / m).rglob("*")) if p.suffix in (".cpp", ".hpp", ".inc")]
    for h in sorted(public.glob("*.hpp")):
        m = module_of_header(h.stem, modules)
        if m is None:
            problems.append(f"{h.relative_to(root)}: public header of no module")
            continue
        files.append((m, h))

    edges = {}
    for m, path in files:
        for lineno, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            hit = INCLUDE.match(line)
            if not hit:
                continue
            target = hit.group(1)
            head, _, rest = target.partition("/")
            if head == "sysid":
                n = module_of_header(pathlib.Path(rest).stem, modules)
            elif head in modules:
                n = head
            else:
                continue  # same-folder or test-support includes
            where = f"{path.relative_to(root)}:{lineno}"
            if n is None:
                problems.append(f"{where}: includes {target}, a header of no module")
                continue
            if n == m:
                continue
            edges.setdefault((m, n), where)
            if m in rank and n in rank and rank[n] >= rank[m]:
                problems.append(
                    f"{where}: module '{m}' includes {target} of module '{n}', which is "
                    f"{'in the same layer' if rank[n] == rank[m] else 'above it'}")

    if (src / "report").is_dir():
        problems += report_problems(src, root)

    table = graph_table(edges, rank)
    if "--graph" in sys.argv:
        print("\n".join(table))
    problems += doc_problems(root / "docs" / "architecture.md", table, root)
    for p in problems:
        print(p, file=sys.stderr)
    if problems:
        print(f"check_modules: {len(problems)} problem(s): module graph or its doc",
              file=sys.stderr)
        return 1
    if "--graph" not in sys.argv:
        print(f"check_modules: {len(modules)} modules, {len(edges)} dependencies, all one-way")
    return 0


if __name__ == "__main__":
    sys.exit(main())
